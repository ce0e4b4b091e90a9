// The editor window's Vulkan side: its own instance, device and swapchain (a second device next to
// the renderer's: GpuRenderer renders into an Image read back to the CPU, and each frame the
// presenter copies those pixels into the swapchain image, then draws Dear ImGui over them).
// On lavapipe both devices are the CPU, so the copy is cheap next to the froxel passes; sharing
// one VkDevice and sampling the renderer's output directly is the next step for real GPUs.
//
// One frame in flight (one fence): simple, and the renderer already waits for its own frame.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/result.h"

struct GLFWwindow;
struct ImDrawData;

namespace brume::editor {

// 8-bit RGBA, row-major from the top-left pixel.
struct Rgba8 {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> pixels;
};

class Presenter {
public:
    static Result<std::unique_ptr<Presenter>> create(GLFWwindow* window, bool validation);
    ~Presenter();
    Presenter(const Presenter&) = delete;
    Presenter& operator=(const Presenter&) = delete;

    // Copies `viewport` to the top-left of the window image (the rest is cleared), draws `ui`
    // over it and presents. With `capture`, also returns the window image as presented.
    Result<void> present(const Rgba8& viewport, ImDrawData* ui, Rgba8* capture = nullptr);
    // Call from the UI before ImGui::NewFrame.
    void newFrame();
    std::vector<std::string> validationMessages() const;
    GLFWwindow* window() const;

    struct State;

private:
    explicit Presenter(std::unique_ptr<State> s);
    std::unique_ptr<State> s_;
};

}  // namespace brume::editor
