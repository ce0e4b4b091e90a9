// Pass-specific record code: what a pass of the table (frame_table.cpp) needs beyond binding its
// pipeline and dispatching by its rule, which the executor (frame_executor.cpp) does for all of
// them. The executor places the barriers (after each pass's start timestamp, see timing.h).
#pragma once

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
    shd::DebugViewParams debugParams{};
    glm::vec3 ambient{0.0f};    // geometry: sky radiance
    float cameraFar = 0.0f;     // geometry: sky view depth
    uint32_t vertexCount = 0;   // geometry
};

// Binds ctx.pipeline and the set and dispatches ctx.pass's rule.
void dispatchPass(const PassContext& ctx);

// Geometry (Record::Geometry): planes, boxes and spheres rasterized with a depth test into the
// sceneColor and sceneDepth targets, shaded like core/geometry.cpp shadeSurface with the fog's
// shadow and the shadow maps, not exact occlusion.
class GeometryPass {
public:
    static Result<GeometryPass> create(const Device& device, VkPipelineLayout layout);
    // Call whenever the screen images are recreated (also makes the pass's own depth buffer).
    Result<void> attach(const Device& device, const FrameResources& r);
    // Picks the fragment shader's variant for this frame (with the sampled fog shadows of
    // ellipsoids and cylinders or not: frame_table.h VariantKey::shapes), creating it on first use.
    Result<void> prepare(const Device& device, VkPipelineLayout layout, bool shapes);
    void record(const PassContext& ctx) const;

private:
    RenderPassOwner renderPass_;
    PipelineOwner pipeline_;
    PipelineOwner shapesPipeline_;  // geometry_shapes.frag, created on first use
    bool useShapes_ = false;
    GpuImage depthBuffer_;  // d32, depth test only
    FramebufferOwner framebuffer_;
};

// Temporal (Record::TemporalCopy): the dispatch, then the history's output copied over sourceImage
// and mediaExtinction (the dispatch reads their neighbours, so it cannot write them).
void recordTemporal(const PassContext& ctx);

// Debug view (Record::DebugView): the view and slice as push constants, then the dispatch.
void recordDebugView(const PassContext& ctx);

}  // namespace brume::gpu
