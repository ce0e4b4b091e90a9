// Temporal pass (shaders/temporal.comp; rule in shaders/shared/temporal.h; reads and writes in
// frame_table.cpp) and integrate pass, both over the temporal region (core/media_region.h
// temporalFroxelRegion); what a pass over the whole grid would write outside it is written by clears.
// The resolved S and sigma_t live in the history's *_OUT side, where integrate, glow, debug view and
// readback read them: in motion the temporal pass writes them there; at rest it only clears, and
// integrate_rest resolves and writes them.
#include <algorithm>
#include <array>
#include <initializer_list>
#include <limits>

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

// Entries stored in every column beyond those the composite's lookups read (integrate.comp): all of
// them for the read-back volumes and the debug views, else the span of the glows' (none: first >
// last, no entry). A frame that skips hidden froxels lights and resolves each column down to these too
// (column_entries.glsl).
glm::ivec2 storedEverywhere(const PassContext& ctx) {
    glm::ivec2 everywhere(std::numeric_limits<int>::max(), -1);
    if (ctx.readBackVolumes || ctx.debugParams.view.x != shd::DEBUG_VIEW_FINAL) {
        everywhere = glm::ivec2(0, ctx.res->froxelDims.z - 1);
    } else if (ctx.glow) {
        for (const shd::GlowParams& g : *ctx.glow)
            everywhere = glm::ivec2(std::min(everywhere.x, g.light.y), std::max(everywhere.y, g.light.z));
    }
    return everywhere;
}

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
    // the history's output itself.
    if (ctx.variant && ctx.variant->temporalRest) return;
    pushRegion(ctx, r.temporalRegion);
    dispatchPass(ctx);
}

void recordIntegrate(const PassContext& ctx) {
    const FrameResources& r = *ctx.res;
    if (wholeGrid(r) && ctx.poisonIntegrated) {
        // Tests: an entry the pass leaves unstored reads NaN scattering (GpuOptions::poisonIntegrated).
        VkClearColorValue nan{};
        nan.float32[0] = nan.float32[1] = nan.float32[2] = std::numeric_limits<float>::quiet_NaN();
        VkClearColorValue half{};
        half.float32[0] = half.float32[1] = half.float32[2] = 0.5f;
        clearImages(ctx.cmd, {{r[ImageId::integratedScattering].image.get(), nan},
                              {r[ImageId::integratedTransmittance].image.get(), half}});
    } else if (!wholeGrid(r)) {
        // Empty froxels integrate to scattering 0 and transmittance 1 (alpha 0, as the shader writes).
        VkClearColorValue one{};
        one.float32[0] = one.float32[1] = one.float32[2] = 1.0f;
        clearImages(ctx.cmd, {{r[ImageId::integratedScattering].image.get(), VkClearColorValue{}},
                              {r[ImageId::integratedTransmittance].image.get(), one}});
    }
    const glm::ivec2 everywhere = storedEverywhere(ctx);
    pushRegion(ctx, r.temporalRegion, everywhere.x, everywhere.y);
    dispatchPass(ctx);
}

void recordColumnEnds(const PassContext& ctx) {
    const glm::ivec2 everywhere = storedEverywhere(ctx);
    pushRegion(ctx, FroxelRegion{}, everywhere.x, everywhere.y);
    dispatchPass(ctx);
}

}  // namespace brume::gpu
