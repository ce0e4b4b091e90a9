// The two CPU renderers. Both take a Scene and return linear radiance.
//   renderReference: per-pixel ray marching, independent of froxels: the ground truth.
//   renderFroxelCpu: the froxel algorithm (voxelize, light, integrate, composite): the GPU's oracle.
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "compile.h"
#include "image.h"
#include "quality.h"
#include "scene.h"
#include "temporal.h"

namespace brume {

// fraction in [0, 1]; called from worker threads (must be thread-safe), at most ~100 times.
using ProgressFn = std::function<void(float fraction)>;

struct RenderRequest {
    int width = 640;
    int height = 360;
    Quality quality = Quality::High;
    int frames = 1;        // froxel renderers: frames rendered (static camera); the last is returned
    HistoryMode history = HistoryMode::Restart;  // froxel renderers: keep the previous call's history?
    int threads = 0;       // 0 = every core
    int shadowReduction = 0;  // fog transmittance volume reduction (core/shadows.h); 0 = the quality's
    bool lightCulling = true;  // froxel renderers: light pass loops over its cluster's lights (core/clusters.h)
    // Froxel renderers: shd::DEBUG_VIEW_* other than FINAL replaces the image by one depth slice of a
    // volume (shaders/shared/debug_view.h, core/debug_view.h); debugSlice is clamped to the grid.
    int debugView = shd::DEBUG_VIEW_FINAL;
    int debugSlice = 0;
    bool vdbShadows = true;    // froxel renderers: vdb volumes in the fog shadows (core/vdb_shadow.h)
    bool vdbCulling = true;    // froxel renderers: skip grid walks in empty occupancy cells (core/vdb_shadow.h)
    // GPU renderer: keep the previous frame's surfaces (the geometry and distant fog passes' output)
    // when everything those passes read equals what they read then, as at rest in the editor, which
    // sets it. Off by default, so that `brume bench` and `brume tradeoff` time whole frames.
    bool reuseSurfaces = false;
    // GPU renderer: where a pass has no pipeline yet for this frame's keys but has its fallback's, use
    // that one instead of compiling (lavapipe: ~250 ms to over 1 s on that frame). The fallbacks give
    // the same image, somewhat slower: no volume culled (a volume that enters or leaves the view's reach
    // mid-drag; a culled volume's terms are exactly 0), and the geometry pass's surface lights read from
    // the light reach list (a light that does; SPEC_SURFACE_LIGHTS -1). The editor sets it and makes
    // the fallbacks while the view rests (GpuRenderer::preparePipelines).
    bool pipelineFallbacks = false;
    ProgressFn progress;   // optional
    // Reference renderer: once set, rows not yet started are skipped and the image is incomplete
    // (the caller, which set it, throws the image away). Lets the editor cancel a long reference.
    const std::atomic<bool>* cancel = nullptr;
};

// Request from the scene's own render block.
RenderRequest requestFromScene(const Scene& scene);

Image renderReference(const Scene& scene, const RenderRequest& request);

// Intermediate volumes of the froxel renderer, kept for GPU-vs-CPU comparisons and debug views.
// Each volume is dims.x * dims.y * dims.z entries, index = (z * dims.y + y) * dims.x + x.
struct FroxelVolumes {
    glm::ivec3 dims{0};
    shd::FrameUniforms frame{};
    std::vector<glm::vec4> mediaScatteringG;         // voxelize: rgb sigma_s [1/m], a: phase g
    std::vector<glm::vec4> mediaExtinction;          // voxelize: rgb sigma_t [1/m], a: unused
    std::vector<glm::vec4> mediaEmission;            // voxelize: rgb emitted radiance per meter, a: unused
    std::vector<glm::vec4> source;                   // light: rgb source S = in-scattered + emitted [radiance/m]
    std::vector<glm::vec4> integratedScattering;     // integrate: rgb scattering, camera to the slice's far side
    std::vector<glm::vec4> integratedTransmittance;  // integrate: rgb transmittance, likewise
    size_t litFroxels = 0;      // froxels with sigma_t > 0 (lit)
    size_t skippedFroxels = 0;  // froxels with sigma_t = 0 (lighting skipped)
    size_t overfullClusters = 0;  // light clusters over shd::CLUSTER_MAX_LIGHTS (unculled there)
};

struct FroxelResult {
    Image image;
    FroxelVolumes volumes;
};

// request.frames frames from a fresh history (request.history is moot); progress covers the last.
FroxelResult renderFroxelCpu(const Scene& scene, const RenderRequest& request);

// The CPU froxel renderer with a history kept across render calls (the GPU renderer's temporal
// oracle): with request.history = Continue, each call continues the sequence of the previous one.
class FroxelCpuRenderer {
public:
    FroxelResult render(const Scene& scene, const RenderRequest& request);
    const CpuHistory& history() const { return history_; }

private:
    CpuHistory history_;
};

}  // namespace brume
