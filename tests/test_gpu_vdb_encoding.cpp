// Quantized vdb grids (Fp16, Fp8) on the GPU: the voxelize and shadow volume passes each have a
// variant per encoding (shaders/vdb_sample.glsl), which must agree with the CPU froxel renderer
// (NanoVDB's Fp16/Fp8 accessors on the same bytes) within the GPU tests' 1%, with vdb shadows on.
// A variant reading the wrong grid type decodes garbage; the vdb volume's share of the image must be
// far above the tolerance so such a GPU fails. Validation must stay silent.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "core/compile.h"
#include "core/render.h"
#include "gpu/gpu_renderer.h"
#include "gpu_test_support.h"
#include "io/vdb_import.h"
#include "test_support.h"
#include "vdb_test_util.h"

using namespace brume;
using namespace brume::gpu;
namespace fs = std::filesystem;

namespace {

using test::asImage;

constexpr double kTolerance = 0.01;

DensityGridPtr load(const fs::path& file, VdbEncoding e) {
    VdbImportOptions options;
    options.encoding = e;
    Result<VdbLoad> r = loadVdbDensity(file.string(), options);
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
    if (!r.ok()) return nullptr;
    EXPECT_EQ(r.value().grid->encoding(), e);
    return r.value().grid;
}

// The grid placed `scale` x its size, 3 m up, over height haze and a ground, a slanted sun (its fog
// shadows march the grid) and a point light beside it.
Scene sceneWith(const DensityGridPtr& grid, float densityScale) {
    Scene s = test::sceneWithTestView();
    s.camera.position = {3.0f, 3.0f, 5.5f};
    s.camera.target = {0.0f, 2.5f, 0.0f};
    Volume v;
    v.type = VolumeType::Vdb;
    v.density = grid;
    v.density_scale = densityScale;
    v.medium.scattering = {2.0f, 2.2f, 2.4f};
    v.medium.absorption = glm::vec3(0.5f);
    v.medium.emission = {0.1f, 0.05f, 0.02f};
    // Fit the grid's world box into a 3 m cube centred 3 m up.
    const shd::VolumeData d = compileVolume(v);
    const glm::vec3 size = glm::vec3(d.worldMax) - glm::vec3(d.worldMin);
    const float fit = 3.0f / std::max(size.x, std::max(size.y, size.z));
    v.transform.scale = glm::vec3(fit);
    v.transform.translation = glm::vec3(0.0f, 3.0f, 0.0f) - fit * 0.5f * (glm::vec3(d.worldMax) + glm::vec3(d.worldMin));
    Volume haze;
    haze.type = VolumeType::Height;
    haze.base_height = 0.5f;
    haze.falloff = 0.8f;
    haze.medium.scattering = glm::vec3(0.15f);
    s.volumes = {v, haze};
    Light sun = makeLight(LightType::Directional);
    sun.direction = glm::normalize(glm::vec3(0.4f, -1.0f, 0.2f));
    Light point = makeLight(LightType::Point);
    point.position = {0.5f, 5.0f, 1.5f};
    point.intensity = 20.0f;
    point.range = 12.0f;
    s.lights = {sun, point};
    s.geometry = {test::groundPlane(glm::vec3(0.6f))};
    return s;
}

class GpuVdbEncoding : public test::ValidatedGpuTest {
protected:

    void expectMatchesCpu(const Scene& scene, const char* what) {
        RenderRequest request;
        request.width = 160;
        request.height = 90;
        request.threads = 2;
        const FroxelResult cpu = renderFroxelCpu(scene, request);
        auto gpu = renderer->render(scene, request, true);
        ASSERT_TRUE(gpu.ok()) << gpu.error().message;
        const FroxelVolumes& g = gpu.value().volumes;
        const double mediaErr = relativeMeanAbsError(asImage(g.mediaExtinction), asImage(cpu.volumes.mediaExtinction));
        const double sourceErr = relativeMeanAbsError(asImage(g.source), asImage(cpu.volumes.source));
        const double imageErr = relativeMeanAbsError(gpu.value().image, cpu.image);
        Scene without = scene;
        without.volumes.erase(without.volumes.begin());
        const FroxelResult cpuWithout = renderFroxelCpu(without, request);
        const double share =
            relativeMeanAbsError(asImage(cpuWithout.volumes.mediaExtinction), asImage(cpu.volumes.mediaExtinction));
        std::printf("[gpu-vs-cpu vdb encoding] %-20s sigma_t %.2e source %.2e image %.2e (the grid's share of "
                    "sigma_t %.2f, of the image %.3f)\n", what, mediaErr, sourceErr, imageErr, share,
                    relativeMeanAbsError(cpuWithout.image, cpu.image));
        EXPECT_TRUE(allFinite(gpu.value().image)) << what;
        EXPECT_LT(mediaErr, kTolerance) << what;
        EXPECT_LT(sourceErr, kTolerance) << what;
        EXPECT_LT(imageErr, kTolerance) << what;
        EXPECT_GT(share, 10.0 * kTolerance) << what << ": the grid barely shows, the test could not fail";
    }

};

}  // namespace

// A bumpy block (0.1 m voxels) whose values vary inside every leaf, so quantization shows.
TEST_F(GpuVdbEncoding, QuantizedSyntheticGridsMatchCpu) {
    test::TempDir dir("gpu_vdb_encoding", "synthetic");
    auto g = test::makeGrid("density", -15, 14, [](openvdb::Coord c) {
        return 0.6f + 0.4f * std::sin(0.7f * static_cast<float>(c.x())) * std::cos(0.5f * static_cast<float>(c.z()));
    }, openvdb::math::Transform::createLinearTransform(0.1));
    test::writeGrids(dir.path / "bumpy.vdb", {g});
    expectMatchesCpu(sceneWith(load(dir.path / "bumpy.vdb", VdbEncoding::Fp16), 1.0f), "synthetic fp16");
    expectMatchesCpu(sceneWith(load(dir.path / "bumpy.vdb", VdbEncoding::Fp8), 1.0f), "synthetic fp8");
}

TEST_F(GpuVdbEncoding, QuantizedGafferSmokeMatchesCpu) {
    const fs::path file = test::sharedVdbDir() / "gaffer_smoke.vdb";
    if (!fs::exists(file)) GTEST_SKIP() << "../shared/vdb is absent; real-file test skipped";
    expectMatchesCpu(sceneWith(load(file, VdbEncoding::Fp16), 40.0f), "gaffer_smoke fp16");
    expectMatchesCpu(sceneWith(load(file, VdbEncoding::Fp8), 40.0f), "gaffer_smoke fp8");
}

// One variant samples every grid of a frame: a scene built in code that mixes encodings (the scene
// format refuses it) is refused with one sentence, and the renderer stays usable.
TEST_F(GpuVdbEncoding, MixedEncodingsAreRefusedClearly) {
    test::TempDir dir("gpu_vdb_encoding", "mixed");
    auto g = test::makeGrid("density", -8, 7, [](openvdb::Coord) { return 1.0f; },
                            openvdb::math::Transform::createLinearTransform(0.1));
    test::writeGrids(dir.path / "cube.vdb", {g});
    Scene s = sceneWith(load(dir.path / "cube.vdb", VdbEncoding::Fp16), 1.0f);
    s.volumes.push_back(s.volumes.front());
    s.volumes.back().density = load(dir.path / "cube.vdb", VdbEncoding::Float);
    RenderRequest request;
    request.width = 64;
    request.height = 36;
    auto r = renderer->render(s, request);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("mix the encodings fp16 and float"), std::string::npos) << r.error().message;
    EXPECT_TRUE(r.error().badInput);
    s.volumes.pop_back();
    EXPECT_TRUE(renderer->render(s, request).ok());
}
