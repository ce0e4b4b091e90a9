#include "passes.h"
#include "shaders/shared/brume.h"

namespace brume::gpu {

Result<ComputePass> createVoxelizePass(const Device& device, VkPipelineLayout layout) {
    return createComputePass(device, layout, "voxelize.comp", "voxelize");
}

Result<ComputePass> createVoxelizeVdbPass(const Device& device, VkPipelineLayout layout) {
    return createComputePass(device, layout, "voxelize_vdb.comp", "voxelize (vdb)");
}

Result<ComputePass> createVoxelizeTexturePass(const Device& device, VkPipelineLayout layout, bool vdb) {
    return vdb ? createComputePass(device, layout, "voxelize_vdb_texture.comp", "voxelize (vdb, texture)")
               : createComputePass(device, layout, "voxelize_texture.comp", "voxelize (texture)");
}

// One invocation per froxel.
void recordVoxelize(VkCommandBuffer cmd, const ComputePass& pass, const DescriptorBindings& b, glm::ivec3 dims) {
    bindComputePass(cmd, pass, b);
    vkCmdDispatch(cmd, static_cast<uint32_t>(shd::brumeDivRoundUp(dims.x, shd::FROXEL_GROUP_X)),
                  static_cast<uint32_t>(shd::brumeDivRoundUp(dims.y, shd::FROXEL_GROUP_Y)),
                  static_cast<uint32_t>(shd::brumeDivRoundUp(dims.z, shd::FROXEL_GROUP_Z)));
}

}  // namespace brume::gpu
