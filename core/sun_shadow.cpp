#include "sun_shadow.h"

#include <cstring>

#include "parallel.h"

namespace brume {
namespace {

// Past the first hit before looking for the second [m]: above float resolution at the rays'
// ~1000 m (6e-5 m), far below any solid's thickness.
constexpr float kSecondDepthGap = 1.0e-3f;

}  // namespace

// docs/shadows.md, "Sun shadow map": at 1024 a 96 m froxel range's map has ~0.2 m texels.
int sunShadowMapResolution(Quality q) { return q == Quality::Low ? 512 : 1024; }

int sunShadowLight(const CompiledScene& cs) {
    for (size_t i = 0; i < cs.lights.size(); ++i) {
        const shd::LightData& l = cs.lights[i];
        if (l.kind.x == shd::LIGHT_DIRECTIONAL && shd::lightCastsShadows(l)) return static_cast<int>(i);
    }
    return -1;
}

void applySunShadowSettings(shd::FrameUniforms& frame, const CompiledScene& cs) {
    frame.sunShadowLight = sunShadowLight(cs) + 1;
}

SunShadowMap buildSunShadowMap(const CompiledScene& cs, const GeometrySet& geometry, const shd::FrameUniforms& frame,
                               int resolution, int threads) {
    SunShadowMap map;
    if (frame.sunShadowLight <= 0) return map;
    map.fit = shd::fitSunShadow(frame, cs.lights[static_cast<size_t>(frame.sunShadowLight - 1)], resolution);
    // Two layers: surfaces' second depths, then the froxels' (shared/sun_shadow.h).
    map.depth.assign(2 * static_cast<size_t>(resolution) * static_cast<size_t>(resolution), shd::BRUME_HUGE);
    const glm::vec3 dir(map.fit.dir);
    // Rays end past the far side of the fitted sphere: nothing beyond can shadow the froxel range.
    const float tMax = shd::SUN_SHADOW_RAY_START + 2.0f * map.fit.centerRadius.w;
    parallelFor(resolution, threads, [&](int j) {
        for (int i = 0; i < resolution; ++i) {
            const Ray ray{shd::sunShadowTexelRayOrigin(map.fit, i, j), dir};
            const SurfaceHit first = geometry.intersect(ray, tMax);
            if (!first.hit()) continue;
            // The second surface: where the ray leaves the first solid (shared/sun_shadow.h).
            const SurfaceHit second = geometry.intersect(ray, tMax, first.t + kSecondDepthGap);
            if (!second.hit()) continue;
            const glm::ivec2 texel(i, j);
            map.depth[static_cast<size_t>(shd::sunShadowIndex(map.fit, texel))] = second.t - shd::SUN_SHADOW_RAY_START;
            const bool plane = geometry.type(first.index) == GeometryType::Plane;
            map.depth[static_cast<size_t>(shd::sunShadowFroxelIndex(map.fit, texel))] =
                (plane ? second.t : first.t) - shd::SUN_SHADOW_RAY_START;
        }
    });
    return map;
}

const SunShadowMap& SunShadowCache::get(const CompiledScene& cs, const std::vector<Geometry>& geometry,
                                        const shd::FrameUniforms& frame, int resolution, int threads) {
    shd::SunShadowFit fit{};
    if (frame.sunShadowLight > 0)
        fit = shd::fitSunShadow(frame, cs.lights[static_cast<size_t>(frame.sunShadowLight - 1)], resolution);
    const bool mapped = frame.sunShadowLight > 0;
    auto same = [&](const Entry& e) {
        return e.valid && e.geometry == geometry && mapped == !e.map.depth.empty() &&
               (!mapped || std::memcmp(&fit, &e.map.fit, sizeof(fit)) == 0);
    };
    if (!same(entries_[0])) {
        std::swap(entries_[0], entries_[1]);  // the older entry moves to the front: reused or rebuilt
        if (!same(entries_[0])) {
            entries_[0].map = buildSunShadowMap(cs, GeometrySet(geometry), frame, resolution, threads);
            entries_[0].geometry = geometry;
            entries_[0].valid = true;
            ++builds_;
        }
    }
    return entries_[0].map;
}

namespace {

// PCF over one layer of the map (0: surfaces, 1: froxels).
float visibilityInLayer(const SunShadowMap& map, const shd::FrameUniforms& frame, int light, glm::vec3 p, bool froxels) {
    if (!shd::sunShadowMapped(frame, light) || map.depth.empty()) return 1.0f;
    const shd::SunShadowLookup k = shd::sunShadowLookup(map.fit, p);
    if (!k.inside) return 1.0f;
    auto at = [&](int dx, int dy) {
        const glm::ivec2 texel = k.texel + glm::ivec2(dx, dy);
        return map.depth[static_cast<size_t>(froxels ? shd::sunShadowFroxelIndex(map.fit, texel)
                                                     : shd::sunShadowIndex(map.fit, texel))];
    };
    return shd::sunShadowPcf(k, at(0, 0), at(1, 0), at(0, 1), at(1, 1));
}

}  // namespace

float sunShadowVisibility(const SunShadowMap& map, const shd::FrameUniforms& frame, int light, glm::vec3 p) {
    return visibilityInLayer(map, frame, light, p, false);
}

float sunShadowFroxelVisibility(const SunShadowMap& map, const shd::FrameUniforms& frame, int light, glm::vec3 p) {
    return visibilityInLayer(map, frame, light, p, true);
}

}  // namespace brume
