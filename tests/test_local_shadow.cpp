// Point and spot light shadow maps of the froxel renderers (shaders/shared/local_shadow.h,
// core/local_shadow.cpp): the maps against exact ray occlusion, a point light's shadow on the ground
// and a spot's shaft against the reference, the per-light cache.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/froxel_frame.h"
#include "core/geometry.h"
#include "core/local_shadow.h"
#include "core/render.h"
#include "shaft_scenes.h"
#include "test_support.h"

using namespace brume;

namespace {

Geometry box(glm::vec3 center, glm::vec3 size) {
    Geometry g;
    g.type = GeometryType::Box;
    g.transform.translation = center;
    g.transform.scale = size;
    g.albedo = glm::vec3(0.4f);
    return g;
}

Light pointLight(glm::vec3 position, float intensity) {
    Light l = makeLight(LightType::Point);
    l.position = position;
    l.intensity = intensity;
    l.shadows = true;
    return l;
}

// A box floating 1 m over the ground, a point light 2 m above it, thin haze: the box's shadow on the
// ground, seen from the side and above so that most of it is in view.
Scene pointOverBox() {
    Scene s = test::sceneWithTestView();
    s.camera.position = {0.0f, 4.0f, 7.0f};
    s.camera.target = {0.0f, 0.0f, 0.0f};
    s.camera.far = 40.0f;
    s.froxels.far = 30.0f;
    s.lights = {pointLight({0.4f, 3.6f, 0.2f}, 40.0f)};
    Volume haze;
    haze.type = VolumeType::Height;
    haze.base_height = 0.0f;
    haze.falloff = 0.5f;
    haze.medium.scattering = glm::vec3(0.04f);
    s.volumes = {haze};
    s.geometry = {test::groundPlane(glm::vec3(0.6f)), box({0.0f, 1.3f, 0.0f}, {1.6f, 0.6f, 1.6f})};
    return s;
}

Scene spotShaft() { return test::spotShaftScene(); }

RenderRequest request(Quality q) {
    RenderRequest r;
    r.width = 160;
    r.height = 90;
    r.quality = q;
    r.threads = 2;
    return r;
}

// Deterministic points spread over [lo, hi].
glm::vec3 spread(int i, glm::vec3 lo, glm::vec3 hi) {
    const float a = std::fmod(static_cast<float>(i) * 0.6180339f, 1.0f);
    const float b = std::fmod(static_cast<float>(i) * 0.4142135f, 1.0f);
    const float c = std::fmod(static_cast<float>(i) * 0.7320508f, 1.0f);
    return lo + (hi - lo) * glm::vec3(a, b, c);
}

// Points at least four texels from any shadow edge must get the exact answer, 0 or 1.
void expectExactAwayFromEdges(const Scene& s, glm::vec3 lo, glm::vec3 hi, int minLit, int minShadowed) {
    const CompiledScene cs = compileScene(s);
    const GeometrySet geometry(s.geometry);
    const int n = localShadowMapResolution(Quality::High);
    const LocalShadowMaps maps = buildLocalShadowMaps(cs, geometry, n, 2);
    const shd::LightData& l = cs.lights[0];
    const glm::vec3 light(l.positionRange);
    int lit = 0, shadowed = 0;
    for (int i = 0; i < 4000; ++i) {
        const glm::vec3 p = spread(i, lo, hi);
        const float dist = glm::length(light - p);
        const glm::vec3 toLight = (light - p) / dist;
        if (shd::evalLight(l, p).irradiance.x <= 0.0f) continue;  // outside a spot's cone
        const bool exact = geometry.occluded(p, toLight, dist);
        const float texel = 2.0f * dist / static_cast<float>(n);
        bool nearEdge = false;
        for (glm::vec3 off : {glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0), glm::vec3(0, 0, 1), glm::vec3(0, 0, -1),
                              glm::vec3(0, 1, 0), glm::vec3(0, -1, 0)}) {
            const glm::vec3 q = p + off * 4.0f * texel;
            nearEdge = nearEdge || geometry.occluded(q, glm::normalize(light - q), glm::length(light - q)) != exact;
        }
        if (nearEdge) continue;
        EXPECT_EQ(localShadowVisibility(maps, l, p), exact ? 0.0f : 1.0f) << "at " << p.x << "," << p.y << "," << p.z;
        ++(exact ? shadowed : lit);
    }
    EXPECT_GT(lit, minLit);
    EXPECT_GT(shadowed, minShadowed);
}

// Sum of the red channel over the pixels of `mask`.
double maskedSum(const Image& img, const std::vector<bool>& mask) {
    double sum = 0.0;
    for (size_t i = 0; i < mask.size(); ++i)
        if (mask[i]) sum += img.pixels[i].x;
    return sum;
}

}  // namespace

// compileScene hands slots to point and spot lights with shadows only, in order.
TEST(LocalShadowMap, SlotsGoToShadowedPointAndSpotLights) {
    Scene s = pointOverBox();
    Light unshadowed = pointLight({1.0f, 2.0f, 0.0f}, 1.0f);
    unshadowed.shadows = false;
    Light sun = makeLight(LightType::Directional);
    sun.shadows = true;
    s.lights = {unshadowed, sun, pointLight({0.0f, 3.0f, 0.0f}, 1.0f), spotShaft().lights[0]};
    const CompiledScene cs = compileScene(s);
    EXPECT_EQ(cs.lights[0].kind.z, 0);
    EXPECT_EQ(cs.lights[1].kind.z, 0);
    EXPECT_EQ(cs.lights[2].kind.z, 1);
    EXPECT_EQ(cs.lights[3].kind.z, 2);
    EXPECT_EQ(localShadowSlots(cs), 2);
    EXPECT_EQ(shd::localShadowFaceCount(cs.lights[2]), 6);
    EXPECT_EQ(shd::localShadowFaceCount(cs.lights[3]), 1);
}

// A cube map (point light) and a perspective map (spot) against exact ray occlusion. A wrong face
// frame, an inverted depth test or a missing bias fails this.
TEST(LocalShadowMap, PointMapMatchesExactOcclusionAwayFromEdges) {
    // Points under the box (0.7 m below its underside at most) and around it, and above the light.
    expectExactAwayFromEdges(pointOverBox(), {-6.0f, 0.05f, -6.0f}, {6.0f, 0.7f, 6.0f}, 500, 100);
    expectExactAwayFromEdges(pointOverBox(), {-6.0f, 3.7f, -6.0f}, {6.0f, 6.0f, 6.0f}, 1000, -1);
}

TEST(LocalShadowMap, SpotMapMatchesExactOcclusionAwayFromEdges) {
    expectExactAwayFromEdges(spotShaft(), {-5.0f, 0.05f, -5.0f}, {5.0f, 3.5f, 5.0f}, 100, 500);
}

// A light with shadows: false is never shadowed by a map, even with a box between.
TEST(LocalShadowMap, UnshadowedLightStaysUnshadowed) {
    Scene s = pointOverBox();
    s.lights[0].shadows = false;
    const CompiledScene cs = compileScene(s);
    const LocalShadowMaps maps = buildLocalShadowMaps(cs, GeometrySet(s.geometry), 256, 2);
    EXPECT_TRUE(maps.depth.empty());
    EXPECT_EQ(localShadowVisibility(maps, cs.lights[0], glm::vec3(0.0f, 0.1f, 0.0f)), 1.0f);
}

// "A point light above a box over a ground plane: the ground's shadowed area within 5% of the
// reference at high". The shadowed area: pixels the reference's exact occlusion darkens by more than
// 30%. Without maps (shadows: false) the froxel renderer lights them fully: checked too, so the
// test cannot pass by being insensitive to the maps.
TEST(LocalShadowMap, PointLightShadowOnGroundWithinFivePercentOfTheReference) {
    const Scene scene = pointOverBox();
    const RenderRequest req = request(Quality::High);
    const Image ref = renderReference(scene, req);
    Scene noMap = scene;
    noMap.lights[0].shadows = false;
    const Image open = renderReference(noMap, req);
    std::vector<bool> mask(ref.pixels.size());
    int count = 0;
    for (size_t i = 0; i < mask.size(); ++i) count += (mask[i] = ref.pixels[i].x < 0.7f * open.pixels[i].x) ? 1 : 0;
    ASSERT_GT(count, 300);
    const Image froxel = renderFroxelCpu(scene, req).image;
    const Image froxelNoMap = renderFroxelCpu(noMap, req).image;
    const double refSum = maskedSum(ref, mask);
    const double err = std::abs(maskedSum(froxel, mask) - refSum) / refSum;
    const double errNoMap = std::abs(maskedSum(froxelNoMap, mask) - refSum) / refSum;
    std::printf("point light over box, high: shadowed area %d px, froxel vs reference %.4f (without the map %.3f); "
                "whole image %.4f\n",
                count, err, errNoMap, relativeMeanAbsError(froxel, ref));
    EXPECT_LT(err, 0.05);
    EXPECT_GT(errNoMap, 1.0);
}

// "A spot through a gap into fog (shaft visible)": the whole image against the reference at high,
// and far off without the map (the whole cone under the roof lit).
TEST(LocalShadowMap, SpotShaftHighMatchesTheReference) {
    const Scene scene = spotShaft();
    const RenderRequest req = request(Quality::High);
    const Image ref = renderReference(scene, req);
    const double err = relativeMeanAbsError(renderFroxelCpu(scene, req).image, ref);
    Scene noMap = scene;
    noMap.lights[0].shadows = false;
    const double errNoMap = relativeMeanAbsError(renderFroxelCpu(noMap, req).image, ref);
    std::printf("spot shaft, high: relative mean abs error %.4f (without the map %.4f)\n", err, errNoMap);
    EXPECT_LT(err, 0.05);
    EXPECT_GT(errNoMap, 0.3);
}

// The cache: the same inputs, or an intensity change, reuse the maps; moving one light rebuilds
// that light's alone; moving a box rebuilds all; every rebuilt array equals a fresh build.
TEST(LocalShadowMap, CacheRebuildsOnlyWhatChanged) {
    Scene s = pointOverBox();
    s.lights.push_back(spotShaft().lights[0]);
    LocalShadowCache cache;
    const int n = 64;
    auto fresh = [&](const Scene& sc) { return buildLocalShadowMaps(compileScene(sc), GeometrySet(sc.geometry), n, 2).depth; };
    cache.get(compileScene(s), s.geometry, n, 2);
    EXPECT_EQ(cache.builds(), 2);
    s.lights[0].intensity *= 2.0f;
    s.lights[1].range = 3.0f;
    cache.get(compileScene(s), s.geometry, n, 2);
    EXPECT_EQ(cache.builds(), 2);
    s.lights[1].position.x += 0.5f;
    EXPECT_EQ(cache.get(compileScene(s), s.geometry, n, 2).depth, fresh(s));
    EXPECT_EQ(cache.builds(), 3);
    s.geometry[1].transform.translation.x += 1.0f;
    EXPECT_EQ(cache.get(compileScene(s), s.geometry, n, 2).depth, fresh(s));
    EXPECT_EQ(cache.builds(), 5);
    s.lights[0].shadows = false;
    EXPECT_EQ(cache.get(compileScene(s), s.geometry, n, 2).depth, fresh(s));
}

// Degenerate lookups stay finite and in [0, 1]: the light's own position, points a hair off it or
// 1e6 m away, and spots from a 0-degree to a 179-degree cone (the cube past 60 degrees).
TEST(LocalShadowMap, ExtremeLookupsStayInZeroOne) {
    Scene s = pointOverBox();
    for (float outer : {0.0f, 1.0f, 59.9f, 60.1f, 179.0f}) {
        Light spot = spotShaft().lights[0];
        spot.outer_deg = outer;
        spot.inner_deg = 0.0f;
        s.lights.push_back(spot);
    }
    const CompiledScene cs = compileScene(s);
    const LocalShadowMaps maps = buildLocalShadowMaps(cs, GeometrySet(s.geometry), 16, 2);
    for (const shd::LightData& l : cs.lights) {
        const glm::vec3 at(l.positionRange);
        for (glm::vec3 off : {glm::vec3(0.0f), glm::vec3(1e-30f, 0.0f, 0.0f), glm::vec3(0.0f, -1e-7f, 0.0f),
                              glm::vec3(3e-8f, -1e-6f, 2e-8f), glm::vec3(1e6f, -1e6f, 1.0f), glm::vec3(0.0f, -5.0f, 0.0f)}) {
            const float v = localShadowVisibility(maps, l, at + off);
            EXPECT_TRUE(v >= 0.0f && v <= 1.0f) << v;
        }
    }
}
