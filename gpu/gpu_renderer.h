// The GPU froxel renderer (Vulkan compute + a raster pass for the preview geometry): the same
// five passes as core/froxel_renderer.cpp (renderFroxelCpu, its oracle), evaluated with the same
// shaders/shared/ functions on the same compiled scene and frame constants.
//
//   auto r = GpuRenderer::create({});            // once: device, pipelines
//   auto out = r.value()->render(scene, request); // many times: resources follow size changes only
#pragma once

#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/render.h"
#include "device.h"
#include "timing.h"

namespace brume::gpu {

struct GpuRender {
    Image image;
    FroxelVolumes volumes;           // filled only when render() is asked to read them back
    std::vector<PassTiming> passes;  // geometry, voxelize, light, temporal, integrate, composite, readback
    double wallMs = 0.0;             // wall clock from submit to completion (covers every pass)
    glm::ivec3 dims{0};              // froxel grid
    size_t litFroxels = 0;           // froxels with sigma_t > 0
    size_t skippedFroxels = 0;       // froxels with sigma_t = 0 (lighting skipped)
    size_t overfullClusters = 0;     // light clusters over shd::CLUSTER_MAX_LIGHTS (unculled there)
    // This call allocated froxel volumes or screen images (a first render, or a size seen neither
    // last nor parked: gpu/renderer_state.h); fresh memory costs its first touch in the passes.
    bool allocated = false;
    // This call created shader pipelines (a first frame, or specialization keys not seen before:
    // lavapipe takes 10-250 ms each), so its time is not what such a frame costs.
    bool compiled = false;
};

// The last frame's output image on the device (after renderOnDevice): rgba32f, in
// VK_IMAGE_LAYOUT_GENERAL, last written by a compute shader of an earlier, finished submission on
// device().queue(). Valid until the next render.
struct OutputImage {
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    glm::ivec2 size{0};
    bool displayValues = false;  // a debug view: display colours already (no tone map)
};

class GpuRenderer {
public:
    static Result<std::unique_ptr<GpuRenderer>> create(const GpuOptions& options);
    ~GpuRenderer();
    GpuRenderer(const GpuRenderer&) = delete;
    GpuRenderer& operator=(const GpuRenderer&) = delete;

    // Renders request.frames frames (temporal accumulation; the history is kept across calls, see
    // RenderRequest::history) and returns the last; wallMs and passes are the last frame's.
    // request.threads is ignored.
    Result<GpuRender> render(const Scene& scene, const RenderRequest& request, bool readBackVolumes = false);
    // The same, but the image stays on the device (GpuRender::image is empty): for the editor's
    // window, which draws outputImage() on device() (gpu/display_pass.h).
    Result<GpuRender> renderOnDevice(const Scene& scene, const RenderRequest& request);
    // Creates now the pipelines a render of (scene, request) would create (for its temporal pass in
    // motion and at rest), and with RenderRequest::pipelineFallbacks the fallbacks it may take where a
    // later frame's are missing, without rendering: the editor calls it for its next coarse frame while
    // the view rests, so that the frames of a drag do not compile (lavapipe: 10-250 ms a pipeline).
    // Whether any was missing.
    Result<bool> preparePipelines(const Scene& scene, const RenderRequest& request);
    // The same for several renders (the editor's next coarse frame and its frames at rest), in one
    // batch: the pipelines they lack compile together, one thread per core.
    Result<bool> preparePipelines(std::span<const std::pair<Scene, RenderRequest>> renders);
    // Whether a render of (scene, request) would find every pipeline it needs made, with the
    // fallbacks RenderRequest::pipelineFallbacks lets it take (for its temporal pass in motion and at
    // rest): a render that would compile (10-250 ms a pipeline on lavapipe) answers false. Compiles
    // nothing. The editor asks it before it renders stand-ins for a volume hidden or deleted
    // (app/editor/view.h withStandIns).
    Result<bool> hasPipelines(const Scene& scene, const RenderRequest& request) const;
    OutputImage outputImage() const;
    const Device& device() const;

    std::string deviceName() const;
    bool validationEnabled() const;
    // Validation warnings and errors since create() (empty when validation is off).
    std::vector<std::string> validationMessages() const;

private:
    Result<GpuRender> renderFrames(const Scene& scene, const RenderRequest& request, bool readBackVolumes,
                                   bool readBackImage);
    struct State;
    explicit GpuRenderer(std::unique_ptr<State> state);
    std::unique_ptr<State> s_;
};

}  // namespace brume::gpu
