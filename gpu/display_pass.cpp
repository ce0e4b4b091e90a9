#include "display_pass.h"

#include <array>

#include "shaders/shared/brume.h"
#include "vk_check.h"

namespace brume::gpu {

Result<DisplayPass> DisplayPass::create(const Device& device) {
    DisplayPass p;
    const std::array<VkDescriptorSetLayoutBinding, 2> bindings{{
        {0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},   // the renderer's output
        {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},  // the window's pixels
    }};
    Result<DescriptorBindings> b = createDescriptorSet(device, bindings, sizeof(shd::DisplayParams), "display");
    if (!b) return b.error();
    p.bindings_ = std::move(b.value());
    // Two builds: lavapipe would run the bilinear filter behind an untaken branch for every pixel of a
    // frame at rest (docs/performance.md, "display").
    Result<ComputePass> exact = createComputePass(device, p.bindings_.pipelineLayout.get(), "display.comp");
    if (!exact) return exact.error();
    p.exact_ = std::move(exact.value());
    Result<ComputePass> scaled = createComputePass(device, p.bindings_.pipelineLayout.get(), "display_scaled.comp");
    if (!scaled) return scaled.error();
    p.scaled_ = std::move(scaled.value());
    return p;
}

void DisplayPass::record(const Device& device, VkCommandBuffer cmd, const OutputImage& source, VkBuffer window,
                         const shd::DisplayParams& params) const {
    VkDescriptorImageInfo image{VK_NULL_HANDLE, source.view, VK_IMAGE_LAYOUT_GENERAL};
    VkDescriptorBufferInfo buffer{window, 0, VK_WHOLE_SIZE};
    std::array<VkWriteDescriptorSet, 2> writes{};
    for (size_t i = 0; i < writes.size(); ++i) {
        writes[i] = vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
        writes[i].dstSet = bindings_.set;
        writes[i].dstBinding = static_cast<uint32_t>(i);
        writes[i].descriptorCount = 1;
    }
    writes[0].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    writes[0].pImageInfo = &image;
    writes[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[1].pBufferInfo = &buffer;
    vkUpdateDescriptorSets(device.vk(), static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);

    device.beginLabel(cmd, "display");
    // The renderer's last pass (composite or debug view) wrote the image in an earlier submission.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    bindComputePass(cmd, params.sourceSize == params.viewSize ? exact_ : scaled_, bindings_);
    vkCmdPushConstants(cmd, bindings_.pipelineLayout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(params), &params);
    vkCmdDispatch(cmd, static_cast<uint32_t>(shd::brumeDivRoundUp(params.windowSize.x, shd::SCREEN_GROUP_X)),
                  static_cast<uint32_t>(shd::brumeDivRoundUp(params.windowSize.y, shd::SCREEN_GROUP_Y)), 1);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_TRANSFER_READ_BIT);
    device.endLabel(cmd);
}

}  // namespace brume::gpu
