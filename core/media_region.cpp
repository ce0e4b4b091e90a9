#include "media_region.h"

#include <algorithm>
#include <cmath>

#include "shaders/shared/froxel.h"

namespace brume {

FroxelRegion mediaFroxelRegion(const CompiledScene& cs, const shd::FrameUniforms& frame) {
    const glm::ivec3 dims(frame.froxelDims);
    const FroxelRegion whole{glm::ivec3(0), dims};
    glm::ivec3 lo(dims), hi(0);
    const float tileW = float(frame.counts.x) / float(frame.froxelDims.w);
    const float tileH = float(frame.counts.y) / float(frame.froxelDims.w);
    for (const shd::VolumeData& v : cs.volumes) {
        const glm::vec3 wlo(v.worldMin), whi(v.worldMax);
        if (wlo.x > whi.x || wlo.y > whi.y || wlo.z > whi.z) continue;  // no extent: never dense
        const float reach = 0.5f * shd::BRUME_HUGE;
        if (glm::any(glm::lessThan(wlo, glm::vec3(-reach))) || glm::any(glm::greaterThan(whi, glm::vec3(reach))))
            return whole;
        // The box's view depths and projected tiles span those of its corners (a linear function and
        // a convex set's perspective image, when every corner is in front of the camera).
        float zMin = INFINITY, zMax = -INFINITY;
        glm::vec2 tMin(INFINITY), tMax(-INFINITY);
        bool behind = false;
        for (int c = 0; c < 8; ++c) {
            const glm::vec3 p((c & 1) ? whi.x : wlo.x, (c & 2) ? whi.y : wlo.y, (c & 4) ? whi.z : wlo.z);
            const glm::vec3 view(frame.viewFromWorld * glm::vec4(p, 1.0f));
            const float z = -view.z;
            zMin = std::min(zMin, z), zMax = std::max(zMax, z);
            if (!(z > 1e-6f)) {
                behind = true;
                continue;
            }
            const glm::vec2 ndc(view.x / (z * frame.projection.x), view.y / (z * frame.projection.y));
            const glm::vec2 tile((ndc.x + 1.0f) * 0.5f * tileW, (1.0f - ndc.y) * 0.5f * tileH);
            tMin = glm::min(tMin, tile), tMax = glm::max(tMax, tile);
        }
        // Froxel samples lie at view depths in [froxel near, froxel far] (slice 0 reaches the camera).
        if (!(zMax > 0.0f) || zMin > frame.froxelRange.y) continue;
        const float n = float(dims.z);
        const float sMin = shd::sliceTFromViewDepth(std::max(zMin, 0.0f), frame.froxelRange.x, frame.froxelRange.y,
                                                    frame.froxelRange.z) * n;
        const float sMax =
            shd::sliceTFromViewDepth(zMax, frame.froxelRange.x, frame.froxelRange.y, frame.froxelRange.z) * n;
        glm::vec3 cMin(tMin, sMin), cMax(tMax, sMax);
        if (behind) cMin.x = cMin.y = -1.0f, cMax.x = float(dims.x), cMax.y = float(dims.y);
        // A sample at id + jitter inside [cMin, cMax] has id in (cMin - 1, cMax]; one more froxel of
        // margin for rounding.
        const glm::vec3 fMin = glm::floor(glm::clamp(cMin, glm::vec3(-4.0f), glm::vec3(dims) + 4.0f));
        const glm::vec3 fMax = glm::floor(glm::clamp(cMax, glm::vec3(-4.0f), glm::vec3(dims) + 4.0f));
        const glm::ivec3 vLo = glm::clamp(glm::ivec3(fMin) - 2, glm::ivec3(0), dims);
        const glm::ivec3 vHi = glm::clamp(glm::ivec3(fMax) + 2, glm::ivec3(0), dims);
        if (glm::any(glm::lessThanEqual(vHi, vLo))) continue;
        lo = glm::min(lo, vLo), hi = glm::max(hi, vHi);
    }
    if (glm::any(glm::lessThanEqual(hi, lo))) return FroxelRegion{};
    return FroxelRegion{lo, hi};
}

}  // namespace brume
