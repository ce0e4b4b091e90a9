// The frame's light reach (core/light_reach.h): the surface-light list holds every light that can
// light a point of the view frustum and leaves out those that cannot; the transmittance volume's
// layers are computed for the lights that touch something only; neither changes the image.
#include <gtest/gtest.h>

#include "test_support.h"

#include <algorithm>
#include <cmath>

#include "core/light_reach.h"
#include "core/render.h"
#include "core/shadows.h"
#include "shaders/shared/glow.h"

using namespace brume;
using glm::vec3;

namespace {

Light point(vec3 p, float range) { return test::pointLight(p, range, 20.0f); }

// Camera at z = 6 looking toward -z over a floor in height fog; lights in view, beside it, behind
// it and past its far plane, one for surfaces only (fog_scale 0) and one dark.
Scene reachScene() {
    Scene s = test::heightFogView(20.0f, 0.5f, {0.2f, 0.2f, 0.25f});
    Geometry floor;
    floor.type = GeometryType::Plane;
    floor.albedo = vec3(0.5f);
    s.geometry = {floor};
    Light sun = makeLight(LightType::Directional);
    sun.direction = glm::normalize(vec3(0.3f, -1.0f, -0.4f));
    s.lights = {sun,
                point({-2.0f, 0.5f, 0.0f}, 1.5f),
                point({0.0f, 1.0f, 14.0f}, 2.0f),    // 2: behind the camera
                point({60.0f, 1.0f, -5.0f}, 4.0f),   // 3: far to the side
                point({0.0f, 1.0f, -30.0f}, 3.0f),   // 4: in view past the froxel far: surfaces only
                point({0.0f, 1.0f, -60.0f}, 4.0f),   // 5: past the camera far
                point({1.0f, 0.5f, -2.0f}, 3.0f),    // 6: fog_scale 0
                point({-1.0f, 0.5f, -2.0f}, 3.0f),   // 7: dark
                point({0.0f, 1.5f, 7.2f}, 2.0f)};    // 8: behind the camera, its range poking in
    s.lights[6].fog_scale = 0.0f;
    s.lights[7].intensity = 0.0f;
    return s;
}

RenderRequest smallRequest() {
    RenderRequest r;
    r.width = 160;
    r.height = 90;
    r.threads = 2;
    return r;
}

shd::FrameUniforms frameOf(const Scene& s, const CompiledScene& cs) {
    shd::FrameUniforms f = makeFrameUniforms(s, cs, 160, 90, resolveFroxelSettings(s, Quality::High));
    applyShadowSettings(f, smallRequest());
    return f;
}

bool contains(const std::vector<int>& v, int i) { return std::find(v.begin(), v.end(), i) != v.end(); }

}  // namespace

// Exact where it matters: at points spread through the whole view frustum (pixels x view depths from
// the camera near to far), every light that lights one of them is a surface light. Tight: the
// lights behind, beside and past the far plane, and the dark one, are not; the one behind the camera
// whose range pokes into the frustum is.
TEST(LightReach, SurfaceLightsAreEveryLightThatLightsTheFrustum) {
    const Scene s = reachScene();
    const CompiledScene cs = compileScene(s);
    const shd::FrameUniforms frame = frameOf(s, cs);
    const LightReach reach = buildLightReach(cs, frame, buildLightClusters(cs, frame));
    for (int absent : {2, 3, 5, 7}) EXPECT_FALSE(contains(reach.surfaceLights, absent)) << "light " << absent;
    for (int present : {0, 1, 4, 6, 8}) EXPECT_TRUE(contains(reach.surfaceLights, present)) << "light " << present;
    int lit = 0;
    for (int py = 0; py <= 90; py += 3)
        for (int px = 0; px <= 160; px += 4)
            for (int d = 0; d <= 64; ++d) {
                const float near = frame.projection.z, far = frame.projection.w;
                const float depth = near * std::pow(far / near, static_cast<float>(d) / 64.0f);
                const vec3 ray = shd::viewRayFromPixel(glm::vec2(px, py), frame);  // z = -1
                const vec3 p = vec3(frame.worldFromView * glm::vec4(ray * depth, 1.0f));
                for (size_t i = 0; i < cs.lights.size(); ++i) {
                    if (shd::evalLight(cs.lights[i], p).irradiance == vec3(0.0f)) continue;
                    ++lit;
                    EXPECT_TRUE(contains(reach.surfaceLights, static_cast<int>(i)))
                        << "light " << i << " lights " << p.x << "," << p.y << "," << p.z;
                }
            }
    EXPECT_GT(lit, 1000);
}

// Layers of the transmittance volume: the sun's, the fog lights' in reach and the surface-only light
// in view inside the froxel grid; not the lights out of reach, the dark one, nor the one that only
// lights surfaces past the froxel far.
TEST(LightReach, ShadowVolumeLayersOnlyForLightsThatTouchSomething) {
    const Scene s = reachScene();
    const CompiledScene cs = compileScene(s);
    const shd::FrameUniforms frame = frameOf(s, cs);
    const LightReach reach = buildLightReach(cs, frame, buildLightClusters(cs, frame));
    EXPECT_EQ(reach.shadowVolume, (std::vector<int>{1, 1, 0, 0, 0, 0, 1, 0, 1}));
    const LightReach all = buildLightReach(cs, frame, buildLightClusters(cs, frame, false), /*culling=*/false);
    EXPECT_EQ(all.shadowVolume, std::vector<int>(cs.lights.size(), 1));
    EXPECT_EQ(all.surfaceLights.size(), cs.lights.size());
    // Without surfaces only the light pass reads layers: not the surface-only light in view (6).
    const LightReach fogOnly = buildLightReach(cs, frame, buildLightClusters(cs, frame), true, /*surfaces=*/false);
    EXPECT_EQ(fogOnly.shadowVolume, (std::vector<int>{1, 1, 0, 0, 0, 0, 0, 0, 1}));
    // The light pass reads the clusters of the froxels it runs only (the GPU's media region): none
    // of them, no layer; all of them, the layers above.
    const LightClusters clusters = buildLightClusters(cs, frame);
    const FroxelRegion none{}, grid{glm::ivec3(0), glm::ivec3(frame.froxelDims)};
    EXPECT_EQ(buildLightReach(cs, frame, clusters, true, false, &none).shadowVolume, std::vector<int>(cs.lights.size(), 0));
    EXPECT_EQ(buildLightReach(cs, frame, clusters, true, true, &grid).shadowVolume, reach.shadowVolume);
}

// Each light's listed froxels (the shadow volume pass's per-layer region): the box of exactly the
// froxels of the given region whose cluster lists the light, found here froxel by froxel; the sun's is
// the whole region, a local light's a small part of it, a light no cluster lists has none; an
// over-full cluster counts for every light.
TEST(LightReach, ListedFroxelRegionsBoundTheFroxelsWhoseClustersListEachLight) {
    const Scene s = reachScene();
    const CompiledScene cs = compileScene(s);
    const shd::FrameUniforms frame = frameOf(s, cs);
    const LightClusters clusters = buildLightClusters(cs, frame);
    const glm::ivec3 dims(frame.froxelDims);
    for (const FroxelRegion& froxels : {FroxelRegion{glm::ivec3(0), dims}, FroxelRegion{glm::ivec3(3, 2, 5), dims - 4}}) {
        const std::vector<FroxelRegion> listed = listedFroxelRegions(clusters, cs.lights.size(), froxels);
        ASSERT_EQ(listed.size(), cs.lights.size());
        std::vector<glm::ivec3> lo(cs.lights.size(), dims), hi(cs.lights.size(), glm::ivec3(0));
        for (int z = froxels.lo.z; z < froxels.hi.z; ++z)
            for (int y = froxels.lo.y; y < froxels.hi.y; ++y)
                for (int x = froxels.lo.x; x < froxels.hi.x; ++x) {
                    const int r = shd::clusterRecord(glm::ivec3(x, y, z), dims);
                    for (int k = 0; k < clusters.records[static_cast<size_t>(r)]; ++k) {
                        const size_t i = static_cast<size_t>(clusters.records[static_cast<size_t>(r + 1 + k)]);
                        lo[i] = glm::min(lo[i], glm::ivec3(x, y, z));
                        hi[i] = glm::max(hi[i], glm::ivec3(x, y, z) + 1);
                    }
                }
        for (size_t i = 0; i < cs.lights.size(); ++i) {
            if (glm::any(glm::lessThanEqual(hi[i], lo[i]))) {
                EXPECT_TRUE(listed[i].empty()) << "light " << i;
                continue;
            }
            EXPECT_EQ(listed[i].lo, lo[i]) << "light " << i;
            EXPECT_EQ(listed[i].hi, hi[i]) << "light " << i;
        }
        EXPECT_EQ(listed[0].lo, froxels.lo);  // the sun: every cluster
        EXPECT_EQ(listed[0].hi, froxels.hi);
        EXPECT_FALSE(listed[1].empty());
        EXPECT_LT(listed[1].froxels() * 2, froxels.froxels());
        EXPECT_TRUE(listed[3].empty());  // far to the side
    }
    // Over-full clusters list every light: each light's region is then the whole one.
    LightClusters full = clusters;
    for (size_t r = 0; r < full.records.size(); r += shd::CLUSTER_STRIDE) full.records[r] = shd::CLUSTER_ALL_LIGHTS;
    const FroxelRegion grid{glm::ivec3(0), dims};
    for (const FroxelRegion& r : listedFroxelRegions(full, cs.lights.size(), grid)) {
        EXPECT_EQ(r.lo, grid.lo);
        EXPECT_EQ(r.hi, grid.hi);
    }
    EXPECT_TRUE(listedFroxelRegions(clusters, cs.lights.size(), FroxelRegion{})[0].empty());
}

// Skipped layers are never read: the CPU image and source are the unculled ones, bit for bit, with
// the fog's shadow on the floor and in the fog (high: point lights too).
TEST(LightReach, CulledImageEqualsUnculled) {
    const Scene s = reachScene();
    RenderRequest r = smallRequest();
    const FroxelResult culled = renderFroxelCpu(s, r);
    r.lightCulling = false;
    const FroxelResult all = renderFroxelCpu(s, r);
    EXPECT_EQ(culled.volumes.source, all.volumes.source);
    EXPECT_EQ(culled.image.pixels, all.image.pixels);
}

// A light that reaches no volume's bounds touches no media: the light pass never reads its layer,
// even where a cluster lists it (a small box, lights in view that cannot reach it, no geometry).
TEST(LightReach, NoLayerForLightsThatReachNoMedia) {
    Scene s = test::sceneWithTestView();
    s.volumes = {test::boxFog({0.0f, 1.0f, 0.0f}, {1.0f, 1.0f, 1.0f}, 0.1f, 0.5f, 0.0f)};
    s.lights = {point({0.6f, 1.0f, 0.0f}, 1.0f), point({-2.5f, 1.0f, 0.0f}, 0.3f)};
    const CompiledScene cs = compileScene(s);
    const shd::FrameUniforms frame = frameOf(s, cs);
    const LightClusters clusters = buildLightClusters(cs, frame);
    EXPECT_EQ(buildLightReach(cs, frame, clusters, true, /*surfaces=*/false).shadowVolume, (std::vector<int>{1, 0}));
}

// The glow pass is dispatched over the glowing lights only (shared/glow.h, gpu/pass_glow.cpp), so that
// lights that reach no fog cost nothing: with a box as the only volume, the point light inside
// it glows, the one whose range stops short of it does not, nor the sun (no glow radius); without
// culling every light with a glow radius is listed. The GPU's record carries the surface lights only:
// the glow pass is dispatched per listed light by the host.
TEST(LightReach, GlowOnlyForLightsWhoseRangeReachesAVolume) {
    Scene s = reachScene();
    s.volumes = {test::boxFog({-2.0f, 0.5f, 0.0f}, vec3(1.0f), 0.1f, 0.2f, 0.05f)};
    s.lights = {s.lights[0], point({-2.0f, 0.5f, 0.0f}, 1.5f), point({2.0f, 0.5f, -2.0f}, 1.0f)};
    const CompiledScene cs = compileScene(s);
    const shd::FrameUniforms frame = frameOf(s, cs);
    ASSERT_GT(shd::lightGlowRadius(cs.lights[1], frame), 0.0f);
    ASSERT_GT(shd::lightGlowRadius(cs.lights[2], frame), 0.0f);
    const LightClusters clusters = buildLightClusters(cs, frame);
    const LightReach reach = buildLightReach(cs, frame, clusters);
    EXPECT_EQ(reach.glowLights, (std::vector<int>{1}));
    EXPECT_EQ(buildLightReach(cs, frame, clusters, /*culling=*/false).glowLights, (std::vector<int>{1, 2}));
    const std::vector<int> record = lightReachRecord(reach, cs.lights.size());
    ASSERT_EQ(record.size(), 1 + cs.lights.size());
    ASSERT_EQ(record[0], static_cast<int>(reach.surfaceLights.size()));
    for (size_t k = 0; k < reach.surfaceLights.size(); ++k) EXPECT_EQ(record[1 + k], reach.surfaceLights[k]);
}
