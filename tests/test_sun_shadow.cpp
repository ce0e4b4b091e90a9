// The sun shadow map of the froxel renderers (shaders/shared/sun_shadow.h, core/sun_shadow.cpp):
// the map's occlusion against exact ray queries, and the light-shaft scene against the reference.
#include <gtest/gtest.h>

#include "core/froxel_frame.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <cstdio>

#include "core/geometry.h"
#include "core/render.h"
#include "core/sun_shadow.h"
#include "shaft_scenes.h"

using namespace brume;

namespace {

Scene shaftScene(float gap = 2.5f) { return test::sunShaftScene(gap); }

RenderRequest request(Quality q) {
    RenderRequest r;
    r.width = 160;
    r.height = 90;
    r.quality = q;
    r.threads = 2;
    return r;
}

}  // namespace

// The map's visibility is exact ray occlusion away from shadow edges: at scattered points in the
// froxel range, those at least four texels from any edge (the map's and the exact answer
// agree on all texels in the PCF footprint) must agree with GeometrySet::occluded. A map ray cast
// with the wrong fit, an inverted depth test or a missing bias fails this.
TEST(SunShadowMap, MatchesExactOcclusionAwayFromEdges) {
    const Scene s = shaftScene();
    const CompiledScene cs = compileScene(s);
    const GeometrySet geometry(s.geometry);
    const FroxelSettings fs = resolveFroxelSettings(s, Quality::High);
    shd::FrameUniforms frame = makeFrameUniforms(s, cs, 160, 90, fs, glm::vec3(0.5f));
    applySunShadowSettings(frame, cs);
    ASSERT_EQ(frame.sunShadowLight, 1);
    const int n = sunShadowMapResolution(Quality::High);
    const SunShadowMap map = buildSunShadowMap(cs, geometry, frame, n, 2);
    const glm::vec3 toSun = -glm::vec3(cs.lights[0].direction);
    const float texel = 2.0f * map.fit.centerRadius.w / static_cast<float>(n);
    int lit = 0, shadowed = 0;
    for (int i = 0; i < 4000; ++i) {
        // A deterministic spread over the space under and around the roof.
        const float a = std::fmod(static_cast<float>(i) * 0.6180339f, 1.0f);
        const float b = std::fmod(static_cast<float>(i) * 0.4142135f, 1.0f);
        const float c = std::fmod(static_cast<float>(i) * 0.7320508f, 1.0f);
        // Up to 0.3 m (6 texels) under the roof: closer than ~2 texels behind a solid's back face the
        // bias lights a point on purpose (shared/sun_shadow.h).
        const glm::vec3 p(-8.0f + 16.0f * a, 0.05f + 3.45f * b, -8.0f + 16.0f * c);
        const bool exact = geometry.occluded(p, toSun, 1.0e4f);
        // Skip points near an edge: the same answer must hold a few texels to either side.
        bool nearEdge = false;
        for (glm::vec3 off : {glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0)})
            nearEdge = nearEdge || geometry.occluded(p + off * 4.0f * texel, toSun, 1.0e4f) != exact;
        if (nearEdge) continue;
        const float vis = sunShadowVisibility(map, frame, 0, p);
        EXPECT_EQ(vis, exact ? 0.0f : 1.0f) << "at " << p.x << "," << p.y << "," << p.z;
        ++(exact ? shadowed : lit);
    }
    EXPECT_GT(lit, 100);
    EXPECT_GT(shadowed, 1000);
}

// "A shaft scene (sun through a gap between boxes into height fog) within 3% at high". Without the
// shadow map the froxel renderer lights all the fog under the roof, far more than 3% off (checked
// too, so the scene cannot pass by being insensitive to shadows).
TEST(SunShadowMap, ShaftSceneHighWithinThreePercentOfTheReference) {
    const Scene scene = shaftScene();
    const RenderRequest req = request(Quality::High);
    const Image ref = renderReference(scene, req);
    const double err = relativeMeanAbsError(renderFroxelCpu(scene, req).image, ref);
    Scene noMap = scene;
    noMap.lights[0].shadows = false;  // the froxel renderers then ignore geometry occlusion
    const double errNoMap = relativeMeanAbsError(renderFroxelCpu(noMap, req).image, ref);
    std::printf("shaft scene, high: relative mean abs error %.4f (without the shadow map %.4f)\n", err, errNoMap);
    // 1.84% measured; 2.69% when the froxels read the surfaces' second-depth layer.
    EXPECT_LT(err, 0.022);
    EXPECT_GT(errNoMap, 0.2);
}

// The same with a 1.5 m gap: the shaft spans about two of high's froxel columns at 160x90, so the
// froxel footprint leaves less margin (docs/shadows.md, "Shaft error": 2.94% measured; 4.36% with
// the fog inside the slabs lit, which the froxels straddling the roof's underside showed).
TEST(SunShadowMap, NarrowShaftHighWithinThreePercentOfTheReference) {
    const Scene scene = shaftScene(1.5f);
    const RenderRequest req = request(Quality::High);
    const double err = relativeMeanAbsError(renderFroxelCpu(scene, req).image, renderReference(scene, req));
    std::printf("narrow shaft, high: relative mean abs error %.4f\n", err);
    EXPECT_LT(err, 0.03);
}

// The froxels' layer: fog inside a solid (never seen) is shadowed, so froxels straddling the roof
// do not carry its light into the pixels looking up at it; surfaces keep the second-depth layer (a
// point at the roof's sunlit top stays lit); fog in the shaft, above the roof and at the sunlit
// ground (a plane: second-depth in both layers) stays lit.
TEST(SunShadowMap, FroxelLayerShadowsFogInsideSolidsOnly) {
    const Scene s = shaftScene();
    const CompiledScene cs = compileScene(s);
    shd::FrameUniforms frame = makeFrameUniforms(s, cs, 160, 90, resolveFroxelSettings(s, Quality::High), glm::vec3(0.5f));
    applySunShadowSettings(frame, cs);
    const SunShadowMap map = buildSunShadowMap(cs, GeometrySet(s.geometry), frame, sunShadowMapResolution(Quality::High), 2);
    const glm::vec3 insideRoof(0.0f, 4.05f, -5.0f), inShaft(0.0f, 2.0f, 0.55f), aboveRoof(0.0f, 4.5f, -5.0f),
        atGround(0.0f, 0.01f, 1.3f), underRoof(0.0f, 2.0f, -5.0f);
    EXPECT_EQ(sunShadowFroxelVisibility(map, frame, 0, insideRoof), 0.0f);
    EXPECT_EQ(sunShadowVisibility(map, frame, 0, insideRoof), 1.0f);
    for (glm::vec3 p : {inShaft, aboveRoof, atGround}) {
        EXPECT_EQ(sunShadowFroxelVisibility(map, frame, 0, p), 1.0f) << p.y << " " << p.z;
        EXPECT_EQ(sunShadowVisibility(map, frame, 0, p), 1.0f) << p.y << " " << p.z;
    }
    EXPECT_EQ(sunShadowFroxelVisibility(map, frame, 0, underRoof), 0.0f);
    EXPECT_EQ(sunShadowVisibility(map, frame, 0, underRoof), 0.0f);
}

// The cache the GPU renderer keeps: the same inputs reuse the map; moving a box or the camera
// rebuilds it, and the rebuilt map equals a fresh build (a stale map would shadow the old place).
TEST(SunShadowMap, CacheRebuildsExactlyWhenGeometryOrFitChange) {
    Scene s = shaftScene();
    const CompiledScene cs = compileScene(s);
    auto frameOf = [&](const Scene& sc) {
        shd::FrameUniforms f = makeFrameUniforms(sc, cs, 64, 36, resolveFroxelSettings(sc, Quality::Low), glm::vec3(0.5f));
        applySunShadowSettings(f, cs);
        return f;
    };
    SunShadowCache cache;
    const int n = 128;
    cache.get(cs, s.geometry, frameOf(s), n, 2);
    cache.get(cs, s.geometry, frameOf(s), n, 2);
    EXPECT_EQ(cache.builds(), 1);
    s.geometry[1].transform.translation.x += 3.0f;
    const std::vector<float> moved = cache.get(cs, s.geometry, frameOf(s), n, 2).depth;
    EXPECT_EQ(cache.builds(), 2);
    EXPECT_EQ(moved, buildSunShadowMap(cs, GeometrySet(s.geometry), frameOf(s), n, 2).depth);
    s.camera.position.x += 1.0f;
    cache.get(cs, s.geometry, frameOf(s), n, 2);
    EXPECT_EQ(cache.builds(), 3);
    cache.get(cs, s.geometry, frameOf(s), n * 2, 2);
    EXPECT_EQ(cache.builds(), 4);
    // Two maps are kept: going back and forth between two resolutions (the editor's coarse frames
    // and its frames at rest) builds each once, and each returned map equals a fresh build.
    for (int k = 0; k < 3; ++k) {
        for (const int res : {n, n * 2}) {
            const SunShadowMap& m = cache.get(cs, s.geometry, frameOf(s), res, 2);
            EXPECT_EQ(m.depth, buildSunShadowMap(cs, GeometrySet(s.geometry), frameOf(s), res, 2).depth) << res;
        }
    }
    EXPECT_EQ(cache.builds(), 4);
    // A third input evicts the older one.
    cache.get(cs, s.geometry, frameOf(s), n / 2, 2);
    EXPECT_EQ(cache.builds(), 5);
    cache.get(cs, s.geometry, frameOf(s), n * 2, 2);
    EXPECT_EQ(cache.builds(), 5);
    cache.get(cs, s.geometry, frameOf(s), n, 2);
    EXPECT_EQ(cache.builds(), 6);
}

// The CPU froxel renderer keeps the map across the frames of a temporal sequence (the jitter does
// not move the fit): --frames N pays the ray cast once; moving a box rebuilds it, and the image of
// a cached frame equals a fresh render's.
TEST(SunShadowMap, CpuFrameSequenceBuildsTheMapOnce) {
    Scene scene = shaftScene();
    RenderRequest req;
    req.width = 64;
    req.height = 36;
    req.quality = Quality::Low;
    req.threads = 2;
    CpuHistory history;
    for (int n = 0; n < 4; ++n) {
        renderFroxelFrameCpu(scene, req, history);
        req.history = HistoryMode::Continue;
    }
    EXPECT_EQ(history.sunShadow.builds(), 1);
    // The same history without a cached map: its next frame must equal the cached renderer's.
    CpuHistory fresh;
    fresh.state = history.state;
    fresh.pair = history.pair;
    const Image cached = renderFroxelFrameCpu(scene, req, history).image;
    EXPECT_EQ(history.sunShadow.builds(), 1);
    EXPECT_EQ(relativeMeanAbsError(renderFroxelFrameCpu(scene, req, fresh).image, cached), 0.0);
    scene.geometry[1].transform.translation.x += 0.5f;
    renderFroxelFrameCpu(scene, req, history);
    EXPECT_EQ(history.sunShadow.builds(), 2);
}

// The map's ray cast tests each texel's rays against the primitives whose bounds project onto that
// texel only (core/sun_shadow.cpp primitiveTexels): the map must equal the one that tests every
// primitive, bit for bit. Random scenes of rotated and scaled boxes and spheres, some straddling the
// map's edge or off it, small ones (a texel or less), two planes, under suns from several directions
// and at several map resolutions; a cut that missed part of a primitive's footprint changes texels.
TEST(SunShadowMap, FootprintCullingBuildsTheSameMapAsTestingEveryPrimitive) {
    uint32_t seed = 12345u;
    auto rnd = [&](float lo, float hi) {
        seed = seed * 1664525u + 1013904223u;
        return lo + (hi - lo) * static_cast<float>(seed >> 8) / static_cast<float>(1u << 24);
    };
    int solidTexels = 0;
    for (int scene = 0; scene < 12; ++scene) {
        Scene s = shaftScene();
        const float far = rnd(6.0f, 40.0f);
        s.froxels.far = far;
        s.lights[0].direction = glm::normalize(glm::vec3(rnd(-1.0f, 1.0f), rnd(-1.0f, -0.2f), rnd(-1.0f, 1.0f)));
        s.geometry.resize(1);  // the ground
        if (scene % 3 == 0) {
            Geometry raised = s.geometry[0];
            raised.height = rnd(-3.0f, -0.5f);
            s.geometry.push_back(raised);
        }
        for (int k = 0; k < 14; ++k) {
            Geometry g;
            g.type = k % 3 == 0 ? GeometryType::Sphere : GeometryType::Box;
            const glm::vec3 at(rnd(-1.5f, 1.5f) * far, rnd(0.0f, 6.0f), rnd(-1.5f, 1.5f) * far);
            const float size = k % 5 == 0 ? rnd(0.005f, 0.05f) : rnd(0.2f, 6.0f);
            g.center = at;
            g.radius = size;
            g.transform.translation = at;
            g.transform.scale = glm::vec3(size * rnd(0.2f, 3.0f), size * rnd(0.2f, 3.0f), size * rnd(0.2f, 3.0f));
            g.transform.rotation_deg = glm::vec3(rnd(-180.0f, 180.0f), rnd(-180.0f, 180.0f), rnd(-180.0f, 180.0f));
            s.geometry.push_back(g);
        }
        const CompiledScene cs = compileScene(s);
        shd::FrameUniforms frame = makeFrameUniforms(s, cs, 64, 36, resolveFroxelSettings(s, Quality::Low), glm::vec3(0.5f));
        applySunShadowSettings(frame, cs);
        ASSERT_EQ(frame.sunShadowLight, 1);
        const GeometrySet geometry(s.geometry);
        for (const int n : {64, 200, 512}) {
            const SunShadowMap culled = buildSunShadowMap(cs, geometry, frame, n, 2);
            const SunShadowMap every = buildSunShadowMap(cs, geometry, frame, n, 2, false);
            ASSERT_EQ(culled.depth.size(), every.depth.size());
            size_t differ = 0;
            for (size_t i = 0; i < culled.depth.size(); ++i)
                differ += std::memcmp(&culled.depth[i], &every.depth[i], sizeof(float)) != 0 ? 1 : 0;
            EXPECT_EQ(differ, 0u) << "scene " << scene << ", " << n << " texels";
            // The froxel layer holds a solid's first depth where one is hit, the plane's second
            // depth elsewhere: count the texels where a solid was hit, so that the scenes are known
            // to put solids on the maps.
            if (n == 200) {
                const GeometrySet ground({s.geometry[0]});
                const SunShadowMap plane = buildSunShadowMap(cs, ground, frame, n, 2, false);
                for (size_t i = 0; i < every.depth.size(); ++i) solidTexels += every.depth[i] != plane.depth[i] ? 1 : 0;
            }
        }
    }
    EXPECT_GT(solidTexels, 5000);
}
