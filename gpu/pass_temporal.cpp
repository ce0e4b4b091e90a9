// Temporal pass (shaders/temporal.comp; rule in shaders/shared/temporal.h; reads and writes in
// frame_table.cpp) and integrate pass, both over the temporal region (core/media_region.h
// temporalFroxelRegion); what a pass over the whole grid would write outside it is written by clears.
// In motion the resolved history *_OUT is copied over sourceImage and mediaExtinction for the
// integrate pass; at rest the temporal pass only clears, and integrate_rest resolves and writes them.
#include <array>
#include <initializer_list>

#include "passes.h"
#include "shaders/shared/bindings.h"
#include "shaders/shared/brume.h"
#include "vk_check.h"

namespace brume::gpu {
namespace {

constexpr VkPipelineStageFlags kCompute = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
constexpr VkPipelineStageFlags kTransfer = VK_PIPELINE_STAGE_TRANSFER_BIT;

bool wholeGrid(const FrameResources& r) {
    return r.temporalRegion.lo == glm::ivec3(0) && r.temporalRegion.hi == r.froxelDims;
}

struct Clear {
    VkImage image;
    VkClearColorValue value;
};

// Clears images (GENERAL), after the frame's layout transitions and earlier readers and writers
// (compute and transfer), before the compute passes that follow.
void clearImages(VkCommandBuffer cmd, std::initializer_list<Clear> clears) {
    memoryBarrier(cmd, kCompute | kTransfer,
                  VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT |
                      VK_ACCESS_TRANSFER_WRITE_BIT,
                  kTransfer, VK_ACCESS_TRANSFER_WRITE_BIT);
    const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    for (const Clear& c : clears) vkCmdClearColorImage(cmd, c.image, VK_IMAGE_LAYOUT_GENERAL, &c.value, 1, &all);
    memoryBarrier(cmd, kTransfer, VK_ACCESS_TRANSFER_WRITE_BIT, kCompute,
                  VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
}

}  // namespace

void recordTemporal(const PassContext& ctx) {
    const VkCommandBuffer cmd = ctx.cmd;
    const FrameResources& r = *ctx.res;
    const GpuImage& outSource = r.image(historyOut(HistoryId::historySource), ctx.historyWriteIndex);
    const VkImage outS = outSource.image.get();
    const VkImage outE = r.image(historyOut(HistoryId::historyExtinction), ctx.historyWriteIndex).image.get();
    // The side written now last held an older frame's history: outside this frame's region it must
    // read 0, as a pass over the whole grid would have written there.
    if (r.clearHistoryOut) clearImages(cmd, {{outS, VkClearColorValue{}}, {outE, VkClearColorValue{}}});
    // At rest the integrate pass (integrate_rest) resolves each froxel with its own history and writes
    // the history's output, sourceImage and mediaExtinction itself.
    if (ctx.variant && ctx.variant->temporalRest) return;
    pushRegion(ctx, r.temporalRegion);
    dispatchPass(ctx);
    if (r.temporalRegion.empty()) return;
    const VkImage source = r[ImageId::sourceImage].image.get(), extinction = r[ImageId::mediaExtinction].image.get();
    constexpr VkImageLayout G = VK_IMAGE_LAYOUT_GENERAL, SRC = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                            DST = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    // The dispatch wrote the history (read by the copy) and read source/extinction (overwritten by it).
    const std::array<LayoutChange, 4> toCopy{{{outS, G, SRC}, {outE, G, SRC}, {source, G, DST}, {extinction, G, DST}}};
    layoutBarrier(cmd, toCopy, kCompute, VK_ACCESS_SHADER_WRITE_BIT, kTransfer,
                  VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT);
    // Outside the region both sides hold 0 already (voxelize's and light's clears, the clear above).
    const glm::ivec3 lo = r.temporalRegion.lo, e = r.temporalRegion.hi - r.temporalRegion.lo;
    VkImageCopy region{};
    region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.dstSubresource = region.srcSubresource;
    region.srcOffset = {lo.x, lo.y, lo.z};
    region.dstOffset = region.srcOffset;
    region.extent = {static_cast<uint32_t>(e.x), static_cast<uint32_t>(e.y), static_cast<uint32_t>(e.z)};
    vkCmdCopyImage(cmd, outS, SRC, source, DST, 1, &region);
    vkCmdCopyImage(cmd, outE, SRC, extinction, DST, 1, &region);
    const std::array<LayoutChange, 4> back{{{outS, SRC, G}, {outE, SRC, G}, {source, DST, G}, {extinction, DST, G}}};
    layoutBarrier(cmd, back, kTransfer, VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT, kCompute,
                  VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
}

void recordIntegrate(const PassContext& ctx) {
    const FrameResources& r = *ctx.res;
    if (!wholeGrid(r)) {
        // Empty froxels integrate to scattering 0 and transmittance 1 (alpha 0, as the shader writes).
        VkClearColorValue one{};
        one.float32[0] = one.float32[1] = one.float32[2] = 1.0f;
        clearImages(ctx.cmd, {{r[ImageId::integratedScattering].image.get(), VkClearColorValue{}},
                              {r[ImageId::integratedTransmittance].image.get(), one}});
    }
    pushRegion(ctx, r.temporalRegion);
    dispatchPass(ctx);
}

}  // namespace brume::gpu
