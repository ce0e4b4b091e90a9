// Temporal pass (shaders/temporal.comp; rule in shaders/shared/temporal.h). in: frame, previous
// frame, source, mediaExtinction, history *_IN. out: history *_OUT, then copied into source and
// mediaExtinction for the integrate pass.
#include <initializer_list>
#include <utility>
#include <vector>

#include "passes.h"
#include "shaders/shared/brume.h"
#include "vk_check.h"

namespace brume::gpu {

Result<ComputePass> createTemporalPass(const Device& device, VkPipelineLayout layout) {
    return createComputePass(device, layout, "temporal.comp", "temporal");
}

namespace {

void relayout(VkCommandBuffer cmd, std::initializer_list<std::pair<VkImage, std::pair<VkImageLayout, VkImageLayout>>> images,
              VkPipelineStageFlags srcStage, VkAccessFlags srcAccess, VkPipelineStageFlags dstStage,
              VkAccessFlags dstAccess) {
    std::vector<VkImageMemoryBarrier> barriers;
    for (const auto& [image, layouts] : images) {
        VkImageMemoryBarrier b = vkStruct<VkImageMemoryBarrier>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER);
        b.srcAccessMask = srcAccess;
        b.dstAccessMask = dstAccess;
        b.oldLayout = layouts.first;
        b.newLayout = layouts.second;
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = image;
        b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        barriers.push_back(b);
    }
    vkCmdPipelineBarrier(cmd, srcStage, dstStage, 0, 0, nullptr, 0, nullptr, static_cast<uint32_t>(barriers.size()),
                         barriers.data());
}

}  // namespace

// One invocation per froxel, then the resolved pair replaces this frame's source and extinction
// (copied in transfer layouts, then every image is back in GENERAL for the passes after).
void recordTemporal(VkCommandBuffer cmd, const ComputePass& pass, const DescriptorBindings& b, const FrameResources& r,
                    int writeIndex) {
    const glm::ivec3 dims = r.froxelDims;
    bindComputePass(cmd, pass, b);
    vkCmdDispatch(cmd, static_cast<uint32_t>(shd::brumeDivRoundUp(dims.x, shd::FROXEL_GROUP_X)),
                  static_cast<uint32_t>(shd::brumeDivRoundUp(dims.y, shd::FROXEL_GROUP_Y)),
                  static_cast<uint32_t>(shd::brumeDivRoundUp(dims.z, shd::FROXEL_GROUP_Z)));
    const HistoryImages& out = r.history[static_cast<size_t>(writeIndex)];
    const VkImage outS = out.source.image.get(), outE = out.extinction.image.get();
    const VkImage source = r.source.image.get(), extinction = r.mediaExtinction.image.get();
    constexpr VkImageLayout G = VK_IMAGE_LAYOUT_GENERAL, SRC = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                            DST = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    // The dispatch wrote the history (read by the copy) and read source/extinction (overwritten by it).
    relayout(cmd, {{outS, {G, SRC}}, {outE, {G, SRC}}, {source, {G, DST}}, {extinction, {G, DST}}},
             VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
             VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT);
    VkImageCopy region{};
    region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.dstSubresource = region.srcSubresource;
    region.extent = out.source.extent;
    vkCmdCopyImage(cmd, outS, SRC, source, DST, 1, &region);
    vkCmdCopyImage(cmd, outE, SRC, extinction, DST, 1, &region);
    relayout(cmd, {{outS, {SRC, G}}, {outE, {SRC, G}}, {source, {DST, G}}, {extinction, {DST, G}}},
             VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT,
             VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
}

}  // namespace brume::gpu
