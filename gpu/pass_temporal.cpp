// Temporal pass (shaders/temporal.comp; rule in shaders/shared/temporal.h; reads and writes in
// frame_table.cpp): the resolved history *_OUT is copied over sourceImage and mediaExtinction for the
// integrate pass.
#include <array>

#include "passes.h"
#include "shaders/shared/brume.h"
#include "vk_check.h"

namespace brume::gpu {

// One invocation per froxel, then the resolved pair replaces this frame's source and extinction
// (copied in transfer layouts, then every image is back in GENERAL for the passes after).
void recordTemporal(const PassContext& ctx) {
    dispatchPass(ctx);
    const VkCommandBuffer cmd = ctx.cmd;
    const FrameResources& r = *ctx.res;
    const GpuImage& outSource = r.image(historyOut(HistoryId::historySource), ctx.historyWriteIndex);
    const VkImage outS = outSource.image.get();
    const VkImage outE = r.image(historyOut(HistoryId::historyExtinction), ctx.historyWriteIndex).image.get();
    const VkImage source = r[ImageId::sourceImage].image.get(), extinction = r[ImageId::mediaExtinction].image.get();
    constexpr VkImageLayout G = VK_IMAGE_LAYOUT_GENERAL, SRC = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                            DST = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    // The dispatch wrote the history (read by the copy) and read source/extinction (overwritten by it).
    const std::array<LayoutChange, 4> toCopy{{{outS, G, SRC}, {outE, G, SRC}, {source, G, DST}, {extinction, G, DST}}};
    layoutBarrier(cmd, toCopy, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT);
    VkImageCopy region{};
    region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.dstSubresource = region.srcSubresource;
    region.extent = outSource.extent;
    vkCmdCopyImage(cmd, outS, SRC, source, DST, 1, &region);
    vkCmdCopyImage(cmd, outE, SRC, extinction, DST, 1, &region);
    const std::array<LayoutChange, 4> back{{{outS, SRC, G}, {outE, SRC, G}, {source, DST, G}, {extinction, DST, G}}};
    layoutBarrier(cmd, back, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
}

}  // namespace brume::gpu
