// `brume render`: options, their checks, and the dispatch to a renderer.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <CLI/CLI.hpp>

#include "command.h"
#include "core/render.h"
#include "core/result.h"

namespace brume::app {

// Add a renderer here and in renderScene/rendererName.
enum class RendererKind { Gpu, FroxelCpu, Reference };

const char* rendererName(RendererKind kind);

// What a render produced besides the image, for --stats and `brume bench`.
struct PassTime {
    std::string name;
    double gpuMs;
};
struct RenderStats {
    std::string device;            // GPU renderer: the Vulkan device's name
    std::vector<PassTime> passes;  // GPU renderer: per-pass GPU milliseconds
    double wallMs = 0.0;           // wall clock of the whole render
    glm::ivec3 froxelDims{0};      // froxel renderers
    size_t litFroxels = 0;
    size_t skippedFroxels = 0;
    size_t overfullClusters = 0;   // light clusters over shd::CLUSTER_MAX_LIGHTS (core/clusters.h)
};

struct RenderOutput {
    Image image;
    RenderStats stats;
};

// A renderer's failure: `userCanFix` = it could not start (no Vulkan device, unknown device name) or
// the scene asks for more than the device can do (Error::badInput): exit 2; otherwise it failed
// while rendering (exit 1).
struct RenderFailure {
    bool userCanFix;
    std::string message;
};

// The one place that knows how to run each renderer. A session keeps what is expensive to create
// (the Vulkan device and pipelines) across renders, as `brume bench` needs.
class RenderSession {
public:
    RenderSession(RendererKind kind, const std::string& device);
    ~RenderSession();
    RenderSession(const RenderSession&) = delete;
    RenderSession& operator=(const RenderSession&) = delete;

    // Set when the renderer could not start (then render() returns it again).
    const std::optional<RenderFailure>& startFailure() const { return startFailure_; }
    std::variant<RenderOutput, RenderFailure> render(const Scene& scene, const RenderRequest& request);

private:
    RendererKind kind_;
    std::optional<RenderFailure> startFailure_;
    struct Gpu;
    std::unique_ptr<Gpu> gpu_;
    FroxelCpuRenderer cpu_;  // keeps the temporal history across render calls, as the GPU renderer does
};

// Writes --stats JSON atomically.
// Prints on stderr that some light clusters were over-full (nothing when none were).
void printClusterWarning(const std::string& scenePath, const RenderStats& stats);

Result<void> writeStatsJson(const std::string& path, RendererKind kind, const RenderRequest& request,
                            const RenderStats& stats);

struct RenderOptions {
    std::string scenePath;
    std::string outputPath;
    int width = 0;  // only read when the option was given (the scene's render block otherwise)
    int height = 0;
    std::string quality;
    int frames = 0;
    float orbit = 0.0f;  // --orbit DEGREES_PER_FRAME
    float time = 0.0f;   // --time SECONDS: scene time of the written frame
    float fps = 24.0f;   // --fps: frame rate of --frames (scene time between frames = 1 / fps)
    float exposure = 0.0f;
    int threads = 0;
    int vdbMemoryMb = 0;
    bool reference = false;
    bool cpu = false;
    std::string device;     // --device, GPU renderer
    std::string statsPath;  // --stats
    std::string debugView;  // --debug-view
    int debugSlice = 0;     // --debug-slice
    std::string sequence;   // --sequence A-B: frames A..B at --fps, written to -o with #### = the frame
    bool overwrite = false; // --overwrite: render sequence frames already on disk again
    // Set by addRenderCommand, to tell given options from scene defaults.
    CLI::Option* widthOption = nullptr;
    CLI::Option* heightOption = nullptr;
    CLI::Option* qualityOption = nullptr;
    CLI::Option* framesOption = nullptr;
    CLI::Option* timeOption = nullptr;
    CLI::Option* orbitOption = nullptr;
    CLI::Option* statsOption = nullptr;
};

CLI::App* addRenderCommand(CLI::App& app, RenderOptions& options);
CommandResult runRender(const RenderOptions& options);

}  // namespace brume::app
