// Glow pass (shaders/glow.comp; reads and writes in frame_table.cpp).
#include <algorithm>
#include <cmath>

#include "passes.h"

namespace brume::gpu {

namespace {

// Pixel columns (x0, x1), inclusive, whose centres' rays on the pixel row at view slope sy (froxel.h
// viewRayFromPixel: ray (sx, sy, -1)) meet the ball of the given radius around view-space centre c;
// x1 < x0 when none. The ray meets the ball where the ball's centre lies within R of it:
// (c . r)^2 >= (|c|^2 - R^2) |r|^2, a quadratic in sx whose leading coefficient
// c.x^2 - (|c|^2 - R^2) = R^2 - c.y^2 - c.z^2 is negative for a ball in front of the camera
// (depth > R), so the slopes lie between its roots. In double precision, with the pixel margin of
// shd::lightGlowScreenRect.
glm::ivec2 glowRowSpan(glm::dvec3 c, double radius, double sy, const shd::FrameUniforms& f) {
    const double d = -c.z;
    const double k = c.y * sy + d;  // c . r without its sx term
    const double m = glm::dot(c, c) - radius * radius;
    const double a = c.x * c.x - m;
    const double b = c.x * k;
    const double cc = k * k - m * (sy * sy + 1.0);
    const double disc = b * b - a * cc;
    if (!(a < 0.0) || disc < 0.0) return {0, -1};
    const double root = std::sqrt(disc);
    const double s0 = (-b + root) / a, s1 = (-b - root) / a;
    const double w = static_cast<double>(f.counts.x);
    const double px0 = (std::min(s0, s1) / static_cast<double>(f.projection.x) + 1.0) * 0.5 * w;
    const double px1 = (std::max(s0, s1) / static_cast<double>(f.projection.x) + 1.0) * 0.5 * w;
    // Pixel i's centre is at i + 0.5; one pixel of margin, as the rectangle's.
    const double x0 = std::clamp(std::floor(px0 - 0.5) - 1.0, -1.0, w), x1 = std::clamp(std::ceil(px1 - 0.5) + 1.0, -1.0, w);
    return {static_cast<int>(x0), static_cast<int>(x1)};
}

}  // namespace

std::vector<shd::GlowParams> glowDispatches(const std::vector<shd::LightData>& lights, const shd::FrameUniforms& frame,
                                            const std::vector<int>& glowLights) {
    std::vector<shd::GlowParams> out;
    for (int index : glowLights) {
        const shd::LightData& l = lights[static_cast<size_t>(index)];
        const glm::ivec4 rect = shd::lightGlowScreenRect(l, frame);
        if (rect.z < rect.x || rect.w < rect.y) continue;
        const glm::ivec4 light(index, 0, 0, 0);
        const float radius = shd::lightGlowRadius(l, frame);
        const glm::vec3 c = glm::vec3(frame.viewFromWorld * glm::vec4(glm::vec3(l.positionRange), 1.0f));
        // The whole image (the ball reaches behind the camera near): one dispatch, as the rectangle.
        if (!(-c.z - radius > 0.5f * frame.projection.z)) {
            out.push_back({rect, light});
            continue;
        }
        // The ball's rectangle in bands of whole workgroup rows, each as wide as its rows' spans.
        const int tileRows = shd::brumeDivRoundUp(rect.w - rect.y + 1, shd::SCREEN_GROUP_Y);
        const int bands = std::min(tileRows, GLOW_BANDS_PER_LIGHT);
        // The span with a radius a little larger, over the band's rows and one more on each side:
        // the GPU's rays (normalized world directions) round otherwise than this.
        const double spanRadius = static_cast<double>(radius) * (1.0 + 1.0e-4);
        for (int band = 0; band < bands; ++band) {
            const int y0 = rect.y + band * tileRows / bands * shd::SCREEN_GROUP_Y;
            const int y1 = std::min(rect.y + (band + 1) * tileRows / bands * shd::SCREEN_GROUP_Y - 1, rect.w);
            glm::ivec2 span(rect.z + 1, rect.x - 1);
            for (int y = y0 - 1; y <= y1 + 1; ++y) {
                const double ndcY = 1.0 - 2.0 * (static_cast<double>(y) + 0.5) / static_cast<double>(frame.counts.y);
                const glm::ivec2 row = glowRowSpan(glm::dvec3(c), spanRadius, ndcY * frame.projection.y, frame);
                if (row.y < row.x) continue;
                span = glm::ivec2(std::min(span.x, row.x), std::max(span.y, row.y));
            }
            span = glm::ivec2(std::max(span.x, rect.x), std::min(span.y, rect.z));
            if (span.y < span.x) continue;
            out.push_back({glm::ivec4(span.x, y0, span.y, y1), light});
        }
    }
    return out;
}

void recordGlow(const PassContext& ctx) {
    bindComputePass(ctx.cmd, *ctx.pipeline, *ctx.bindings);
    const VkPipelineStageFlags compute = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
    for (size_t i = 0; i < ctx.glow->size(); ++i) {
        const shd::GlowParams& g = (*ctx.glow)[i];
        // Each light adds to the output the previous one wrote; a light's bands hold other pixels.
        if (i > 0 && (*ctx.glow)[i - 1].light.x != g.light.x)
            memoryBarrier(ctx.cmd, compute, VK_ACCESS_SHADER_WRITE_BIT, compute,
                          VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
        vkCmdPushConstants(ctx.cmd, ctx.bindings->pipelineLayout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(g), &g);
        vkCmdDispatch(ctx.cmd, static_cast<uint32_t>(shd::brumeDivRoundUp(g.rect.z - g.rect.x + 1, shd::SCREEN_GROUP_X)),
                      static_cast<uint32_t>(shd::brumeDivRoundUp(g.rect.w - g.rect.y + 1, shd::SCREEN_GROUP_Y)), 1);
    }
}

}  // namespace brume::gpu
