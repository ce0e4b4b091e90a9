// Clustered light culling on the GPU (core/clusters.h, shaders/light.comp): with many lights of
// which few reach the fog, the culled GPU image agrees with the CPU froxel renderer within the GPU
// tests' 1% and with the GPU's own unculled image to float noise. Validation must stay silent.
#include <gtest/gtest.h>

#include "test_support.h"

#include <cstdio>

#include "core/render.h"
#include "gpu/gpu_renderer.h"

using namespace brume;
using namespace brume::gpu;

namespace {

// Height fog, a sun, and a ring of 24 short-range point lights of which the first 4 sit in the fog
// in view and the rest far out of reach (the benchmark's shape, scaled down).
Scene manyLights() {
    Scene s = test::heightFogView(30.0f, 0.6f, {0.2f, 0.22f, 0.25f});
    s.volumes[0].medium.phase_g = 0.3f;
    Light sun = makeLight(LightType::Directional);
    sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.4f));
    sun.shadows = false;
    sun.intensity = 0.5f;
    s.lights = {sun};
    for (int i = 0; i < 24; ++i) {
        Light l = makeLight(LightType::Point);
        const float a = 0.26f * static_cast<float>(i);
        l.position = i < 4 ? glm::vec3(-2.0f + 1.3f * static_cast<float>(i), 0.6f, -1.0f - static_cast<float>(i))
                           : glm::vec3(50.0f * std::cos(a), 1.0f, 50.0f * std::sin(a));
        l.range = 2.5f;
        l.intensity = 15.0f;
        l.shadows = false;
        s.lights.push_back(l);
    }
    return s;
}

}  // namespace

// The light reach (core/light_reach.h) on the GPU: the geometry pass loops over the surface lights
// only and the shadow volume pass skips the layers nobody reads. With a floor under the lights, one
// of them for surfaces only (fog_scale 0) and fog shadows toward every light (high), the culled image
// equals the unculled one to float noise and the unculled CPU's within the GPU tests' 1%.
// First in this file: a fresh device whose skipped layers cannot hold an earlier test's values.
TEST(GpuClusters, LightReachKeepsSurfacesAndFogShadowsUnchanged) {
    GpuOptions options;
    options.validation = true;
    auto created = GpuRenderer::create(options);
    ASSERT_TRUE(created.ok()) << created.error().message;
    GpuRenderer& gpu = *created.value();
    Scene s = manyLights();
    Geometry floor;
    floor.type = GeometryType::Plane;
    floor.albedo = glm::vec3(0.5f);
    s.geometry = {floor};
    s.lights[2].fog_scale = 0.0f;
    RenderRequest r;
    r.width = 160;
    r.height = 90;
    r.threads = 2;
    auto culled = gpu.render(s, r);
    ASSERT_TRUE(culled.ok()) << culled.error().message;
    r.lightCulling = false;
    auto all = gpu.render(s, r);
    ASSERT_TRUE(all.ok()) << all.error().message;
    // The CPU unculled: a reach that skipped a needed light on both sides would still differ from it.
    const FroxelResult cpu = renderFroxelCpu(s, r);
    const double vsCpu = relativeMeanAbsError(culled.value().image, cpu.image);
    const double vsUnculled = relativeMeanAbsError(culled.value().image, all.value().image);
    EXPECT_LT(vsCpu, 0.01);
    EXPECT_LT(vsUnculled, 1.0e-6);
    std::printf("[gpu-reach] culled vs cpu %.2e, culled vs unculled %.2e\n", vsCpu, vsUnculled);
    const std::vector<std::string> messages = gpu.validationMessages();
    EXPECT_TRUE(messages.empty()) << messages.size() << " validation messages, first: " << messages.front();
}

TEST(GpuClusters, CulledMatchesCpuAndUnculled) {
    GpuOptions options;
    options.validation = true;
    auto created = GpuRenderer::create(options);
    ASSERT_TRUE(created.ok()) << created.error().message;
    GpuRenderer& gpu = *created.value();
    const Scene s = manyLights();
    RenderRequest r;
    r.width = 160;
    r.height = 90;
    r.threads = 2;
    const FroxelResult cpu = renderFroxelCpu(s, r);
    auto culled = gpu.render(s, r);
    ASSERT_TRUE(culled.ok()) << culled.error().message;
    r.lightCulling = false;
    auto all = gpu.render(s, r);
    ASSERT_TRUE(all.ok()) << all.error().message;
    EXPECT_TRUE(allFinite(culled.value().image));
    const double vsCpu = relativeMeanAbsError(culled.value().image, cpu.image);
    const double vsUnculled = relativeMeanAbsError(culled.value().image, all.value().image);
    EXPECT_LT(vsCpu, 0.01);
    EXPECT_LT(vsUnculled, 1.0e-6);
    EXPECT_EQ(culled.value().overfullClusters, 0u);
    std::printf("[gpu-clusters] culled vs cpu %.2e, culled vs unculled %.2e\n", vsCpu, vsUnculled);
    const std::vector<std::string> messages = gpu.validationMessages();
    EXPECT_TRUE(messages.empty()) << messages.size() << " validation messages, first: " << messages.front();
}

