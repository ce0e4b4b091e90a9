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
