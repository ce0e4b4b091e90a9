#include "passes.h"
#include "shaders/shared/brume.h"

namespace brume::gpu {

Result<ComputePass> createShadowVolumePass(const Device& device, VkPipelineLayout layout) {
    return createComputePass(device, layout, "shadow_volume.comp", "shadow volume");
}

Result<ComputePass> createShadowVolumeVdbPass(const Device& device, VkPipelineLayout layout) {
    return createComputePass(device, layout, "shadow_volume_vdb.comp", "shadow volume (vdb)");
}

// One invocation per cell and light (extent = cells x cells x cells * lights).
void recordShadowVolume(VkCommandBuffer cmd, const ComputePass& pass, const DescriptorBindings& b, glm::ivec3 extent) {
    bindComputePass(cmd, pass, b);
    vkCmdDispatch(cmd, static_cast<uint32_t>(shd::brumeDivRoundUp(extent.x, shd::FROXEL_GROUP_X)),
                  static_cast<uint32_t>(shd::brumeDivRoundUp(extent.y, shd::FROXEL_GROUP_Y)),
                  static_cast<uint32_t>(shd::brumeDivRoundUp(extent.z, shd::FROXEL_GROUP_Z)));
}

}  // namespace brume::gpu
