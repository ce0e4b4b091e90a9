#include "local_shadow.h"

#include <algorithm>

#include "parallel.h"

namespace brume {
namespace {

// Past the first hit before looking for the second [m]: far below any solid's thickness, above
// float resolution at the distances a local light lights (1e-3 m is 1 ulp at ~8 km).
constexpr float kSecondDepthGap = 1.0e-3f;
// Texel rays end here [m]: beyond any range a local light is given in practice.
constexpr float kRayMax = 1.0e5f;

size_t slotSize(int n) {
    return static_cast<size_t>(shd::LOCAL_SHADOW_FACES) * static_cast<size_t>(n) * static_cast<size_t>(n);
}

// The inputs of light l's map: a change of anything else (intensity, range, fog_scale) keeps it.
bool sameMapInputs(const shd::LightData& a, const shd::LightData& b) {
    return a.kind == b.kind && glm::vec3(a.positionRange) == glm::vec3(b.positionRange) &&
           a.direction == b.direction && a.spot.x == b.spot.x;
}

}  // namespace

// docs/shadows.md: 256 texels per cube face is ~0.4 degree, 2 cm at 3 m from the light.
int localShadowMapResolution(Quality q) {
    switch (q) {
        case Quality::Low: return 128;
        case Quality::Medium: return 256;
        case Quality::High: return 256;
        case Quality::Ultra: return 512;
    }
    return 256;
}

int localShadowSlots(const CompiledScene& cs) {
    int slots = 0;
    for (const shd::LightData& l : cs.lights) slots = std::max(slots, shd::lightShadowSlot(l) + 1);
    return slots;
}

void buildLocalShadowMap(const shd::LightData& light, const GeometrySet& geometry, LocalShadowMaps& maps,
                         int threads) {
    const int n = maps.resolution;
    const int faces = shd::localShadowFaceCount(light);
    const glm::vec3 origin(light.positionRange);
    const size_t base = static_cast<size_t>(shd::lightShadowSlot(light)) * slotSize(n);
    parallelFor(faces * n, threads, [&](int row) {
        const int f = row / n, j = row % n;
        const shd::LocalShadowFace face = shd::localShadowFace(light, f);
        float* out = maps.depth.data() + base + static_cast<size_t>(f * n + j) * static_cast<size_t>(n);
        for (int i = 0; i < n; ++i) {
            const Ray ray{origin, shd::localShadowTexelDir(face, i, j, n)};
            float second = shd::BRUME_HUGE;
            const SurfaceHit first = geometry.intersect(ray, kRayMax);
            if (first.hit()) {
                // The second surface: where the ray leaves the first solid (shared/local_shadow.h).
                const SurfaceHit exit = geometry.intersect(ray, kRayMax, first.t + kSecondDepthGap);
                if (exit.hit()) second = exit.t;
            }
            out[i] = second;
        }
    });
}

LocalShadowMaps buildLocalShadowMaps(const CompiledScene& cs, const GeometrySet& geometry, int resolution,
                                     int threads) {
    LocalShadowMaps maps;
    const int slots = localShadowSlots(cs);
    if (resolution <= 0 || slots == 0) return maps;
    maps.resolution = resolution;
    maps.depth.assign(static_cast<size_t>(slots) * slotSize(resolution), shd::BRUME_HUGE);
    for (const shd::LightData& l : cs.lights)
        if (shd::localShadowMapped(l, resolution)) buildLocalShadowMap(l, geometry, maps, threads);
    return maps;
}

const LocalShadowMaps& LocalShadowCache::get(const CompiledScene& cs, const std::vector<Geometry>& geometry,
                                             int resolution, int threads) {
    const int slots = resolution > 0 ? localShadowSlots(cs) : 0;
    const bool resized = slots != static_cast<int>(lights_.size()) || resolution != maps_.resolution ||
                         !(geometry == geometry_);
    if (resized) {
        maps_ = LocalShadowMaps{};
        lights_.assign(static_cast<size_t>(slots), shd::LightData{});
        geometry_ = geometry;
        if (slots > 0) {
            maps_.resolution = resolution;
            maps_.depth.assign(static_cast<size_t>(slots) * slotSize(resolution), shd::BRUME_HUGE);
        }
    }
    const GeometrySet set(geometry);
    for (const shd::LightData& l : cs.lights) {
        if (!shd::localShadowMapped(l, resolution)) continue;
        shd::LightData& kept = lights_[static_cast<size_t>(shd::lightShadowSlot(l))];
        if (!resized && sameMapInputs(kept, l)) continue;
        std::fill_n(maps_.depth.begin() + static_cast<std::ptrdiff_t>(static_cast<size_t>(shd::lightShadowSlot(l)) * slotSize(resolution)),
                    slotSize(resolution), shd::BRUME_HUGE);
        buildLocalShadowMap(l, set, maps_, threads);
        kept = l;
        ++builds_;
    }
    return maps_;
}

float localShadowVisibility(const LocalShadowMaps& maps, const shd::LightData& l, glm::vec3 p) {
    const int n = maps.resolution;
    if (!shd::localShadowMapped(l, n) || maps.depth.empty()) return 1.0f;
    const shd::LocalShadowLookup k = shd::localShadowLookup(l, n, p);
    if (!k.inside) return 1.0f;
    auto at = [&](int dx, int dy) { return maps.depth[static_cast<size_t>(shd::localShadowIndex(k, n, glm::ivec2(dx, dy)))]; };
    return shd::localShadowPcf(k, at(0, 0), at(1, 0), at(0, 1), at(1, 1));
}

}  // namespace brume
