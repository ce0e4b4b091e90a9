// The GPU froxel renderer (Vulkan compute + a raster pass for the preview geometry): the same
// five passes as core/froxel_renderer.cpp (renderFroxelCpu, its oracle), evaluated with the same
// shaders/shared/ functions on the same compiled scene and frame constants.
//
//   auto r = GpuRenderer::create({});            // once: device, pipelines
//   auto out = r.value()->render(scene, request); // many times: resources follow size changes only
#pragma once

#include <memory>
#include <string>
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

    std::string deviceName() const;
    bool validationEnabled() const;
    // Validation warnings and errors since create() (empty when validation is off).
    std::vector<std::string> validationMessages() const;

private:
    struct State;
    explicit GpuRenderer(std::unique_ptr<State> state);
    std::unique_ptr<State> s_;
};

}  // namespace brume::gpu
