// Pass-specific record code: what a pass of the table (frame_table.cpp) needs beyond binding its
// pipeline and dispatching by its rule, which the executor (frame_executor.cpp) does for all of
// them. The executor places the barriers (after each pass's start timestamp, see timing.h).
#pragma once

#include <map>
#include <tuple>
#include <vector>

#include <glm/glm.hpp>

#include "frame_resources.h"
#include "pipeline.h"
#include "shaders/shared/brume.h"

namespace brume::gpu {

// What one pass's recording sees.
struct PassContext {
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    const PassDecl* pass = nullptr;
    const DescriptorBindings* bindings = nullptr;
    const FrameResources* res = nullptr;
    const ComputePass* pipeline = nullptr;  // compute passes: this frame's variant
    int historyWriteIndex = 0;              // the history side written this frame
    const VariantKey* variant = nullptr;     // this frame's shader variants
    bool readBackVolumes = false;            // the froxel volumes are read back after the frame
    bool poisonIntegrated = false;           // GpuOptions::poisonIntegrated (tests)
    bool poisonSource = false;               // GpuOptions::poisonSource (tests)
    shd::DebugViewParams debugParams{};
    const std::vector<shd::GlowParams>* glow = nullptr;  // glow: one dispatch each
    glm::vec3 ambient{0.0f};    // geometry: sky radiance
    float cameraFar = 0.0f;     // geometry: sky view depth
    uint32_t triangleVertices = 0;  // geometry: GeometryMesh::triangleVertices
    uint32_t sphereVertices = 0;    // geometry: GeometryMesh::sphereVertices
};

// Binds ctx.pipeline and the set and dispatches ctx.pass's rule.
void dispatchPass(const PassContext& ctx);

// Pushes region as the pass's shd::FroxelRegionParams, loW in lo.w (the shadow volume's light, the
// integrate and column ends passes' first entry stored in every column), hiW in hi.w (their last one).
void pushRegion(const PassContext& ctx, const FroxelRegion& region, int loW = 0, int hiW = 0);

// Shadow volume (Record::ShadowCells): its cell region pushed, then the dispatch over its cells.
void recordShadowCells(const PassContext& ctx);

// Composite (Record::Composite): when the pixels that can read fog (FrameResources::compositeLo,
// compositeHi) are not the whole screen, sceneColor copied over outputImage (the others' result: no
// fog leaves the background as it is); then those pixels pushed and dispatched.
void recordComposite(const PassContext& ctx);

// Voxelize (Record::ClearMedia): the images it writes cleared to 0 when the media region is not the
// whole grid, then the dispatch over the region.
void recordClearMedia(const PassContext& ctx);

// Geometry (Record::Geometry): planes, boxes and spheres rasterized with a depth test into the
// sceneColor and sceneDepth targets, shaded like core/geometry.cpp shadeSurface with the fog's
// shadow and the shadow maps, not exact occlusion.
class GeometryPass {
public:
    static Result<GeometryPass> create(const Device& device, VkPipelineLayout layout);
    // Selects (creating on first use) the pipelines specialized for key (pipeline.h SpecKey), with the
    // fragment shader's variant with the sampled fog shadows of ellipsoids and cylinders or not
    // (frame_table.h VariantKey::shapes); those of the sphere proxies too when `spheres`.
    Result<void> usePipeline(const Device& device, VkPipelineLayout layout, const SpecKey& key, bool shapes,
                             bool spheres);
    // Adds to `batch` the creation of the shading pipelines usePipeline with these arguments would
    // create (pipeline.h PipelineBatch); run it before the next usePipeline or request.
    void request(const Device& device, VkPipelineLayout layout, const SpecKey& key, bool shapes, bool spheres,
                 PipelineBatch& batch);
    // Whether usePipeline with these arguments would create nothing (its pipelines are made).
    bool has(const SpecKey& key, bool shapes, bool spheres) const;
    // Call whenever the screen images are recreated (also makes the pass's own depth buffer).
    Result<void> attach(const Device& device, const FrameResources& r);
    void record(const PassContext& ctx) const;

private:
    RenderPassOwner renderPass_;
    // Shading pipelines by specialization key (the constants the geometry shaders read: constantsReadBy),
    // shapes variant and sphere proxies or triangles.
    std::map<std::tuple<SpecKey, bool, bool>, PipelineOwner> pipelines_;
    VkPipeline pipeline_ = VK_NULL_HANDLE;        // the triangles' one usePipeline chose
    VkPipeline spherePipeline_ = VK_NULL_HANDLE;  // the sphere proxies' one (spheres only)
    PipelineOwner depthPipeline_;        // the depth pre-pass of triangles: vertex shader only
    PipelineOwner sphereDepthPipeline_;  // that of sphere proxies: the ray cast's depth (made on first use)
    GpuImage depthBuffer_;  // d32, depth test only
    FramebufferOwner framebuffer_;
};

// Temporal (Record::TemporalCopy): the history side it writes cleared to 0 when it may hold values
// outside this frame's temporal region (FrameResources::clearHistoryOut), then, in motion, the
// dispatch over the region. The later passes read the resolved values from the history's output.
void recordTemporal(const PassContext& ctx);

// Integrate (Record::Integrate): the temporal region and integrateColumns pushed with the dispatch
// over those columns (Dispatch::IntegrateColumns). The region's columns integrate; the stored entries in front of it and in the
// other columns get what empty froxels integrate to (scattering 0, transmittance 1) from the pass
// itself, not from a clear of both volumes over the whole grid (shaders/integrate.comp).
void recordIntegrate(const PassContext& ctx);

// The columns [xy, zw) whose integrated entries a reader looks up this frame: every column for the
// read-back volumes, the debug views and a composite over every pixel (distant fog); else the
// temporal region's with a column of margin (the composite) and those around each glow's rectangle.
// Empty (all 0) when nothing is looked up.
glm::ivec4 integrateColumns(const PassContext& ctx);

// The integrated entries stored in every column (pushed as lo.w .. hi.w to integrate and column ends): all
// of them for the read-back volumes and the debug views, else the span of the glows' entries (empty:
// first > last).
glm::ivec2 storedEverywhere(const PassContext& ctx);

// Column ends (Record::ColumnEnds): storedEverywhere pushed, then the dispatch over the froxel columns
// (each column's walk end: shaders/column_entries.glsl).
void recordColumnEnds(const PassContext& ctx);

// Debug view (Record::DebugView): the view and slice as push constants, then the dispatch.
void recordDebugView(const PassContext& ctx);

// Glow (Record::Glow): per glowing light in order, its rectangle and index as push constants, a
// dispatch over the rectangle, and a barrier before the next (the rectangles may overlap).
void recordGlow(const PassContext& ctx);

// The glow pass's dispatches for the lights the light reach lists as glowing (core/light_reach.h),
// in that order, leaving out those whose ball no pixel's ray meets (shd::lightGlowScreenRect).
std::vector<shd::GlowParams> glowDispatches(const std::vector<shd::LightData>& lights, const shd::FrameUniforms& frame,
                                            const std::vector<int>& glowLights);

}  // namespace brume::gpu
