// Debug views (core/debug_view.h, shaders/shared/debug_view.h) on the CPU froxel renderer: a depth
// slice of density, scattering or transmittance shows the froxels where the fog is, and only there.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>

#include "core/debug_view.h"
#include "core/render.h"
#include "io/image_io.h"
#include "io/scene_json.h"
#include "test_support.h"

namespace brume {
namespace {

constexpr glm::vec3 kBoxCenter{0.0f, 1.0f, 0.0f};
constexpr glm::vec3 kBoxSize{4.0f, 2.4f, 3.0f};
constexpr float kSigmaS = 0.4f, kSigmaA = 0.2f;

// A box of fog in front of the test view, lit by the sun; nothing else in the froxel range.
Scene boxScene() {
    Scene s = test::sceneWithTestView();
    s.volumes.push_back(test::boxFog(kBoxCenter, kBoxSize, 0.0f, kSigmaS, kSigmaA));
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, -0.2f));
    s.lights.push_back(sun);
    return s;
}

RenderRequest debugRequest(int view, int slice) {
    RenderRequest r;
    r.width = 160;
    r.height = 90;
    r.quality = Quality::Medium;
    r.debugView = view;
    r.debugSlice = slice;
    return r;
}

// The slice holding view depth z.
int sliceAt(const shd::FrameUniforms& f, float z) {
    const float t = shd::sliceTFromViewDepth(z, f.froxelRange.x, f.froxelRange.y, f.froxelRange.z);
    return std::min(static_cast<int>(t * static_cast<float>(f.froxelDims.z)), f.froxelDims.z - 1);
}

// Whether p is inside the box by more than `margin` (> 0) or outside by more than -margin (< 0).
bool inBox(glm::vec3 p, float margin) {
    const glm::vec3 d = glm::abs(p - kBoxCenter) - 0.5f * kBoxSize;
    return margin > 0.0f ? glm::all(glm::lessThan(d, glm::vec3(-margin))) : glm::any(glm::greaterThan(d, glm::vec3(-margin)));
}

// Each pixel shows its froxel of the slice: the fog's colour where the froxel's sample point (the
// frame's jitter) is in the box, black where it is not.
TEST(DebugView, BoxFogFillsExactlyItsFroxelsInTheDensitySlice) {
    const Scene scene = boxScene();
    const shd::FrameUniforms f0 = renderFroxelCpu(scene, debugRequest(shd::DEBUG_VIEW_FINAL, 0)).volumes.frame;
    const float boxDepth = glm::length(kBoxCenter - scene.camera.position);
    const int slice = sliceAt(f0, boxDepth);
    const FroxelResult r = renderFroxelCpu(scene, debugRequest(shd::DEBUG_VIEW_DENSITY, slice));
    const Image& img = r.image;
    const shd::FrameUniforms& f = r.volumes.frame;
    ASSERT_EQ(img.width, 160);
    const glm::vec3 fogColor = shd::debugViewColor(glm::vec4(kSigmaS + kSigmaA), shd::DEBUG_VIEW_DENSITY);
    int inside = 0, outside = 0;
    for (int y = 0; y < img.height; ++y) {
        for (int x = 0; x < img.width; ++x) {
            const int tile = f.froxelDims.w;
            const glm::vec3 coord(x / tile, y / tile, slice);
            const glm::vec3 p = shd::worldFromFroxelCoord(coord + glm::vec3(f.jitter), f);
            const glm::vec3 c = img.at(x, y);
            if (inBox(p, 1e-3f)) {
                ++inside;
                EXPECT_NEAR(glm::length(c - fogColor), 0.0f, 1e-5f) << "pixel " << x << "," << y;
            } else if (inBox(p, -1e-3f)) {
                ++outside;
                EXPECT_EQ(c, glm::vec3(0.0f)) << "pixel " << x << "," << y;
            }
        }
    }
    // Every pixel is classified, and both kinds are well represented, or the test proves nothing.
    EXPECT_EQ(inside + outside, img.width * img.height);
    EXPECT_GE(inside, 1000);
    EXPECT_GE(outside, 5000);
    std::printf("[debug-view] slice %d: %d pixels show fog froxels, %d empty ones\n", slice, inside, outside);
    // The slice in front of the box holds no fog at all.
    const Image front = renderFroxelCpu(scene, debugRequest(shd::DEBUG_VIEW_DENSITY, sliceAt(f, 4.0f))).image;
    for (const glm::vec3& q : front.pixels) ASSERT_EQ(q, glm::vec3(0.0f));
}

TEST(DebugView, TransmittanceIsOneBeforeTheFogAndFallsBehindIt) {
    const Scene scene = boxScene();
    const shd::FrameUniforms f = renderFroxelCpu(scene, debugRequest(shd::DEBUG_VIEW_FINAL, 0)).volumes.frame;
    const float boxDepth = glm::length(kBoxCenter - scene.camera.position);
    const int first = sliceAt(f, boxDepth - 2.5f), last = sliceAt(f, boxDepth + 2.0f);
    // The pixel looking at the box's centre.
    const glm::vec4 c = shd::froxelCoordFromWorld(kBoxCenter, f);
    const int px = static_cast<int>(c.x * static_cast<float>(f.froxelDims.w));
    const int py = static_cast<int>(c.y * static_cast<float>(f.froxelDims.w));
    const FroxelResult r = renderFroxelCpu(scene, debugRequest(shd::DEBUG_VIEW_TRANSMITTANCE, last));
    EXPECT_EQ(r.image.pixels, debugViewImage(r.volumes, shd::DEBUG_VIEW_TRANSMITTANCE, last).pixels);
    float previous = 1.0f;
    for (int s = 0; s < f.froxelDims.z; ++s) {
        const Image img = debugViewImage(r.volumes, shd::DEBUG_VIEW_TRANSMITTANCE, s);
        ASSERT_TRUE(allFinite(img));
        const float t = img.at(px, py).x;
        if (s <= first) {
            for (const glm::vec3& p : img.pixels) ASSERT_EQ(p, glm::vec3(1.0f)) << "slice " << s;
        }
        EXPECT_LE(t, previous + 1e-6f) << "slice " << s;
        // 3 m of sigma_t 0.6 on the way: exp(-1.8) = 0.17.
        if (s >= last) {
            EXPECT_LT(t, 0.25f) << "slice " << s;
        }
        previous = t;
    }
}

TEST(DebugView, ScatteringSliceShowsTheLitBoxOnly) {
    const Scene scene = boxScene();
    const shd::FrameUniforms f = renderFroxelCpu(scene, debugRequest(shd::DEBUG_VIEW_FINAL, 0)).volumes.frame;
    const int slice = sliceAt(f, glm::length(kBoxCenter - scene.camera.position));
    const Image img = renderFroxelCpu(scene, debugRequest(shd::DEBUG_VIEW_SCATTERING, slice)).image;
    const glm::vec4 c = shd::froxelCoordFromWorld(kBoxCenter, f);
    const int tile = f.froxelDims.w;
    EXPECT_GT(img.at(static_cast<int>(c.x) * tile, static_cast<int>(c.y) * tile).z, 0.3f);
    EXPECT_EQ(img.at(0, 0), glm::vec3(0.0f));
    EXPECT_TRUE(allFinite(img));
}

TEST(DebugView, RampIsMonotonicBlackAtZeroAndFlagsBadValues) {
    float lastBrightness = -1.0f;
    for (float v : {0.0f, 1e-4f, 1e-3f, 1e-2f, 0.1f, 1.0f, 10.0f, 100.0f, 1e4f}) {
        const glm::vec3 c = shd::debugViewColor(glm::vec4(v), shd::DEBUG_VIEW_DENSITY);
        const float b = c.x + c.y + c.z;
        EXPECT_GE(b, lastBrightness) << v;
        lastBrightness = b;
        if (v == 0.0f) {
            EXPECT_EQ(c, glm::vec3(0.0f));
        } else {
            EXPECT_GT(b, 0.0f) << v;
        }
    }
    EXPECT_EQ(shd::debugViewColor(glm::vec4(1e4f), shd::DEBUG_VIEW_DENSITY), glm::vec3(1.0f));
    EXPECT_EQ(shd::debugViewColor(glm::vec4(0.25f), shd::DEBUG_VIEW_TRANSMITTANCE), glm::vec3(0.25f));
    EXPECT_EQ(shd::debugViewColor(glm::vec4(NAN), shd::DEBUG_VIEW_SCATTERING), glm::vec3(1.0f, 0.0f, 1.0f));
    EXPECT_EQ(shd::debugViewColor(glm::vec4(-1.0f), shd::DEBUG_VIEW_DENSITY), glm::vec3(1.0f, 0.0f, 1.0f));
}

std::string readBytes(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), {});
}

// `brume render --debug-view density --debug-slice N` writes the slice image as it is.
TEST(DebugView, CliWritesTheSliceImageUntoneMapped) {
    test::TempDir dir("debug_view", "cli");
    const std::string scenePath = (dir.path / "box.json").string();
    ASSERT_TRUE(saveSceneFile(boxScene(), scenePath).ok());
    const int slice = 14;
    const std::string out = (dir.path / "density.png").string();
    const std::string cmd = std::string(BRUME_EXE) + " render " + scenePath + " -o " + out +
                            " --cpu --width 160 --height 90 --quality medium --exposure 4 --debug-view density "
                            "--debug-slice " + std::to_string(slice) + " > /dev/null 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    Result<Scene> saved = loadSceneFile(scenePath);
    ASSERT_TRUE(saved.ok());
    const Image expected = renderFroxelCpu(saved.value(), debugRequest(shd::DEBUG_VIEW_DENSITY, slice)).image;
    const std::string expectedPath = (dir.path / "expected.png").string();
    ASSERT_TRUE(writeDisplayPng(expected, expectedPath).ok());
    EXPECT_EQ(readBytes(out), readBytes(expectedPath));
    const std::string bad = std::string(BRUME_EXE) + " render " + scenePath + " -o " + out +
                            " --debug-view fog > /dev/null 2>&1";
    EXPECT_EQ(WEXITSTATUS(std::system(bad.c_str())), 2);
}

}  // namespace
}  // namespace brume
