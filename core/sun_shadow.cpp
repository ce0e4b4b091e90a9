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

namespace {

// The texels [lo, hi] (inclusive, clamped to the map; empty when lo > hi) whose rays can meet a
// primitive.
struct TexelRect {
    glm::ivec2 lo, hi;
};

// Each primitive's texels: its world bounds' 8 corners projected on the map's right and up axes (the
// texel rays run along its third, dir), widened by 2 texels, far more than the rounding of the
// projection and of the rays' origins. A plane, unbounded, covers the map.
std::vector<TexelRect> primitiveTexels(const GeometrySet& geometry, const shd::SunShadowFit& fit, int n) {
    std::vector<TexelRect> rects;
    const glm::vec3 centre(fit.centerRadius), right(fit.right), up(fit.up);
    const float r = fit.centerRadius.w;
    for (int k = 0; k < geometry.size(); ++k) {
        glm::vec3 lo, hi;
        if (!geometry.worldBounds(k, lo, hi)) {
            rects.push_back({glm::ivec2(0), glm::ivec2(n - 1)});
            continue;
        }
        glm::vec2 uvLo(shd::BRUME_HUGE), uvHi(-shd::BRUME_HUGE);
        for (int c = 0; c < 8; ++c) {
            const glm::vec3 p((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
            const glm::vec2 uv(glm::dot(p - centre, right), glm::dot(p - centre, up));
            uvLo = glm::min(uvLo, uv);
            uvHi = glm::max(uvHi, uv);
        }
        // Texel i's ray sits at u = ((i + 0.5) / n * 2 - 1) r (shd::sunShadowTexelRayOrigin).
        auto texel = [&](glm::vec2 uv) { return (uv / r + 1.0f) * 0.5f * static_cast<float>(n) - 0.5f; };
        const glm::vec2 a = glm::floor(texel(uvLo)) - 2.0f, b = glm::ceil(texel(uvHi)) + 2.0f;
        const float last = static_cast<float>(n - 1);
        if (!(a.x <= b.x && a.y <= b.y)) {
            rects.push_back({glm::ivec2(0), glm::ivec2(n - 1)});  // not finite (a degenerate transform): every texel
        } else if (b.x < 0.0f || b.y < 0.0f || a.x > last || a.y > last) {
            rects.push_back({glm::ivec2(1), glm::ivec2(0)});  // off the map
        } else {
            // Clamped as floats: bounds of 1e30 stay representable.
            rects.push_back({glm::ivec2(glm::max(a, glm::vec2(0.0f))), glm::ivec2(glm::min(b, glm::vec2(last)))});
        }
    }
    return rects;
}

}  // namespace

SunShadowMap buildSunShadowMap(const CompiledScene& cs, const GeometrySet& geometry, const shd::FrameUniforms& frame,
                               int resolution, int threads, bool cullByFootprint) {
    SunShadowMap map;
    if (frame.sunShadowLight <= 0) return map;
    map.fit = shd::fitSunShadow(frame, cs.lights[static_cast<size_t>(frame.sunShadowLight - 1)], resolution);
    // Two layers: surfaces' second depths, then the froxels' (shared/sun_shadow.h).
    map.depth.assign(2 * static_cast<size_t>(resolution) * static_cast<size_t>(resolution), shd::BRUME_HUGE);
    const glm::vec3 dir(map.fit.dir);
    // Rays end past the far side of the fitted sphere: nothing beyond can shadow the froxel range.
    const float tMax = shd::SUN_SHADOW_RAY_START + 2.0f * map.fit.centerRadius.w;
    const std::vector<TexelRect> rects = primitiveTexels(geometry, map.fit, resolution);
    parallelFor(resolution, threads, [&](int j) {
        // The primitives whose texels include row j, then those of texel (i, j), in index order.
        // A row whose primitives all span it (planes, or no culling) keeps one list for every texel.
        std::vector<int> row, candidates;
        bool wholeRow = true;
        for (int k = 0; k < geometry.size(); ++k) {
            const TexelRect& t = rects[static_cast<size_t>(k)];
            if (cullByFootprint && !(t.lo.y <= j && j <= t.hi.y)) continue;
            row.push_back(k);
            wholeRow = wholeRow && (!cullByFootprint || (t.lo.x == 0 && t.hi.x == resolution - 1));
        }
        // A ray that can meet one plane alone has no second surface (the plane's t again is not
        // past the first hit): its texel keeps BRUME_HUGE, as the ray cast below would leave it.
        auto planeAlone = [&](const std::vector<int>& c) {
            return c.size() == 1 && geometry.type(c[0]) == GeometryType::Plane;
        };
        if (wholeRow && (row.empty() || planeAlone(row))) return;
        if (wholeRow) candidates = row;
        candidates.reserve(row.size());
        for (int i = 0; i < resolution; ++i) {
            if (!wholeRow) {
                candidates.clear();
                for (const int k : row) {
                    const TexelRect& t = rects[static_cast<size_t>(k)];
                    if (t.lo.x <= i && i <= t.hi.x) candidates.push_back(k);
                }
            }
            if (candidates.empty() || planeAlone(candidates)) continue;
            const Ray ray{shd::sunShadowTexelRayOrigin(map.fit, i, j), dir};
            const GeometrySet::Nearest first = geometry.nearest(ray, tMax, 0.0f, candidates);
            if (first.index < 0) continue;
            // The second surface: where the ray leaves the first solid (shared/sun_shadow.h).
            const GeometrySet::Nearest second = geometry.nearest(ray, tMax, first.t + kSecondDepthGap, candidates);
            if (second.index < 0) continue;
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
