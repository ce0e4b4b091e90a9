#include "light_reach.h"

#include <cmath>

#include "clusters.h"

namespace brume {
namespace {

// Relative slack on distances: fragment positions are interpolated in float and may lie a little
// outside the frustum; a light grazing it must not be culled by rounding.
constexpr float kSlack = 1.0e-3f;

// The axis-aligned box around the froxel grid's eight corners (the grid is a convex frustum).
void froxelGridBox(const shd::FrameUniforms& frame, glm::vec3& lo, glm::vec3& hi) {
    const glm::vec3 dims(glm::ivec3(frame.froxelDims));
    lo = glm::vec3(shd::BRUME_HUGE);
    hi = glm::vec3(-shd::BRUME_HUGE);
    for (int k = 0; k < 8; ++k) {
        const glm::vec3 corner((k & 1) ? dims.x : 0.0f, (k & 2) ? dims.y : 0.0f, (k & 4) ? dims.z : 0.0f);
        const glm::vec3 w = shd::worldFromFroxelCoord(corner, frame);
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
    }
}

}  // namespace

bool lightMayReachFrustum(const shd::LightData& l, const shd::FrameUniforms& frame) {
    if (glm::vec3(l.intensity) == glm::vec3(0.0f)) return false;
    const float range = l.positionRange.w;
    if (l.kind.x == shd::LIGHT_DIRECTIONAL || range <= 0.0f) return true;
    const glm::vec3 q = glm::vec3(frame.viewFromWorld * glm::vec4(glm::vec3(l.positionRange), 1.0f));
    const float depth = -q.z;
    const float reach = range + kSlack * (range + glm::length(q) + frame.projection.w);
    const float tx = frame.projection.x, ty = frame.projection.y;
    // Signed distances outside the near, far and four side planes (view space, camera at 0).
    if (frame.projection.z - depth > reach || depth - frame.projection.w > reach) return false;
    if ((std::abs(q.x) - tx * depth) / std::sqrt(1.0f + tx * tx) > reach) return false;
    if ((std::abs(q.y) - ty * depth) / std::sqrt(1.0f + ty * ty) > reach) return false;
    return true;
}

LightReach buildLightReach(const CompiledScene& cs, const shd::FrameUniforms& frame, bool culling) {
    LightReach out;
    out.shadowVolume.assign(cs.lights.size(), 0);
    glm::vec3 lo, hi;
    froxelGridBox(frame, lo, hi);
    for (size_t i = 0; i < cs.lights.size(); ++i) {
        const shd::LightData& l = cs.lights[i];
        const bool surface = !culling || lightMayReachFrustum(l, frame);
        if (surface) out.surfaceLights.push_back(static_cast<int>(i));
        if (!shd::fogShadowsLight(l, frame.shadows.x)) continue;
        // The grid test without fog_scale, which only the light pass's readers depend on.
        shd::LightData lit = l;
        lit.intensity.w = 1.0f;
        const bool read = l.intensity.w > 0.0f || surface;
        out.shadowVolume[i] = !culling || (read && lightMayReachBox(lit, lo, hi)) ? 1 : 0;
    }
    return out;
}

std::vector<int> lightReachRecord(const LightReach& reach, size_t lightCount) {
    std::vector<int> record(1 + 2 * lightCount, 0);
    record[0] = static_cast<int>(reach.surfaceLights.size());
    for (size_t k = 0; k < reach.surfaceLights.size(); ++k) record[1 + k] = reach.surfaceLights[k];
    for (size_t i = 0; i < lightCount; ++i) record[1 + lightCount + i] = reach.shadowVolume[i];
    return record;
}

}  // namespace brume
