// Glow pass (shaders/glow.comp; reads and writes in frame_table.cpp).
#include <algorithm>

#include "passes.h"

namespace brume::gpu {

std::vector<shd::GlowParams> glowDispatches(const std::vector<shd::LightData>& lights, const shd::FrameUniforms& frame,
                                            const std::vector<int>& glowLights) {
    std::vector<shd::GlowParams> out;
    for (int index : glowLights) {
        const shd::LightData& l = lights[static_cast<size_t>(index)];
        const glm::ivec4 rect = shd::lightGlowScreenRect(l, frame);
        if (rect.z < rect.x || rect.w < rect.y) continue;
        // The glow reads the integrated transmittance where a pixel's ray enters the ball: at view
        // depths within the ball's radius of the light's (0 from inside it). The integrate pass keeps
        // those entries in every column (integrate.comp).
        const float depth = -(frame.viewFromWorld * glm::vec4(glm::vec3(l.positionRange), 1.0f)).z;
        const float radius = shd::lightGlowRadius(l, frame);
        const glm::ivec2 entries = shd::integratedEntryRange(std::max(depth - radius, 0.0f), std::max(depth + radius, 0.0f), frame);
        out.push_back({rect, glm::ivec4(index, entries.x, entries.y, 0)});
    }
    return out;
}

void recordGlow(const PassContext& ctx) {
    bindComputePass(ctx.cmd, *ctx.pipeline, *ctx.bindings);
    const VkPipelineStageFlags compute = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
    for (size_t i = 0; i < ctx.glow->size(); ++i) {
        const shd::GlowParams& g = (*ctx.glow)[i];
        // Each light adds to the output the previous one wrote.
        if (i > 0)
            memoryBarrier(ctx.cmd, compute, VK_ACCESS_SHADER_WRITE_BIT, compute,
                          VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
        vkCmdPushConstants(ctx.cmd, ctx.bindings->pipelineLayout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(g), &g);
        vkCmdDispatch(ctx.cmd, static_cast<uint32_t>(shd::brumeDivRoundUp(g.rect.z - g.rect.x + 1, shd::SCREEN_GROUP_X)),
                      static_cast<uint32_t>(shd::brumeDivRoundUp(g.rect.w - g.rect.y + 1, shd::SCREEN_GROUP_Y)), 1);
    }
}

}  // namespace brume::gpu
