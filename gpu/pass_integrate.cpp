#include "passes.h"
#include "shaders/shared/brume.h"

namespace brume::gpu {

Result<ComputePass> createIntegratePass(const Device& device, VkPipelineLayout layout) {
    return createComputePass(device, layout, "integrate.comp", "integrate");
}

// One invocation per froxel column: slices depend on the one in front, so they run serially.
void recordIntegrate(VkCommandBuffer cmd, const ComputePass& pass, const DescriptorBindings& b, glm::ivec3 dims) {
    bindComputePass(cmd, pass, b);
    vkCmdDispatch(cmd, static_cast<uint32_t>(shd::brumeDivRoundUp(dims.x, shd::INTEGRATE_GROUP_X)),
                  static_cast<uint32_t>(shd::brumeDivRoundUp(dims.y, shd::INTEGRATE_GROUP_Y)), 1);
}

}  // namespace brume::gpu
