#include "passes.h"
#include "shaders/shared/brume.h"

namespace brume::gpu {

Result<ComputePass> createDebugViewPass(const Device& device, VkPipelineLayout layout) {
    return createComputePass(device, layout, "debug_view.comp", "debug view");
}

// One invocation per pixel; the view and slice travel as push constants (the layout's one range).
void recordDebugView(VkCommandBuffer cmd, const ComputePass& pass, const DescriptorBindings& b, glm::ivec2 size,
                     const shd::DebugViewParams& params) {
    bindComputePass(cmd, pass, b);
    vkCmdPushConstants(cmd, b.pipelineLayout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(params), &params);
    vkCmdDispatch(cmd, static_cast<uint32_t>(shd::brumeDivRoundUp(size.x, shd::SCREEN_GROUP_X)),
                  static_cast<uint32_t>(shd::brumeDivRoundUp(size.y, shd::SCREEN_GROUP_Y)), 1);
}

}  // namespace brume::gpu
