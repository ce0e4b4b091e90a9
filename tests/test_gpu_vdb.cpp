// vdb volumes on the GPU: the voxelize pass samples the NanoVDB grids with PNanoVDB and must agree
// with its oracle, the CPU froxel renderer (which samples the same bytes with NanoVDB), within the
// GPU tests' 1% relative mean absolute error; the validation layer must stay silent.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <vector>
#include <unistd.h>

#include "core/compile.h"
#include "core/render.h"
#include "gpu/gpu_renderer.h"
#include "gpu_test_support.h"
#include "io/vdb_import.h"
#include "vdb_test_util.h"

using namespace brume;
using namespace brume::gpu;
namespace fs = std::filesystem;

namespace {

using test::asImage;

constexpr double kTolerance = 0.01;

DensityGridPtr loadGrid(const fs::path& file) {
    Result<VdbLoad> r = loadVdbDensity(file.string(), {});
    EXPECT_TRUE(r.ok()) << r.error().message;
    return r.ok() ? r.value().grid : nullptr;
}

Volume vdbVolume(const DensityGridPtr& grid) {
    Volume v;
    v.type = VolumeType::Vdb;
    v.density = grid;
    v.medium.scattering = {1.2f, 1.4f, 1.6f};
    v.medium.absorption = glm::vec3(0.3f);
    v.medium.emission = {0.2f, 0.1f, 0.05f};
    v.medium.phase_g = 0.4f;
    return v;
}

// A camera 2.5 bounding-box diagonals away looking at the volume's centre, with a sun and a point
// light, froxels covering the volume.
Scene sceneAround(const Volume& v) {
    const shd::VolumeData d = compileVolume(v);
    const glm::vec3 lo(d.worldMin), hi(d.worldMax);
    const glm::vec3 centre = 0.5f * (lo + hi);
    const float diag = glm::length(hi - lo);
    Scene s;
    s.camera.target = centre;
    s.camera.position = centre + diag * glm::vec3(0.6f, 0.5f, 2.2f);
    s.camera.far = 8.0f * diag;
    s.froxels.tile_px = 8;
    s.froxels.slices = 48;
    s.froxels.far = 5.0f * diag;
    s.ambient = {0.05f, 0.06f, 0.08f};
    Light sun = makeLight(LightType::Directional);
    sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.4f));
    sun.shadows = false;
    Light point = makeLight(LightType::Point);
    point.position = centre + glm::vec3(0.3f * diag, 0.2f * diag, 0.4f * diag);
    point.range = 2.0f * diag;
    point.color = {1.0f, 0.7f, 0.5f};
    s.lights = {sun, point};
    s.volumes = {v};
    return s;
}

class GpuVdb : public test::ValidatedGpuTest {
protected:
    void SetUp() override {
        ValidatedGpuTest::SetUp();
        if (HasFatalFailure()) return;
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir = fs::temp_directory_path() / ("brume_gpu_vdb_" + std::to_string(getpid()) + "_" + info->name());
        fs::create_directories(dir);
    }
    void TearDown() override {
        std::error_code ec;
        fs::remove_all(dir, ec);
        ValidatedGpuTest::TearDown();
    }

    // GPU vs CPU froxel: media (the voxelize pass itself), integrated volumes and image. Also checks
    // that the vdb volume matters (its share of sigma_t), so an empty GPU volume fails.
    void expectMatchesCpu(const Scene& scene, const char* what) {
        RenderRequest request;
        request.width = 160;
        request.height = 90;
        request.threads = 2;
        const FroxelResult cpu = renderFroxelCpu(scene, request);
        auto gpu = renderer->render(scene, request, true);
        ASSERT_TRUE(gpu.ok()) << gpu.error().message;
        const FroxelVolumes& g = gpu.value().volumes;
        ASSERT_EQ(g.dims, cpu.volumes.dims);
        const double mediaErr = relativeMeanAbsError(asImage(g.mediaExtinction), asImage(cpu.volumes.mediaExtinction));
        const double scatErr =
            relativeMeanAbsError(asImage(g.integratedScattering), asImage(cpu.volumes.integratedScattering));
        const double imageErr = relativeMeanAbsError(gpu.value().image, cpu.image);
        EXPECT_TRUE(allFinite(gpu.value().image)) << what;
        EXPECT_LT(mediaErr, kTolerance) << what << ": sigma_t";
        EXPECT_LT(scatErr, kTolerance) << what << ": integrated scattering";
        EXPECT_LT(imageErr, kTolerance) << what << ": image";
        EXPECT_EQ(gpu.value().litFroxels, cpu.volumes.litFroxels) << what;
        EXPECT_GT(cpu.volumes.litFroxels, 0u) << what;

        // The vdb volumes' share of sigma_t: far above the tolerance, or the comparison proves nothing.
        Scene without = scene;
        std::erase_if(without.volumes, [](const Volume& v) { return v.type == VolumeType::Vdb; });
        const FroxelResult cpuWithout = renderFroxelCpu(without, request);
        const double share =
            relativeMeanAbsError(asImage(cpuWithout.volumes.mediaExtinction), asImage(cpu.volumes.mediaExtinction));
        EXPECT_GT(share, 20.0 * kTolerance) << what << ": the vdb volume barely shows, the test could not fail";
        std::printf("[gpu-vs-cpu vdb] %-24s sigma_t %.2e scattering %.2e image %.2e (vdb share of sigma_t %.2f)\n",
                    what, mediaErr, scatErr, imageErr, share);
    }

    fs::path dir;
};

}  // namespace

// A known smooth field (a lumpy ball) under a rotated, non-uniformly scaled voxel transform, placed
// by a rotated and scaled volume transform, overlapping an analytic box.
TEST_F(GpuVdb, SyntheticSkewedGridMatchesCpu) {
    auto grid = test::makeGrid("density", -20, 20, [](openvdb::Coord c) {
        const double r = std::sqrt(double(c.x() * c.x() + c.y() * c.y() + c.z() * c.z())) / 20.0;
        const double lumps = 0.6 + 0.4 * std::sin(0.5 * c.x()) * std::cos(0.35 * c.y() + 0.2 * c.z());
        return static_cast<float>(std::max(0.0, 1.0 - r) * lumps * 3.0);
    }, test::skewedTransform());
    test::writeGrids(dir / "ball.vdb", {grid});
    Volume v = vdbVolume(loadGrid(dir / "ball.vdb"));
    ASSERT_TRUE(v.density);
    v.transform.translation = {0.5f, -0.3f, 0.2f};
    v.transform.rotation_deg = {10.0f, -40.0f, 25.0f};
    v.transform.scale = {1.5f, 0.7f, 1.2f};
    v.density_scale = 1.5f;
    Scene s = sceneAround(v);
    Volume box;
    box.type = VolumeType::Box;
    box.transform.translation = s.camera.target;
    box.transform.scale = glm::vec3(1.5f);
    box.medium.scattering = glm::vec3(0.2f);
    s.volumes.push_back(box);
    expectMatchesCpu(s, "skewed synthetic grid");
}

// The done-when file: Houdini smoke, half floats, old file version.
TEST_F(GpuVdb, GafferSmokeMatchesCpu) {
    BRUME_REQUIRE_SHARED_VDB();
    Volume v = vdbVolume(loadGrid(test::sharedVdbDir() / "gaffer_smoke.vdb"));
    ASSERT_TRUE(v.density);
    v.density_scale = 4.0f;
    expectMatchesCpu(sceneAround(v), "gaffer_smoke.vdb");
}

// One storage buffer binds every grid: past the device's maxStorageBufferRange (128 MiB on
// lavapipe) the render is refused with a sentence saying so, not a validation error or a crash.
TEST_F(GpuVdb, GridsPastTheStorageBufferLimitAreRefusedClearly) {
    auto grid = test::makeGrid("density", 0, 63, [](openvdb::Coord) { return 1.0f; },
                               openvdb::math::Transform::createLinearTransform(0.01));
    test::writeGrids(dir / "cube.vdb", {grid});
    Volume v = vdbVolume(loadGrid(dir / "cube.vdb"));
    ASSERT_TRUE(v.density);
    // The same grid in many volumes: each is uploaded at its own offset, so the total grows.
    const size_t copies = (size_t(128) << 20) / v.density->size() + 1;
    Scene s = sceneAround(v);
    s.volumes.assign(copies, v);
    RenderRequest request;
    request.width = 64;
    request.height = 36;
    auto r = renderer->render(s, request);
    if (r.ok()) GTEST_SKIP() << "this device binds more than 128 MiB per storage buffer";
    EXPECT_NE(r.error().message.find("vdb grids take"), std::string::npos) << r.error().message;
    EXPECT_NE(r.error().message.find("storage buffer"), std::string::npos) << r.error().message;
    EXPECT_TRUE(r.error().badInput) << "the user can fix it: brume render exits 2";
    // The renderer stays usable after the refusal.
    s.volumes.resize(1);
    EXPECT_TRUE(renderer->render(s, request).ok());
}
