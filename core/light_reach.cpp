#include "light_reach.h"

#include <algorithm>
#include <cmath>

#include "clusters.h"
#include "shaders/shared/glow.h"

namespace brume {
namespace {

// Relative slack on distances: fragment positions are interpolated in float and may lie a little
// outside the frustum; a light grazing it must not be culled by rounding.
constexpr float kSlack = 1.0e-3f;

// Lights some cluster holding a froxel of `froxels` lists (every light that can reach one, when a
// cluster is over-full and loops over all of them).
std::vector<char> listedInClusters(const LightClusters& clusters, size_t lightCount, const FroxelRegion& froxels) {
    std::vector<char> listed(lightCount, 0);
    if (froxels.empty()) return listed;
    const glm::ivec3 lo = froxels.lo / shd::CLUSTER_FROXELS;
    const glm::ivec3 hi = glm::min((froxels.hi - 1) / shd::CLUSTER_FROXELS, clusters.dims - 1);
    for (int z = lo.z; z <= hi.z; ++z) {
        for (int y = lo.y; y <= hi.y; ++y) {
            for (int x = lo.x; x <= hi.x; ++x) {
                const size_t r =
                    static_cast<size_t>((z * clusters.dims.y + y) * clusters.dims.x + x) * shd::CLUSTER_STRIDE;
                const int n = clusters.records[r];
                if (n == shd::CLUSTER_ALL_LIGHTS) return std::vector<char>(lightCount, 1);
                for (int k = 0; k < n; ++k)
                    listed[static_cast<size_t>(clusters.records[r + 1 + static_cast<size_t>(k)])] = 1;
            }
        }
    }
    return listed;
}

}  // namespace

std::vector<FroxelRegion> listedFroxelRegions(const LightClusters& clusters, size_t lightCount,
                                              const FroxelRegion& froxels) {
    std::vector<FroxelRegion> out(lightCount);
    if (froxels.empty()) return out;
    auto grow = [&](size_t light, const FroxelRegion& box) { out[light] = regionUnion(out[light], box); };
    const glm::ivec3 lo = froxels.lo / shd::CLUSTER_FROXELS;
    const glm::ivec3 hi = glm::min((froxels.hi - 1) / shd::CLUSTER_FROXELS, clusters.dims - 1);
    for (int z = lo.z; z <= hi.z; ++z) {
        for (int y = lo.y; y <= hi.y; ++y) {
            for (int x = lo.x; x <= hi.x; ++x) {
                // The cluster's froxels inside `froxels`.
                const glm::ivec3 c(x, y, z);
                const FroxelRegion box{glm::max(c * shd::CLUSTER_FROXELS, froxels.lo),
                                       glm::min((c + 1) * shd::CLUSTER_FROXELS, froxels.hi)};
                const size_t r =
                    static_cast<size_t>((z * clusters.dims.y + y) * clusters.dims.x + x) * shd::CLUSTER_STRIDE;
                const int n = clusters.records[r];
                if (n == shd::CLUSTER_ALL_LIGHTS) {
                    for (size_t i = 0; i < lightCount; ++i) grow(i, box);
                    continue;
                }
                for (int k = 0; k < n; ++k) grow(static_cast<size_t>(clusters.records[r + 1 + static_cast<size_t>(k)]), box);
            }
        }
    }
    return out;
}

bool lightMayReachFrustum(const shd::LightData& l, const shd::FrameUniforms& frame, float nearDepth, float farDepth) {
    if (glm::vec3(l.intensity) == glm::vec3(0.0f)) return false;
    const float range = l.positionRange.w;
    if (l.kind.x == shd::LIGHT_DIRECTIONAL || range <= 0.0f) return true;
    const glm::vec3 q = glm::vec3(frame.viewFromWorld * glm::vec4(glm::vec3(l.positionRange), 1.0f));
    const float depth = -q.z;
    const float reach = range + kSlack * (range + glm::length(q) + farDepth);
    const float tx = frame.projection.x, ty = frame.projection.y;
    // Signed distances outside the near, far and four side planes (view space, camera at 0).
    if (nearDepth - depth > reach || depth - farDepth > reach) return false;
    if ((std::abs(q.x) - tx * depth) / std::sqrt(1.0f + tx * tx) > reach) return false;
    if ((std::abs(q.y) - ty * depth) / std::sqrt(1.0f + ty * ty) > reach) return false;
    return true;
}

LightReach buildLightReach(const CompiledScene& cs, const shd::FrameUniforms& frame, const LightClusters& clusters,
                           bool culling, bool surfaces, const FroxelRegion* lightPassFroxels) {
    LightReach out;
    out.shadowVolume.assign(cs.lights.size(), 0);
    const FroxelRegion grid{glm::ivec3(0), glm::ivec3(frame.froxelDims)};
    const std::vector<char> listed =
        listedInClusters(clusters, cs.lights.size(), lightPassFroxels ? *lightPassFroxels : grid);
    // The light pass reads a light's layer only where the light reaches media: inside some volume's
    // bounds (outside them every density is 0 and the pass skips the froxel).
    auto reachesMedia = [&](const shd::LightData& l) {
        for (const shd::VolumeData& v : cs.volumes)
            if (lightMayReachBox(l, glm::vec3(v.worldMin), glm::vec3(v.worldMax))) return true;
        return false;
    };
    for (size_t i = 0; i < cs.lights.size(); ++i) {
        const shd::LightData& l = cs.lights[i];
        if (shd::lightGlowRadius(l, frame) > 0.0f && (!culling || reachesMedia(l)))
            out.glowLights.push_back(static_cast<int>(i));
        const bool surface = !culling || lightMayReachFrustum(l, frame, frame.projection.z, frame.projection.w);
        if (surface) out.surfaceLights.push_back(static_cast<int>(i));
        if (!shd::fogShadowsLight(l, frame.localFogShadows)) continue;
        // Surfaces read the volume inside the froxel grid only: from the camera to the froxel far.
        const bool read = (listed[i] && reachesMedia(l)) ||
                          (surfaces && surface && lightMayReachFrustum(l, frame, 0.0f, frame.froxelRange.y));
        out.shadowVolume[i] = !culling || read ? 1 : 0;
    }
    std::stable_partition(out.surfaceLights.begin(), out.surfaceLights.end(),
                          [&](int i) { return cs.lights[static_cast<size_t>(i)].kind.x == shd::LIGHT_DIRECTIONAL; });
    return out;
}

std::vector<int> lightReachRecord(const LightReach& reach, size_t lightCount) {
    std::vector<int> record(1 + lightCount, 0);
    record[0] = static_cast<int>(reach.surfaceLights.size());
    for (size_t k = 0; k < reach.surfaceLights.size(); ++k) record[1 + k] = reach.surfaceLights[k];
    return record;
}

}  // namespace brume
