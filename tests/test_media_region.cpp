// The media region (core/media_region.h): every froxel whose sample point can lie inside a volume's
// bounds is in it, whatever the jitter, so dispatching voxelize and light over it alone (the rest
// cleared to 0) changes nothing; and it follows the content: a small box gives a small region, a box
// out of view none, an unbounded fog the whole grid.
#include <gtest/gtest.h>

#include "test_support.h"

#include "core/media_region.h"
#include "core/render.h"
#include "shaders/shared/froxel.h"
#include "shaders/shared/media.h"
#include "shaders/shared/shadow_volume.h"

using namespace brume;
using glm::vec3;

namespace {

shd::FrameUniforms frameOf(const Scene& s, const CompiledScene& cs, vec3 jitter) {
    return makeFrameUniforms(s, cs, 160, 90, resolveFroxelSettings(s, Quality::High), jitter);
}

bool inRegion(const FroxelRegion& r, glm::ivec3 id) {
    return glm::all(glm::greaterThanEqual(id, r.lo)) && glm::all(glm::lessThan(id, r.hi));
}

}  // namespace

TEST(MediaRegion, HoldsEveryFroxelWhoseSampleIsInsideAVolume) {
    // Boxes in view, straddling the camera plane, partly off screen, reaching past the froxel far,
    // rotated; jitters at the corners of [0, 1)^3.
    const std::vector<Volume> boxes = {
        test::boxFog({0.0f, 1.0f, 0.0f}, {1.0f, 1.0f, 1.0f}, 0.1f, 0.5f, 0.0f),
        test::boxFog({0.0f, 1.8f, 7.0f}, {2.0f, 2.0f, 2.0f}, 0.0f, 0.5f, 0.0f),
        test::boxFog({4.0f, 0.5f, 2.0f}, {3.0f, 1.0f, 1.0f}, 0.0f, 0.5f, 0.0f),
        test::boxFog({0.0f, 1.0f, -40.0f}, {4.0f, 4.0f, 30.0f}, 0.0f, 0.5f, 0.0f),
        test::boxFog({0.3f, 1.5f, 5.0f}, {0.8f, 0.6f, 0.8f}, 0.0f, 0.5f, 0.0f),  // near the camera
    };
    for (size_t b = 0; b < boxes.size(); ++b) {
        Scene s = test::sceneWithTestView();
        s.volumes = {boxes[b]};
        if (b == 2) s.volumes[0].transform.rotation_deg = {20.0f, 35.0f, 10.0f};
        const CompiledScene cs = compileScene(s);
        for (vec3 jitter : {vec3(0.0f), vec3(0.999f), vec3(0.999f, 0.0f, 0.5f), vec3(0.0f, 0.999f, 0.999f)}) {
            const shd::FrameUniforms f = frameOf(s, cs, jitter);
            const FroxelRegion r = mediaFroxelRegion(cs, f);
            const glm::ivec3 dims(f.froxelDims);
            int inside = 0;
            for (int z = 0; z < dims.z; ++z)
                for (int y = 0; y < dims.y; ++y)
                    for (int x = 0; x < dims.x; ++x) {
                        const vec3 p = shd::worldFromFroxelCoord(vec3(x, y, z) + jitter, f);
                        if (!shd::insideBounds(cs.volumes[0], p)) continue;
                        ++inside;
                        ASSERT_TRUE(inRegion(r, {x, y, z})) << "box " << b << " froxel " << x << " " << y << " " << z;
                    }
            EXPECT_GT(inside, 0) << "box " << b << " reaches no froxel: the test checks nothing";
        }
    }
}

TEST(MediaRegion, FollowsTheContent) {
    Scene s = test::sceneWithTestView();
    s.volumes = {test::boxFog({0.0f, 1.0f, 0.0f}, {0.8f, 0.8f, 0.8f}, 0.1f, 0.5f, 0.0f)};
    CompiledScene cs = compileScene(s);
    shd::FrameUniforms f = frameOf(s, cs, vec3(0.5f));
    const int64_t grid = int64_t(f.froxelDims.x) * f.froxelDims.y * f.froxelDims.z;
    EXPECT_LT(mediaFroxelRegion(cs, f).froxels(), grid / 10) << "a small box in view";

    s.volumes = {test::boxFog({0.0f, 1.0f, 20.0f}, {2.0f, 2.0f, 2.0f}, 0.1f, 0.5f, 0.0f)};  // behind the camera
    cs = compileScene(s);
    EXPECT_TRUE(mediaFroxelRegion(cs, frameOf(s, cs, vec3(0.5f))).empty());

    s.volumes = {test::boxFog({0.0f, 1.0f, -200.0f}, {2.0f, 2.0f, 2.0f}, 0.1f, 0.5f, 0.0f)};  // past the froxel far
    cs = compileScene(s);
    EXPECT_TRUE(mediaFroxelRegion(cs, frameOf(s, cs, vec3(0.5f))).empty());

    s = test::heightFogView(20.0f, 0.5f, {0.2f, 0.2f, 0.2f});  // unbounded
    cs = compileScene(s);
    f = frameOf(s, cs, vec3(0.5f));
    const FroxelRegion r = mediaFroxelRegion(cs, f);
    EXPECT_EQ(r.lo, glm::ivec3(0));
    EXPECT_EQ(r.hi, glm::ivec3(f.froxelDims));
}

namespace {

// The largest optical depth of volume 0 toward each light whose fog shadow is evaluated, and whether
// its bounds hold a point, over a sweep of points (froxel sample points or surface points).
struct VolumeTerms {
    float maxDepth = 0.0f;
    bool holdsSample = false;

    void add(const CompiledScene& cs, const shd::FrameUniforms& f, vec3 p) {
        holdsSample = holdsSample || shd::insideBounds(cs.volumes[0], p);
        for (const shd::LightData& l : cs.lights) {
            if (!shd::fogShadowsLight(l, f.localFogShadows)) continue;
            const shd::LightSample ls = shd::evalLight(l, p);
            const vec3 tau = shd::shadowOpticalDepth(cs.volumes[0], p, ls.toLight, ls.distance);
            maxDepth = std::max(maxDepth, std::max(tau.x, std::max(tau.y, tau.z)));
        }
    }
};

// Over the froxels of a coarse sweep of the grid (every 3rd froxel per axis, two jitters).
VolumeTerms froxelTerms(const CompiledScene& cs, const shd::FrameUniforms& f) {
    VolumeTerms t;
    const glm::ivec3 dims(f.froxelDims);
    for (vec3 jitter : {vec3(0.0f), vec3(0.999f)})
        for (int z = 0; z <= dims.z; z += 3)
            for (int y = 0; y <= dims.y; y += 3)
                for (int x = 0; x <= dims.x; x += 3)
                    t.add(cs, f, shd::worldFromFroxelCoord(glm::min(vec3(x, y, z) + jitter, vec3(dims)), f));
    return t;
}

// Over the view frustum from the camera near to the camera far (33 x 19 rays through the image, 40
// depths), where the geometry pass can shade a surface.
VolumeTerms surfaceTerms(const CompiledScene& cs, const shd::FrameUniforms& f) {
    VolumeTerms t;
    const float zNear = f.projection.z, zFar = f.projection.w;
    for (int d = 0; d < 40; ++d) {
        const float z = zNear * std::pow(zFar / zNear, float(d) / 39.0f);
        for (int y = 0; y <= 18; ++y)
            for (int x = 0; x <= 32; ++x) {
                const glm::vec2 pixel(float(f.counts.x) * float(x) / 32.0f, float(f.counts.y) * float(y) / 18.0f);
                t.add(cs, f, vec3(f.worldFromView * glm::vec4(shd::viewRayFromPixel(pixel, f) * z, 1.0f)));
            }
    }
    return t;
}

struct ReachCase {
    vec3 boxCentre;
    vec3 sunDirection;  // the way the light travels
    bool expectCulled;
};

// The test view with a faded box at the case's centre, its sun and a point light; froxelFar > 0
// overrides the preset's froxel far.
Scene reachScene(const ReachCase& c, float froxelFar) {
    Scene s = test::sceneWithTestView();
    if (froxelFar > 0.0f) s.froxels.far = froxelFar;
    s.volumes = {test::boxFog(c.boxCentre, {3.0f, 2.4f, 3.0f}, 0.35f, 0.5f, 0.02f)};
    Light sun = makeLight(LightType::Directional);
    sun.direction = glm::normalize(c.sunDirection);
    s.lights = {sun, test::pointLight({1.0f, 1.0f, 0.0f}, 6.0f, 5.0f)};
    return s;
}

// Each case's volume is out of `reach` exactly when expected; a volume out of reach adds nothing
// over `terms`' sweep, and each one expected in reach adds something there (so the first check has
// teeth). Unbounded fog is always in reach.
template <typename Reach, typename Terms>
void expectReachCases(const std::vector<ReachCase>& cases, float froxelFar, Reach reach, Terms terms) {
    int culled = 0;
    for (size_t c = 0; c < cases.size(); ++c) {
        const Scene s = reachScene(cases[c], froxelFar);
        const CompiledScene cs = compileScene(s);
        const shd::FrameUniforms f = frameOf(s, cs, vec3(0.5f));
        const std::vector<bool> inReach = reach(cs, f);
        ASSERT_EQ(inReach.size(), 1u);
        const VolumeTerms t = terms(cs, f);
        if (!inReach[0]) {
            ++culled;
            EXPECT_FALSE(t.holdsSample) << "case " << c;
            EXPECT_EQ(t.maxDepth, 0.0f) << "case " << c;
        }
        if (!cases[c].expectCulled) {
            EXPECT_TRUE(t.holdsSample || t.maxDepth > 0.0f) << "case " << c;
        }
        EXPECT_EQ(!inReach[0], cases[c].expectCulled) << "case " << c << ": holds a point " << t.holdsSample
                                                      << ", largest optical depth " << t.maxDepth;
    }
    EXPECT_GT(culled, 0);
    const Scene h = test::heightFogView(20.0f, 0.5f, {0.2f, 0.2f, 0.2f});
    const CompiledScene hc = compileScene(h);
    EXPECT_TRUE(reach(hc, frameOf(h, hc, vec3(0.5f)))[0]);
}

}  // namespace

// The froxel passes leave out a volume only when it adds exactly nothing to them: no sample point in
// its bounds and no fog shadow through it. And they do leave out a box behind the camera that no
// shadow ray from the view crosses.
TEST(MediaRegion, VolumesOutOfReachAddNothingToTheFroxels) {
    expectReachCases(
        {
            {{0.0f, 1.0f, 20.0f}, {-0.8f, -0.35f, -0.3f}, true},  // behind the camera, sun from the side-front
            {{0.0f, 1.0f, 20.0f}, {0.0f, -0.3f, -1.0f}, false},   // behind the camera, sun shining through it
            {{0.0f, 1.0f, -200.0f}, {0.0f, -1.0f, 0.0f}, true},   // past the froxel far, sun from above
            {{0.0f, 1.0f, -200.0f}, {0.0f, -0.2f, 1.0f}, false},  // past the froxel far, low sun behind it
            {{0.0f, 1.0f, 0.0f}, {0.0f, -1.0f, 0.0f}, false},     // in view
            {{0.0f, 30.0f, 0.0f}, {0.0f, -1.0f, 0.0f}, false},    // above the view, overhead sun
            {{40.0f, 1.0f, 0.0f}, {0.0f, -1.0f, 0.0f}, true},     // far to the side, overhead sun
        },
        0.0f, froxelVolumesInReach, froxelTerms);
}

// The geometry pass leaves out a volume only when it adds exactly nothing to any surface the view
// can hold: no point of the view frustum (camera near to camera far) in its bounds and no fog shadow
// through it from such a point. It leaves out the offscreen bench scene's box behind the camera, and
// keeps a box in view past the froxel far, which the froxel passes leave out.
TEST(MediaRegion, VolumesOutOfTheSurfacesReachAddNothingToThem) {
    const float froxelFar = 20.0f;  // the froxels end well before the camera far (60 m)
    const ReachCase pastTheFroxels{{0.0f, 1.0f, -30.0f}, {0.0f, -1.0f, 0.0f}, false};
    expectReachCases(
        {
            {{0.0f, 1.0f, 20.0f}, {-0.8f, -0.35f, -0.3f}, true},  // behind the camera (bench/scenes/default_offscreen_volume.json)
            {{0.0f, 1.0f, 20.0f}, {0.0f, -0.3f, -1.0f}, false},   // behind the camera, sun shining through it
            {{0.0f, 1.0f, -200.0f}, {0.0f, -1.0f, 0.0f}, true},   // past the camera far, sun from above
            {{0.0f, 1.0f, -200.0f}, {0.0f, -0.2f, 1.0f}, false},  // past the camera far, low sun behind it
            pastTheFroxels,                                       // in view past the froxel far
            {{0.0f, 30.0f, 0.0f}, {0.0f, -1.0f, 0.0f}, false},    // above the view, overhead sun
            {{60.0f, 1.0f, 0.0f}, {0.0f, -1.0f, 0.0f}, true},     // far to the side, overhead sun
        },
        froxelFar, surfaceVolumesInReach, surfaceTerms);
    const Scene s = reachScene(pastTheFroxels, froxelFar);
    const CompiledScene cs = compileScene(s);
    EXPECT_FALSE(froxelVolumesInReach(cs, frameOf(s, cs, vec3(0.5f)))[0]) << "the two tests differ here";
}

// The shadow volume pass computes only shadowCellRegion's cells: every cell the light pass's lookup
// (shd::shadowLookup, its lower and upper corners) takes at a froxel of the media region (where every
// froxel with media lies, HoldsEveryFroxelWhoseSampleIsInsideAVolume) is in it, at the presets'
// reductions and at 3; the region follows the content (a small box: a small part of the volume; none
// without media); and surfaces, which read the vdb layers anywhere, get the whole volume when vdb
// shadows are on.
TEST(MediaRegion, ShadowCellsHoldEveryCellTheLightPassReads) {
    const std::vector<Volume> boxes = {
        test::boxFog({0.0f, 1.0f, 0.0f}, {0.8f, 0.8f, 0.8f}, 0.1f, 0.5f, 0.0f),      // small, in view
        test::boxFog({4.0f, 0.5f, 2.0f}, {3.0f, 1.0f, 1.0f}, 0.0f, 0.5f, 0.0f),      // partly off screen
        test::boxFog({0.0f, 1.0f, -40.0f}, {4.0f, 4.0f, 30.0f}, 0.0f, 0.5f, 0.0f),   // past the froxel far
        test::boxFog({0.0f, 1.0f, 0.0f}, {60.0f, 30.0f, 60.0f}, 0.0f, 0.5f, 0.0f),   // larger than the view
    };
    int checked = 0;
    for (size_t b = 0; b < boxes.size(); ++b) {
        Scene s = test::sceneWithTestView();
        s.volumes = {boxes[b]};
        const CompiledScene cs = compileScene(s);
        for (int r : {1, 2, 3, 4}) {
            shd::FrameUniforms f = frameOf(s, cs, vec3(0.5f));
            f.shadowReduction = r;
            const glm::ivec3 dims(f.froxelDims);
            const glm::ivec3 cells = shd::shadowVolumeDims(dims, r);
            const FroxelRegion media = mediaFroxelRegion(cs, f);
            ASSERT_FALSE(media.empty()) << "box " << b;
            const FroxelRegion c = shadowCellRegion(media, f, /*surfaces=*/true);  // no vdb shadows: surfaces read nothing
            ASSERT_TRUE(regionContains(FroxelRegion{glm::ivec3(0), cells}, c)) << "box " << b << " r " << r;
            for (int z = media.lo.z; z < media.hi.z; ++z)
                for (int y = media.lo.y; y < media.hi.y; ++y)
                    for (int x = media.lo.x; x < media.hi.x; ++x) {
                        const shd::ShadowLookup k = shd::shadowLookup({x, y, z}, dims, r);
                        ASSERT_EQ(k.cells, cells);
                        ASSERT_TRUE(inRegion(c, k.cell) && inRegion(c, k.upper))
                            << "box " << b << " r " << r << " froxel " << x << " " << y << " " << z;
                        ++checked;
                    }
            if (b == 0) {
                EXPECT_LT(c.froxels() * 10, int64_t(cells.x) * cells.y * cells.z) << "r " << r;
            }
            if (b == 3) {
                EXPECT_EQ(glm::ivec2(c.hi - c.lo), glm::ivec2(cells)) << "r " << r;  // the whole view
            }
        }
    }
    EXPECT_GT(checked, 0);

    Scene s = test::sceneWithTestView();
    s.volumes = {test::boxFog({0.0f, 1.0f, 20.0f}, {2.0f, 2.0f, 2.0f}, 0.1f, 0.5f, 0.0f)};  // behind the camera
    CompiledScene cs = compileScene(s);
    shd::FrameUniforms f = frameOf(s, cs, vec3(0.5f));
    f.shadowReduction = 2;
    EXPECT_TRUE(shadowCellRegion(mediaFroxelRegion(cs, f), f, true).empty());
    f.vdbShadowSamples = 2;  // surfaces read the vdb layers anywhere
    EXPECT_TRUE(shadowCellRegion(mediaFroxelRegion(cs, f), f, false).empty());
    const FroxelRegion all = shadowCellRegion(mediaFroxelRegion(cs, f), f, true);
    EXPECT_EQ(all.lo, glm::ivec3(0));
    EXPECT_EQ(all.hi, shd::shadowVolumeDims(glm::ivec3(f.froxelDims), 2));
}

// regionUnion (the shadow volume's per-light boxes, core/light_reach.h listedFroxelRegions): the
// smallest box holding both, an empty region adding nothing whatever its corners.
TEST(MediaRegion, UnionHoldsBothAndIgnoresEmptyRegions) {
    const FroxelRegion a{glm::ivec3(1, 2, 3), glm::ivec3(4, 5, 6)};
    const FroxelRegion b{glm::ivec3(3, 0, 5), glm::ivec3(7, 3, 9)};
    const FroxelRegion u = regionUnion(a, b);
    EXPECT_EQ(u.lo, glm::ivec3(1, 0, 3));
    EXPECT_EQ(u.hi, glm::ivec3(7, 5, 9));
    EXPECT_TRUE(regionContains(u, a) && regionContains(u, b));
    // Empty regions with corners far outside: they must not stretch the box.
    const FroxelRegion farEmpty{glm::ivec3(-50), glm::ivec3(-60)};
    EXPECT_EQ(regionUnion(a, farEmpty).lo, a.lo);
    EXPECT_EQ(regionUnion(farEmpty, a).hi, a.hi);
    EXPECT_TRUE(regionUnion(farEmpty, FroxelRegion{}).empty());
}
