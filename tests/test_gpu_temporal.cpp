// The GPU temporal pass against its oracle, the CPU froxel renderer's (core/temporal.cpp), frame by
// frame through a sequence with camera motion, a scene edit (a light switched off: the history is
// dropped on both sides) and a restart, on lavapipe with validation on and silent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/render.h"
#include "gpu/gpu_renderer.h"
#include "gpu_test_support.h"

using namespace brume;
using namespace brume::gpu;

namespace {

using test::asImage;

constexpr double kTolerance = 0.01;  // relative mean abs error, as for every GPU-vs-CPU test

Scene temporalScene() {
    Scene s;
    s.camera.position = {0.0f, 1.8f, 7.0f};
    s.camera.target = {0.0f, 1.0f, 0.0f};
    s.camera.far = 60.0f;
    s.ambient = {0.02f, 0.025f, 0.03f};
    s.froxels.tile_px = 8;
    s.froxels.slices = 48;
    s.froxels.far = 30.0f;
    Light spot = makeLight(LightType::Spot);
    spot.position = {1.5f, 4.0f, -1.0f};
    spot.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, 0.1f));
    spot.intensity = 120.0f;
    spot.inner_deg = 12.0f;
    spot.outer_deg = 18.0f;
    Light point = makeLight(LightType::Point);
    point.position = {-2.0f, 2.0f, 1.0f};
    point.intensity = 8.0f;
    s.lights = {spot, point};
    Volume box;
    box.type = VolumeType::Box;
    box.transform.translation = {0.0f, 1.5f, -2.0f};
    box.transform.scale = {10.0f, 3.0f, 12.0f};
    box.edge_fade = 0.3f;
    box.medium.scattering = glm::vec3(0.03f);
    box.medium.absorption = glm::vec3(0.003f);
    box.medium.phase_g = 0.3f;
    Volume height;
    height.type = VolumeType::Height;
    height.falloff = 0.7f;
    height.medium.scattering = glm::vec3(0.02f);
    s.volumes = {box, height};
    Geometry ground;
    ground.type = GeometryType::Plane;
    s.geometry = {ground};
    return s;
}

}  // namespace

TEST(GpuTemporal, MatchesTheCpuFrameByFrameThroughMotionEditsAndRestarts) {
    GpuOptions options;
    options.validation = true;
    auto created = GpuRenderer::create(options);
    ASSERT_TRUE(created.ok()) << created.error().message;
    GpuRenderer& gpu = *created.value();
    FroxelCpuRenderer cpu;

    const Scene base = temporalScene();
    RenderRequest req;
    req.width = 96;
    req.height = 54;
    req.threads = 2;
    double worst = 0.0;
    Image last;
    Scene lastScene;
    for (int n = 0; n < 12; ++n) {
        Scene s = base;
        s.camera = orbitCamera(base.camera, 2.0f * static_cast<float>(n));  // moving from frame 0
        if (n >= 6) s.lights[0].intensity = 0.0f;                          // edit: history dropped
        req.history = n == 9 ? HistoryMode::Restart : HistoryMode::Continue;  // caller's restart
        const FroxelResult c = cpu.render(s, req);
        auto g = gpu.render(s, req, true);
        ASSERT_TRUE(g.ok()) << g.error().message;
        const FroxelVolumes& gv = g.value().volumes;
        ASSERT_EQ(gv.dims, c.volumes.dims);
        const double source = relativeMeanAbsError(asImage(gv.source), asImage(c.volumes.source));
        const double scattering =
            relativeMeanAbsError(asImage(gv.integratedScattering), asImage(c.volumes.integratedScattering));
        const double image = relativeMeanAbsError(g.value().image, c.image);
        EXPECT_TRUE(brume::allFinite(g.value().image));
        EXPECT_LT(source, kTolerance) << "frame " << n;
        EXPECT_LT(scattering, kTolerance) << "frame " << n;
        EXPECT_LT(image, kTolerance) << "frame " << n;
        worst = std::max({worst, source, scattering, image});
        last = g.value().image;
        lastScene = s;
    }
    std::printf("[gpu-vs-cpu temporal] 12 frames, worst relative mean abs error %.2e\n", worst);
    // The history mattered: the last frame without it (a fresh render) differs well beyond the tolerance.
    req.history = HistoryMode::Restart;
    EXPECT_GT(relativeMeanAbsError(last, renderFroxelCpu(lastScene, req).image), 10.0 * worst);
    const std::vector<std::string> messages = gpu.validationMessages();
    EXPECT_TRUE(messages.empty()) << messages.size() << " validation messages, first: " << messages.front();
}

TEST(GpuTemporal, FramesOptionAccumulatesLikeTheCpu) {
    GpuOptions options;
    options.validation = true;
    auto created = GpuRenderer::create(options);
    ASSERT_TRUE(created.ok()) << created.error().message;
    const Scene scene = temporalScene();
    RenderRequest req;
    req.width = 96;
    req.height = 54;
    req.threads = 2;
    req.frames = 8;
    const FroxelResult c = renderFroxelCpu(scene, req);
    auto g = created.value()->render(scene, req, true);
    ASSERT_TRUE(g.ok()) << g.error().message;
    const double image = relativeMeanAbsError(g.value().image, c.image);
    req.frames = 1;
    const double versusOneFrame = relativeMeanAbsError(g.value().image, renderFroxelCpu(scene, req).image);
    std::printf("[gpu-vs-cpu temporal] 8 frames: image %.2e (vs 1 frame: %.2e)\n", image, versusOneFrame);
    EXPECT_LT(image, kTolerance);
    EXPECT_GT(versusOneFrame, 10.0 * image);  // the 8 frames did accumulate something else than frame 1
    const std::vector<std::string> messages = created.value()->validationMessages();
    EXPECT_TRUE(messages.empty()) << messages.size() << " validation messages, first: " << messages.front();
}
