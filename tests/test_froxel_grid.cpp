// The froxel grid mapping (shaders/shared/froxel.h) and the settings that size it: the slice
// distribution and its inverse at extreme near/far ratios and exponents, froxel positions against
// the camera's projection, the integration range, and preset resolution.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/compile.h"
#include "core/quality.h"
#include "shaders/shared/brume.h"

using namespace brume;

namespace {

constexpr float kNear = 1e-3f;
constexpr float kFar = 1e6f;
const std::vector<float> kExponents = {0.1f, 0.25f, 0.5f, 1.0f, 2.0f, 3.0f, 5.0f, 8.0f};

double depthDouble(double t, double k) { return kNear + (double(kFar) - kNear) * std::pow(t, k); }

// Float values farther apart than this many ulps must come out strictly ordered.
bool distinctInFloat(double a, double b) {
    const double ulp = std::nextafter(float(std::max(std::abs(a), std::abs(b))), kFar * 10.0f) -
                       float(std::max(std::abs(a), std::abs(b)));
    return std::abs(b - a) > 4.0 * ulp;
}

Scene testScene() {
    Scene s;
    s.camera.position = {3.0f, 2.0f, 7.0f};
    s.camera.target = {-1.0f, 0.5f, -2.0f};
    s.camera.fov_y_deg = 50.0f;
    s.camera.near = 0.2f;
    s.camera.far = 200.0f;
    return s;
}

}  // namespace

TEST(SliceMapping, DepthRoundTripsThroughSliceT) {
    for (float k : kExponents) {
        for (int i = 0; i <= 1024; ++i) {
            const float t = float(i) / 1024.0f;
            const float z = shd::viewDepthFromSliceT(t, kNear, kFar, k);
            const float t2 = shd::sliceTFromViewDepth(z, kNear, kFar, k);
            const float z2 = shd::viewDepthFromSliceT(t2, kNear, kFar, k);
            EXPECT_NEAR(z2, z, 1e-6 * z) << "k " << k << " t " << t;
            // Where z stands clear of near, t itself is recovered (the inverse is well conditioned).
            if (z - kNear > 1e-2 * z) {
                EXPECT_NEAR(t2, t, 5e-6 * (1.0 + 1.0 / k) * t) << "k " << k << " t " << t;
            }
        }
        EXPECT_EQ(shd::viewDepthFromSliceT(0.0f, kNear, kFar, k), kNear);
        EXPECT_EQ(shd::viewDepthFromSliceT(1.0f, kNear, kFar, k), kFar);
        EXPECT_EQ(shd::sliceTFromViewDepth(kNear, kNear, kFar, k), 0.0f);
        EXPECT_EQ(shd::sliceTFromViewDepth(kFar, kNear, kFar, k), 1.0f);
        // Outside the range the mapping clamps instead of making NaN.
        EXPECT_EQ(shd::sliceTFromViewDepth(0.0f, kNear, kFar, k), 0.0f);
        EXPECT_EQ(shd::sliceTFromViewDepth(1e9f, kNear, kFar, k), 1.0f);
    }
}

TEST(SliceMapping, DepthFromSliceTIsMonotonic) {
    const int n = 8192;
    for (float k : kExponents) {
        float prev = shd::viewDepthFromSliceT(0.0f, kNear, kFar, k);
        for (int i = 1; i <= n; ++i) {
            const float t = float(i) / float(n), tPrev = float(i - 1) / float(n);
            const float z = shd::viewDepthFromSliceT(t, kNear, kFar, k);
            ASSERT_GE(z, prev) << "k " << k << " t " << t;
            if (distinctInFloat(depthDouble(tPrev, k), depthDouble(t, k))) {
                ASSERT_GT(z, prev) << "k " << k << " t " << t;
            }
            prev = z;
        }
    }
}

TEST(SliceMapping, SliceTFromDepthIsMonotonic) {
    // Depths spread geometrically from near to far, so every decade of the 1e9 ratio is visited.
    const int n = 8192;
    for (float k : kExponents) {
        float prev = 0.0f;
        double zPrev = kNear;
        for (int i = 1; i <= n; ++i) {
            const double z = kNear * std::pow(double(kFar) / kNear, double(i) / n);
            const float t = shd::sliceTFromViewDepth(float(z), kNear, kFar, k);
            ASSERT_GE(t, prev) << "k " << k << " z " << z;
            const double tD = std::pow((z - kNear) / (double(kFar) - kNear), 1.0 / k);
            const double tPrevD = std::pow((zPrev - kNear) / (double(kFar) - kNear), 1.0 / k);
            if (distinctInFloat(zPrev, z) && distinctInFloat(tPrevD, tD) && tPrevD > 1e-30) {
                ASSERT_GT(t, prev) << "k " << k << " z " << z;
            }
            prev = t;
            zPrev = z;
        }
    }
}

TEST(FroxelBounds, FroxelCoordinatesProjectToTheirPixels) {
    const Scene scene = testScene();
    const CompiledScene cs = compileScene(scene);
    const FroxelSettings fs{7, 40, 0.2f, 150.0f, 2.5f};
    const int width = 160, height = 90;
    const shd::FrameUniforms f = makeFrameUniforms(scene, cs, width, height, fs);
    ASSERT_EQ(f.froxelDims, glm::ivec4(23, 13, 40, 7));
    for (glm::vec3 c : {glm::vec3(0.0f), glm::vec3(3.5f, 2.25f, 0.5f), glm::vec3(22.9f, 12.8f, 39.0f),
                        glm::vec3(11.0f, 6.0f, 40.0f), glm::vec3(1.0f, 12.0f, 17.3f)}) {
        const glm::vec3 world = shd::worldFromFroxelCoord(c, f);
        const glm::vec4 clip = f.clipFromWorld * glm::vec4(world, 1.0f);
        // Vulkan clip space with y flipped: NDC (-1,-1) is the top-left pixel corner.
        const float px = (clip.x / clip.w * 0.5f + 0.5f) * float(width);
        const float py = (clip.y / clip.w * 0.5f + 0.5f) * float(height);
        EXPECT_NEAR(px, c.x * float(fs.tile_px), 2e-3f) << c.x << " " << c.y << " " << c.z;
        EXPECT_NEAR(py, c.y * float(fs.tile_px), 2e-3f) << c.x << " " << c.y << " " << c.z;
        const float depth = shd::viewDepthFromSliceT(c.z / float(fs.slices), fs.near, fs.far, fs.distribution);
        EXPECT_NEAR(clip.w, depth, 1e-5f * depth);  // perspective clip w is the view depth
    }
}

TEST(FroxelBounds, SliceZeroTouchesTheCameraAndSlicesTileTheRay) {
    const Scene scene = testScene();
    const CompiledScene cs = compileScene(scene);
    const FroxelSettings fs{8, 64, 0.5f, 120.0f, 2.0f};
    const shd::FrameUniforms f = makeFrameUniforms(scene, cs, 160, 90, fs);
    for (glm::vec2 pixel : {glm::vec2(4.0f, 4.0f), glm::vec2(80.0f, 45.0f), glm::vec2(156.0f, 86.0f)}) {
        const float rayPerDepth = glm::length(shd::viewRayFromPixel(pixel, f));
        EXPECT_NEAR(shd::sliceRayLength(0, pixel, f),
                    shd::viewDepthFromSliceT(1.0f / 64.0f, fs.near, fs.far, fs.distribution) * rayPerDepth, 1e-5f);
        double total = 0.0;
        for (int s = 0; s < fs.slices; ++s) {
            const float d = shd::sliceRayLength(s, pixel, f);
            EXPECT_GT(d, 0.0f);
            total += d;
        }
        const glm::vec3 farPoint = shd::worldFromFroxelCoord(glm::vec3(pixel / 8.0f, 64.0f), f);
        const double cameraToFar = glm::length(farPoint - scene.camera.position);
        EXPECT_NEAR(total, cameraToFar, 1e-5 * cameraToFar);
    }
}

TEST(FroxelGrid, DimsRoundUp) {
    auto dims = [](int w, int h, int tile, int slices) {
        return froxelGridDims(w, h, FroxelSettings{tile, slices, 0.1f, 50.0f, 2.0f});
    };
    EXPECT_EQ(dims(640, 360, 16, 32), glm::ivec3(40, 23, 32));
    EXPECT_EQ(dims(640, 360, 7, 64), glm::ivec3(92, 52, 64));
    EXPECT_EQ(dims(64, 36, 4, 8), glm::ivec3(16, 9, 8));
    EXPECT_EQ(dims(1, 1, 64, 1), glm::ivec3(1, 1, 1));
    EXPECT_EQ(dims(65, 1, 64, 3), glm::ivec3(2, 1, 3));
}

TEST(FroxelSettingsResolve, PresetThenOverridesThenCameraClamp) {
    Scene scene = testScene();
    for (Quality q : {Quality::Low, Quality::Medium, Quality::High, Quality::Ultra}) {
        const QualityPreset& p = qualityPreset(q);
        const FroxelSettings s = resolveFroxelSettings(scene, q);
        EXPECT_EQ(s.tile_px, p.tile_px);
        EXPECT_EQ(s.slices, p.slices);
        EXPECT_EQ(s.distribution, p.distribution);
        EXPECT_EQ(s.near, scene.camera.near);
        EXPECT_EQ(s.far, std::min(p.far, scene.camera.far));
    }
    scene.froxels.tile_px = 5;
    scene.froxels.slices = 17;
    scene.froxels.distribution = 3.5f;
    scene.froxels.near = 0.7f;
    scene.froxels.far = 33.0f;
    EXPECT_EQ(resolveFroxelSettings(scene, Quality::Low), (FroxelSettings{5, 17, 0.7f, 33.0f, 3.5f}));

    scene.froxels.far = 5000.0f;  // beyond the camera's far (200): fog cannot outlive the geometry
    EXPECT_EQ(resolveFroxelSettings(scene, Quality::High).far, scene.camera.far);
    scene.camera.far = 20.0f;
    scene.froxels = {};
    EXPECT_EQ(resolveFroxelSettings(scene, Quality::Ultra).far, 20.0f);

    scene.froxels.near = 50.0f;  // a near override past the far: the span stays positive
    const FroxelSettings odd = resolveFroxelSettings(scene, Quality::Medium);
    EXPECT_GT(odd.far, odd.near);
    EXPECT_TRUE(std::isfinite(shd::sliceTFromViewDepth(30.0f, odd.near, odd.far, odd.distribution)));
}
