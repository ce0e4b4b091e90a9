// The GPU's debug views (shaders/debug_view.comp) against the CPU froxel renderer's
// (core/debug_view.cpp), on lavapipe with validation on.
#include <gtest/gtest.h>

#include "core/debug_view.h"
#include "gpu/gpu_renderer.h"
#include "test_support.h"

namespace brume {
namespace {

constexpr double kTolerance = 0.01;  // relative mean abs error, as the other GPU-vs-CPU tests

Scene boxScene() {
    Scene s = test::sceneWithTestView();
    s.volumes.push_back(test::boxFog({0.0f, 1.0f, 0.0f}, {4.0f, 2.4f, 3.0f}, 0.2f, 0.4f, 0.2f));
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, -0.2f));
    s.lights.push_back(sun);
    s.geometry.push_back(test::groundPlane(glm::vec3(0.5f)));
    return s;
}

TEST(GpuDebugView, EverySliceViewMatchesTheCpuFroxelRenderer) {
    gpu::GpuOptions options;
    options.validation = true;
    auto created = gpu::GpuRenderer::create(options);
    ASSERT_TRUE(created.ok()) << created.error().message;
    gpu::GpuRenderer& renderer = *created.value();
    const Scene scene = boxScene();
    for (int view : {shd::DEBUG_VIEW_DENSITY, shd::DEBUG_VIEW_SCATTERING, shd::DEBUG_VIEW_TRANSMITTANCE}) {
        for (int slice : {0, 21, 40, 999}) {  // 999: past the last slice, clamped to it
            RenderRequest request;
            request.width = 160;
            request.height = 90;
            request.quality = Quality::Medium;
            request.debugView = view;
            request.debugSlice = slice;
            const Image cpu = renderFroxelCpu(scene, request).image;
            auto g = renderer.render(scene, request);
            ASSERT_TRUE(g.ok()) << g.error().message;
            const Image& gpu = g.value().image;
            ASSERT_TRUE(allFinite(gpu));
            const double err = relativeMeanAbsError(gpu, cpu);
            EXPECT_LT(err, kTolerance) << debugViewName(view) << " slice " << slice;
            std::printf("[gpu-vs-cpu] debug %-13s slice %3d: %.2e\n", debugViewName(view), slice, err);
        }
    }
    // The final image is back once the debug view is off.
    RenderRequest plain;
    plain.width = 160;
    plain.height = 90;
    plain.quality = Quality::Medium;
    auto g = renderer.render(scene, plain);
    ASSERT_TRUE(g.ok());
    EXPECT_LT(relativeMeanAbsError(g.value().image, renderFroxelCpu(scene, plain).image), kTolerance);
    const std::vector<std::string> messages = renderer.validationMessages();
    EXPECT_TRUE(messages.empty()) << messages.size() << " validation messages, first: " << messages.front();
}

}  // namespace
}  // namespace brume
