#include "media_region.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "shaders/shared/brume.h"

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

FroxelRegion temporalFroxelRegion(const FroxelRegion& media, glm::ivec3 dims) {
    if (media.empty()) return FroxelRegion{};
    return FroxelRegion{glm::max(media.lo - 1, glm::ivec3(0)), glm::min(media.hi + 1, dims)};
}

FroxelRegion shadowCellRegion(const FroxelRegion& media, const shd::FrameUniforms& frame, bool surfaces) {
    const int r = std::max(frame.shadowReduction, 1);
    const glm::ivec3 cells = shd::shadowVolumeDims(glm::ivec3(frame.froxelDims), r);
    if (surfaces && frame.vdbShadowSamples > 0) return FroxelRegion{glm::ivec3(0), cells};
    if (media.empty()) return FroxelRegion{};
    return FroxelRegion{media.lo / r, glm::min((media.hi - 1) / r + 2, cells)};
}

bool regionContains(const FroxelRegion& outer, const FroxelRegion& inner) {
    if (inner.empty()) return true;
    return glm::all(glm::lessThanEqual(outer.lo, inner.lo)) && glm::all(glm::greaterThanEqual(outer.hi, inner.hi));
}

FroxelRegion regionUnion(const FroxelRegion& a, const FroxelRegion& b) {
    if (a.empty()) return b.empty() ? FroxelRegion{} : b;
    if (b.empty()) return a;
    return FroxelRegion{glm::min(a.lo, b.lo), glm::max(a.hi, b.hi)};
}

namespace {

// The convex set of points (the hull of `points`, swept along `sweep` to infinity when it is not
// zero) against an axis-aligned box: false when some axis separates them (the separating axis test
// over the box's axes, the hull's edge directions, the sweep and their cross products). Only a proof
// of separation culls, so a missing axis costs a missed cull, never a wrong one.
bool mayIntersect(const std::vector<glm::vec3>& points, const std::vector<glm::vec3>& edges, glm::vec3 sweep,
                  glm::vec3 boxLo, glm::vec3 boxHi) {
    std::vector<glm::vec3> dirs = edges;
    if (sweep != glm::vec3(0.0f)) dirs.push_back(sweep);
    std::vector<glm::vec3> axes{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (size_t i = 0; i < dirs.size(); ++i) {
        for (int a = 0; a < 3; ++a) axes.push_back(glm::cross(axes[static_cast<size_t>(a)], dirs[i]));
        for (size_t j = i + 1; j < dirs.size(); ++j) axes.push_back(glm::cross(dirs[i], dirs[j]));
    }
    const glm::vec3 centre = 0.5f * (boxLo + boxHi), half = 0.5f * (boxHi - boxLo);
    float scale = glm::length(half);
    for (const glm::vec3& p : points) scale = std::max(scale, glm::length(p - centre));
    for (glm::vec3 axis : axes) {
        const float len = glm::length(axis);
        if (!(len > 1e-6f)) continue;
        axis /= len;
        float lo = INFINITY, hi = -INFINITY;
        for (const glm::vec3& p : points) {
            const float d = glm::dot(p - centre, axis);
            lo = std::min(lo, d), hi = std::max(hi, d);
        }
        const float s = glm::dot(sweep, axis);
        if (s > 0.0f) hi = INFINITY;
        if (s < 0.0f) lo = -INFINITY;
        const float r = glm::dot(half, glm::abs(axis));
        const float margin = 1e-4f * scale + 1e-4f;  // rounding of the frustum's and the shaders' points
        if (lo > r + margin || hi < -r - margin) return false;
    }
    return true;
}

}  // namespace

namespace {

// Per volume: whether its bounds may meet the convex set `frustum` (8 corners: near x0y0, x1y0, x0y1,
// x1y1, then far the same) or a shadow ray from a point of it toward a light whose fog shadow is
// evaluated. Unbounded volumes: true.
std::vector<bool> volumesInReach(const CompiledScene& cs, const shd::FrameUniforms& frame,
                                 const std::vector<glm::vec3>& frustum) {
    // Its edge directions: along x, along y, and the four from the near to the far corners.
    std::vector<glm::vec3> edges{frustum[1] - frustum[0], frustum[2] - frustum[0]};
    for (int c = 0; c < 4; ++c) edges.push_back(frustum[static_cast<size_t>(c + 4)] - frustum[static_cast<size_t>(c)]);
    std::vector<bool> inReach(cs.volumes.size(), true);
    for (size_t i = 0; i < cs.volumes.size(); ++i) {
        const shd::VolumeData& v = cs.volumes[i];
        const glm::vec3 lo(v.worldMin), hi(v.worldMax);
        const float reach = 0.5f * shd::BRUME_HUGE;
        if (glm::any(glm::lessThan(lo, glm::vec3(-reach))) || glm::any(glm::greaterThan(hi, glm::vec3(reach)))) continue;
        bool any = mayIntersect(frustum, edges, glm::vec3(0.0f), lo, hi);
        for (const shd::LightData& l : cs.lights) {
            if (any) break;
            if (!shd::fogShadowsLight(l, frame.localFogShadows)) continue;
            if (l.kind.x == shd::LIGHT_DIRECTIONAL) {
                any = mayIntersect(frustum, edges, -glm::vec3(l.direction), lo, hi);
            } else {
                std::vector<glm::vec3> points = frustum, toLight = edges;
                points.push_back(glm::vec3(l.positionRange));
                for (const glm::vec3& p : frustum) toLight.push_back(glm::vec3(l.positionRange) - p);
                any = mayIntersect(points, toLight, glm::vec3(0.0f), lo, hi);
            }
        }
        inReach[i] = any;
    }
    return inReach;
}

}  // namespace

std::vector<bool> froxelVolumesInReach(const CompiledScene& cs, const shd::FrameUniforms& frame) {
    // The froxel frustum: sample points have froxel coordinates in [0, dims] on each axis.
    const glm::vec3 dims(glm::ivec3(frame.froxelDims));
    std::vector<glm::vec3> frustum;
    for (int c = 0; c < 8; ++c)
        frustum.push_back(shd::worldFromFroxelCoord(
            glm::vec3((c & 1) ? dims.x : 0.0f, (c & 2) ? dims.y : 0.0f, (c & 4) ? dims.z : 0.0f), frame));
    return volumesInReach(cs, frame, frustum);
}

std::vector<bool> surfaceVolumesInReach(const CompiledScene& cs, const shd::FrameUniforms& frame) {
    // The view frustum from the camera near to the camera far, where the rasterizer keeps surfaces:
    // the image's corner rays (shd::viewRayFromPixel, view depth 1) at both depths.
    const glm::vec2 size(glm::ivec2(frame.counts));
    std::vector<glm::vec3> frustum;
    for (int c = 0; c < 8; ++c) {
        const glm::vec3 ray = shd::viewRayFromPixel(glm::vec2((c & 1) ? size.x : 0.0f, (c & 2) ? size.y : 0.0f), frame);
        const float depth = (c & 4) ? frame.projection.w : frame.projection.z;
        frustum.push_back(glm::vec3(frame.worldFromView * glm::vec4(ray * depth, 1.0f)));
    }
    return volumesInReach(cs, frame, frustum);
}

}  // namespace brume
