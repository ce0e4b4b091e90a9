#include "clusters.h"

#include <algorithm>
#include <cmath>

namespace brume {
namespace {

using glm::ivec3;
using glm::vec3;

// Relative slack on distances: froxel sample points are computed in float by another expression
// than the corners, so a light exactly grazing the box must not be culled by rounding.
constexpr float kSlack = 1.0e-4f;

bool reachesNothing(const shd::LightData& l) {
    return l.fogScale <= 0.0f || vec3(l.intensity) == vec3(0.0f);
}

// Cone (apex, unit axis, outer half-angle) against a sphere (centre c, radius r): Wronski's test,
// "cull that cone" (2017). A spot cone wider than a hemisphere is kept (the test needs cos >= 0).
bool coneMayReachSphere(const shd::LightData& l, vec3 c, float r) {
    const float cosOuter = l.spot.x;
    if (cosOuter <= 0.0f) return true;
    const vec3 v = c - vec3(l.positionRange);
    const float along = glm::dot(v, vec3(l.direction));
    const float sinOuter = std::sqrt(std::max(0.0f, 1.0f - cosOuter * cosOuter));
    const float across = std::sqrt(std::max(0.0f, glm::dot(v, v) - along * along));
    const float outside = cosOuter * across - along * sinOuter;  // signed distance beyond the cone's side
    return outside <= r && along >= -r;
}

}  // namespace

bool lightMayReachBox(const shd::LightData& l, vec3 lo, vec3 hi) {
    if (reachesNothing(l)) return false;
    if (l.kind.x == shd::LIGHT_DIRECTIONAL) return true;
    const vec3 p = vec3(l.positionRange);
    const float range = l.positionRange.w;
    const float extent = glm::length(hi - lo);
    const float slack = kSlack * (extent + glm::length(p));
    // rangeWindow is 0 at dist >= range; range 0 means no window.
    if (range > 0.0f) {
        const vec3 nearest = glm::clamp(p, lo, hi);
        if (glm::length(nearest - p) >= range + slack) return false;
    }
    if (l.kind.x == shd::LIGHT_SPOT) return coneMayReachSphere(l, 0.5f * (lo + hi), 0.5f * extent + slack);
    return true;
}

LightClusters buildLightClusters(const CompiledScene& cs, const shd::FrameUniforms& frame, bool culling) {
    LightClusters out;
    const ivec3 froxels(frame.froxelDims);
    out.dims = shd::clusterDims(froxels);
    const size_t count =
        static_cast<size_t>(out.dims.x) * static_cast<size_t>(out.dims.y) * static_cast<size_t>(out.dims.z);
    out.records.assign(count * shd::CLUSTER_STRIDE, 0);
    // Only the lights that can reach some volume's bounds are tested per cluster: outside every
    // volume's bounds the density is 0, so another light's term is exactly 0 in every froxel that
    // has media (its range window is 0 there, or its cone misses). Lights in view that light no fog
    // (target 4's 32 dark lights: ~1 ms of host time a frame at `high`) then cost one test per volume,
    // not one per cluster.
    std::vector<int> candidates;
    for (size_t li = 0; culling && li < cs.lights.size(); ++li) {
        bool reaches = false;
        for (const shd::VolumeData& v : cs.volumes)
            reaches = reaches || lightMayReachBox(cs.lights[li], vec3(v.worldMin), vec3(v.worldMax));
        if (reaches) candidates.push_back(static_cast<int>(li));
    }
    for (int cz = 0; cz < out.dims.z; ++cz)
        for (int cy = 0; cy < out.dims.y; ++cy)
            for (int cx = 0; cx < out.dims.x; ++cx) {
                const ivec3 first = ivec3(cx, cy, cz) * shd::CLUSTER_FROXELS;
                const ivec3 last = glm::min(first + ivec3(shd::CLUSTER_FROXELS), froxels);
                // Sample points lie in [x, x + 1) froxel coordinates, and a froxel is convex: the
                // cluster's eight corners bound them all.
                vec3 lo(shd::BRUME_HUGE), hi(-shd::BRUME_HUGE);
                for (int k = 0; k < 8; ++k) {
                    const ivec3 corner((k & 1) ? last.x : first.x, (k & 2) ? last.y : first.y,
                                       (k & 4) ? last.z : first.z);
                    const vec3 w = shd::worldFromFroxelCoord(vec3(corner), frame);
                    lo = glm::min(lo, w);
                    hi = glm::max(hi, w);
                }
                int* record = &out.records[static_cast<size_t>(shd::clusterRecord(first, froxels))];
                int n = 0;
                for (size_t c = 0; culling && c < candidates.size() && n <= shd::CLUSTER_MAX_LIGHTS; ++c) {
                    const int li = candidates[c];
                    if (!lightMayReachBox(cs.lights[static_cast<size_t>(li)], lo, hi)) continue;
                    if (n < shd::CLUSTER_MAX_LIGHTS) record[1 + n] = li;
                    ++n;
                }
                if (!culling || n > shd::CLUSTER_MAX_LIGHTS) {
                    record[0] = shd::CLUSTER_ALL_LIGHTS;
                    if (culling) ++out.overfullClusters;
                } else {
                    record[0] = n;
                }
            }
    return out;
}

}  // namespace brume
