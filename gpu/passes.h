// The froxel passes, one file each (gpu/pass_*.cpp, shaders/*.comp|vert|frag), in execution order.
// Each records into a command buffer whose descriptor set already points at FrameResources; the
// caller places the barriers between them (after each pass's start timestamp, see timing.h).
#pragma once

#include <glm/glm.hpp>

#include "frame_resources.h"
#include "pipeline.h"
#include "shaders/shared/brume.h"

namespace brume::gpu {

// Geometry: planes, boxes and spheres rasterized with a depth test and shaded like
// core/geometry.cpp shadeSurface with the fog's shadow and the sun shadow map, not exact occlusion.
// in: frame, lights, lightClusters (light reach), vertices, shadowTransmittance, sunShadowMap, localShadowMaps. out: sceneColor (sky = ambient), sceneDepth (sky = camera far).
class GeometryPass {
public:
    static Result<GeometryPass> create(const Device& device, VkPipelineLayout layout);
    // Call whenever the screen targets are recreated.
    Result<void> attach(const Device& device, const FrameResources& r);
    void record(VkCommandBuffer cmd, const DescriptorBindings& b, const FrameResources& r, uint32_t vertexCount,
                glm::vec3 ambient, float cameraFar) const;

private:
    RenderPassOwner renderPass_;
    PipelineOwner pipeline_;
    FramebufferOwner framebuffer_;
};

// Voxelize. in: frame, volumes. out: mediaScatteringG, mediaExtinction, mediaEmission.
Result<ComputePass> createVoxelizePass(const Device& device, VkPipelineLayout layout);
// The variant that samples vdb grids; costs ~9x more on lavapipe, so only for scenes that have them.
Result<ComputePass> createVoxelizeVdbPass(const Device& device, VkPipelineLayout layout);
// The variants that also apply density textures (created on first use, for the same reason).
Result<ComputePass> createVoxelizeTexturePass(const Device& device, VkPipelineLayout layout, bool vdb);
void recordVoxelize(VkCommandBuffer cmd, const ComputePass& pass, const DescriptorBindings& b, glm::ivec3 dims);

// Shadow volume. in: frame, volumes, lights, lightClusters (light reach). out: shadowTransmittance (each shadowing light's fog
// transmittance on the reduced grid of shaders/shared/shadow_volume.h).
Result<ComputePass> createShadowVolumePass(const Device& device, VkPipelineLayout layout);
// The variant for scenes with vdb grids: also marches them into each light's vdb layer
// (shaders/shared/vdb_shadow.h) when frame.vdb.x asks.
Result<ComputePass> createShadowVolumeVdbPass(const Device& device, VkPipelineLayout layout);
void recordShadowVolume(VkCommandBuffer cmd, const ComputePass& pass, const DescriptorBindings& b, glm::ivec3 extent);

// Light. in: frame, lights, media*, shadowTransmittance, sunShadowMap, localShadowMaps. out: source, counters.
Result<ComputePass> createLightPass(const Device& device, VkPipelineLayout layout);
void recordLight(VkCommandBuffer cmd, const ComputePass& pass, const DescriptorBindings& b, glm::ivec3 dims);

// Temporal (between light and integrate). in: frame, previous frame, source, mediaExtinction,
// history[1 - writeIndex]. out: history[writeIndex], copied over source and mediaExtinction.
Result<ComputePass> createTemporalPass(const Device& device, VkPipelineLayout layout);
void recordTemporal(VkCommandBuffer cmd, const ComputePass& pass, const DescriptorBindings& b, const FrameResources& r,
                    int writeIndex);

// Integrate. in: frame, source, mediaExtinction. out: integratedScattering, integratedTransmittance.
Result<ComputePass> createIntegratePass(const Device& device, VkPipelineLayout layout);
void recordIntegrate(VkCommandBuffer cmd, const ComputePass& pass, const DescriptorBindings& b, glm::ivec3 dims);

// Composite. in: frame, lights, lightClusters (light reach), integrated*, sceneColor, sceneDepth. out: output.
Result<ComputePass> createCompositePass(const Device& device, VkPipelineLayout layout);
void recordComposite(VkCommandBuffer cmd, const ComputePass& pass, const DescriptorBindings& b, glm::ivec2 size);

// Debug view (only when RenderRequest::debugView asks). in: frame, mediaExtinction | source |
// integratedTransmittance. out: output, overwritten with the slice's display colours.
Result<ComputePass> createDebugViewPass(const Device& device, VkPipelineLayout layout);
void recordDebugView(VkCommandBuffer cmd, const ComputePass& pass, const DescriptorBindings& b, glm::ivec2 size,
                     const shd::DebugViewParams& params);

}  // namespace brume::gpu
