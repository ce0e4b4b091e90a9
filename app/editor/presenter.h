// The editor window's Vulkan side, on the renderer's device (gpu::Device created with a
// PresentTarget for the window: one instance, one device choice, one queue that renders and
// presents). Each frame: the display pass (gpu/display_pass.h) turns the renderer's output image
// into the window's 8-bit pixels on the device, a copy puts them in the swapchain image (a coarse
// frame: its pixels at the source's size, blitted up; present_path.h), and Dear ImGui draws over
// them in a render pass that loads them. The rendered image never visits the CPU
// (a screenshot reads the window image back).
//
// One frame in flight (one fence): the renderer waits for its own frame anyway, so a second
// would overlap only the UI's few milliseconds with the next frame's CPU work.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/result.h"
#include "gpu/gpu_renderer.h"
#include "gpu/timing.h"

struct GLFWwindow;
struct ImDrawData;

namespace brume::editor {

// 8-bit RGBA, row-major from the top-left pixel.
struct Rgba8 {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> pixels;
};

// What gpu::Device needs to present to `window`: GLFW's instance extensions and its surface.
Result<gpu::PresentTarget> windowPresentTarget(GLFWwindow* window);

class Presenter {
public:
    // `device` must have been created with windowPresentTarget(window), and outlive the presenter.
    static Result<std::unique_ptr<Presenter>> create(GLFWwindow* window, const gpu::Device& device);
    ~Presenter();
    Presenter(const Presenter&) = delete;
    Presenter& operator=(const Presenter&) = delete;

    // Draws `source` (the renderer's output; no image: nothing rendered yet) scaled to `viewSize`
    // at the window's top-left (the rest is cleared), `ui` over it, and presents. With `capture`,
    // also returns the window image as presented. `generation` names the source's content (the
    // editor's render count): while it, the source and the sizes stay the same, the display pass's
    // last output is reused and only copied (a frame that redraws the UI alone).
    Result<void> present(const gpu::OutputImage& source, glm::ivec2 viewSize, uint64_t generation, ImDrawData* ui,
                         Rgba8* capture = nullptr);
    // Waits until the last present()'s commands have finished: call before the renderer records
    // again, since they read its output image (which a new size also destroys).
    Result<void> waitForFrame();
    // Call from the UI before ImGui::NewFrame.
    void newFrame();
    // The last present()'s parts (brume-editor --bench): the device's passes (display, copy, ui) from
    // timestamps, waiting for that frame if needed, and the host's (acquire, record, submit, queue
    // present) from the wall clock; names end in "(gpu)" or "(cpu)".
    // With `on`, present() also waits for the device between submitting and presenting, so that
    // the device's work and the window system's copy are timed apart (the software swapchain waits
    // for the frame in vkQueuePresentKHR anyway).
    void measureParts(bool on);
    Result<std::vector<gpu::PassTiming>> lastParts();
    GLFWwindow* window() const;

    struct State;

private:
    explicit Presenter(std::unique_ptr<State> s);
    std::unique_ptr<State> s_;
};

}  // namespace brume::editor
