// Temporal pass (shaders/temporal.comp; rule in shaders/shared/temporal.h; reads and writes in
// frame_table.cpp) over the temporal region (core/media_region.h temporalFroxelRegion), what a pass
// over the whole grid would write outside it written by clears; integrate pass, integrating the
// region's columns and storing the empty entries of the others itself (shaders/integrate.comp).
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
    // No clear: the pass runs over the columns some reader looks up (integrateColumns) and stores every
    // entry they read there, scattering 0 and transmittance 1 in front of the temporal region and
    // outside its columns (integrate.comp).
    if (ctx.poisonIntegrated) {
        // Tests: an entry the pass leaves unstored reads NaN scattering (GpuOptions::poisonIntegrated).
        VkClearColorValue nan{};
        nan.float32[0] = nan.float32[1] = nan.float32[2] = std::numeric_limits<float>::quiet_NaN();
        VkClearColorValue half{};
        half.float32[0] = half.float32[1] = half.float32[2] = 0.5f;
        clearImages(ctx.cmd, {{r[ImageId::integratedScattering].image.get(), nan},
                              {r[ImageId::integratedTransmittance].image.get(), half}});
    }
    // The push constants (IntegrateParams) with the dispatch (frame_executor.cpp Dispatch::IntegrateColumns).
    dispatchPass(ctx);
}

glm::ivec4 integrateColumns(const PassContext& ctx) {
    const FrameResources& r = *ctx.res;
    const glm::ivec2 dims(r.froxelDims);
    const glm::ivec4 all(0, 0, dims);
    if (ctx.readBackVolumes || ctx.debugParams.view.x != shd::DEBUG_VIEW_FINAL || r.distantFog) return all;
    glm::ivec2 lo = dims, hi(0);
    auto add = [&](glm::ivec2 a, glm::ivec2 b) {
        a = glm::max(a, glm::ivec2(0)), b = glm::min(b, dims);
        if (glm::any(glm::lessThanEqual(b, a))) return;
        lo = glm::min(lo, a), hi = glm::max(hi, b);
    };
    // Pixel x's lookups read columns floor((x + 0.5) / tile - 0.5) and the next (shared/froxel.h
    // integratedLookup, clamped to the grid): for the pixels [a, b], the columns from a's first to b's
    // second, with a column more on each side should the shader's division round the other way at a
    // column's edge.
    const float tile = static_cast<float>(r.froxelTile);
    auto addPixels = [&](glm::ivec2 a, glm::ivec2 b) {
        auto first = [&](glm::ivec2 p) { return glm::ivec2(glm::floor((glm::vec2(p) + 0.5f) / tile - 0.5f)); };
        add(first(a) - 1, first(b) + 3);
    };
    // The composite's pixels (gpu_renderer.cpp compositePixels) and each glow's rectangle.
    if (r.compositeHi.x > r.compositeLo.x && r.compositeHi.y > r.compositeLo.y) addPixels(r.compositeLo, r.compositeHi - 1);
    if (ctx.glow) {
        for (const shd::GlowParams& g : *ctx.glow)
            if (g.rect.z >= g.rect.x && g.rect.w >= g.rect.y) addPixels(glm::ivec2(g.rect.x, g.rect.y), glm::ivec2(g.rect.z, g.rect.w));
    }
    return glm::any(glm::lessThanEqual(hi, lo)) ? glm::ivec4(0) : glm::ivec4(lo, hi);
}

void recordColumnEnds(const PassContext& ctx) {
    const glm::ivec2 everywhere = storedEverywhere(ctx);
    pushRegion(ctx, FroxelRegion{}, everywhere.x, everywhere.y);
    dispatchPass(ctx);
}

}  // namespace brume::gpu
