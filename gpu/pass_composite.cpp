#include "passes.h"
#include "shaders/shared/brume.h"

namespace brume::gpu {

Result<ComputePass> createCompositePass(const Device& device, VkPipelineLayout layout) {
    return createComputePass(device, layout, "composite.comp", "composite");
}

// One invocation per pixel.
void recordComposite(VkCommandBuffer cmd, const ComputePass& pass, const DescriptorBindings& b, glm::ivec2 size) {
    bindComputePass(cmd, pass, b);
    vkCmdDispatch(cmd, static_cast<uint32_t>(shd::brumeDivRoundUp(size.x, shd::SCREEN_GROUP_X)),
                  static_cast<uint32_t>(shd::brumeDivRoundUp(size.y, shd::SCREEN_GROUP_Y)), 1);
}

}  // namespace brume::gpu
