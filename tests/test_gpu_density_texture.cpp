// Density textures on the GPU: the voxelize pass's texture variants (with and without vdb volumes)
// sample the tiled, scrolled grid with PNanoVDB and must agree with their oracle, the CPU froxel
// renderer, within the GPU tests' 1% relative mean absolute error; strength 0 is the plain volume;
// the validation layer must stay silent.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <unistd.h>

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
constexpr int kN = 16;
constexpr double kTwoPi = 6.283185307179586;

DensityGridPtr loadGrid(const fs::path& file, const std::string& grid) {
    VdbImportOptions o;
    o.grid = grid;
    Result<VdbLoad> r = loadVdbDensity(file.string(), o);
    EXPECT_TRUE(r.ok()) << r.error().message;
    return r.ok() ? r.value().grid : nullptr;
}

DensityTexture texture(const DensityGridPtr& grid, float tile, float strength, glm::vec3 scroll) {
    DensityTexture t;
    t.tile_size_m = tile;
    t.strength = strength;
    t.scroll_mps = scroll;
    t.density = grid;
    t.mean = static_cast<float>(grid->activeBoxMean());
    return t;
}

class GpuDensityTexture : public test::ValidatedGpuTest {
protected:
    void SetUp() override {
        ValidatedGpuTest::SetUp();
        if (HasFatalFailure()) return;
        // A periodic field (a sine in x and in y + z) on [0, 15]^3, and a ball for a vdb volume.
        auto noise = test::makeGrid("noise", 0, kN - 1, [](openvdb::Coord c) {
            return static_cast<float>(1.0 + 0.6 * std::sin(kTwoPi * c.x() / kN) + 0.3 * std::sin(kTwoPi * (c.y() + c.z()) / kN));
        }, openvdb::math::Transform::createLinearTransform(0.1));
        auto ball = test::makeGrid("density", -10, 10, [](openvdb::Coord c) {
            const double r = std::sqrt(double(c.x() * c.x() + c.y() * c.y() + c.z() * c.z())) / 10.0;
            return static_cast<float>(std::max(0.0, 1.0 - r) * 2.0);
        }, openvdb::math::Transform::createLinearTransform(0.08));
        test::writeGrids(dir.path / "grids.vdb", {noise, ball});
        noiseGrid = loadGrid(dir.path / "grids.vdb", "noise");
        ballGrid = loadGrid(dir.path / "grids.vdb", "density");
    }

    // A textured box (and optionally a textured vdb ball) under the test view, sun and sky, at time t.
    Scene scene(bool withVdb, float strength) const {
        Scene s = test::sceneWithTestView();
        Volume box = test::boxFog({0.0f, 1.0f, 0.0f}, {5.0f, 2.0f, 5.0f}, 0.1f, {0.5f, 0.6f, 0.7f}, glm::vec3(0.2f));
        box.medium.emission = {0.3f, 0.15f, 0.05f};
        box.density_texture = texture(noiseGrid, 4.0f, strength, {0.8f, 0.0f, -0.3f});
        s.volumes.push_back(box);
        if (withVdb) {
            Volume ball;
            ball.type = VolumeType::Vdb;
            ball.density = ballGrid;
            ball.transform.translation = {1.0f, 1.2f, 1.5f};
            ball.medium.scattering = glm::vec3(1.5f);
            ball.density_texture = texture(noiseGrid, 1.0f, strength, {0.0f, 0.5f, 0.0f});
            s.volumes.push_back(ball);
        }
        s.lights.push_back(makeLight(LightType::Directional));
        s.froxels.tile_px = 4;
        s.froxels.slices = 48;
        s.froxels.far = 20.0f;
        s.time_s = 2.25f;
        return s;
    }

    static RenderRequest request() {
        RenderRequest r;
        r.width = 160;
        r.height = 90;
        r.threads = 2;
        return r;
    }

    // GPU vs CPU froxel: media (the voxelize pass itself) and image; the texture's share of sigma_t
    // must be far above the tolerance, or the comparison proves nothing.
    void expectMatchesCpu(const Scene& s, const char* what) {
        const FroxelResult cpu = renderFroxelCpu(s, request());
        auto gpu = renderer->render(s, request(), true);
        ASSERT_TRUE(gpu.ok()) << gpu.error().message;
        const FroxelVolumes& g = gpu.value().volumes;
        ASSERT_EQ(g.dims, cpu.volumes.dims);
        const double mediaErr = relativeMeanAbsError(asImage(g.mediaExtinction), asImage(cpu.volumes.mediaExtinction));
        const double imageErr = relativeMeanAbsError(gpu.value().image, cpu.image);
        Scene plain = s;
        for (Volume& v : plain.volumes) v.density_texture.reset();
        const FroxelResult cpuPlain = renderFroxelCpu(plain, request());
        const double share =
            relativeMeanAbsError(asImage(cpuPlain.volumes.mediaExtinction), asImage(cpu.volumes.mediaExtinction));
        std::printf("[gpu-vs-cpu texture] %-18s sigma_t %.2e image %.2e (texture's share of sigma_t %.2f)\n", what,
                    mediaErr, imageErr, share);
        EXPECT_TRUE(allFinite(gpu.value().image)) << what;
        EXPECT_LT(mediaErr, kTolerance) << what;
        EXPECT_LT(imageErr, kTolerance) << what;
        EXPECT_GT(share, 20.0 * kTolerance) << what;
    }

    test::TempDir dir{"gpu_density_texture", ::testing::UnitTest::GetInstance()->current_test_info()->name()};
    DensityGridPtr noiseGrid, ballGrid;
};

}  // namespace

TEST_F(GpuDensityTexture, TexturedBoxMatchesCpu) {
    ASSERT_TRUE(noiseGrid);
    expectMatchesCpu(scene(false, 1.0f), "box");
}

// The contrast exponent (each voxel's value^exponent before the trilinear mix, shared/density_texture.h).
TEST_F(GpuDensityTexture, TextureExponentMatchesCpu) {
    ASSERT_TRUE(noiseGrid);
    Scene s = scene(false, 1.0f);
    DensityTexture& t = *s.volumes[0].density_texture;
    t.exponent = 2.5f;
    t.mean = static_cast<float>(noiseGrid->activeBoxMean(t.exponent));
    expectMatchesCpu(s, "box, exponent 2.5");
}

TEST_F(GpuDensityTexture, TexturedBoxAndVdbVolumeMatchCpu) {
    ASSERT_TRUE(noiseGrid && ballGrid);
    expectMatchesCpu(scene(true, 1.5f), "box + vdb ball");
}

// Strength 0 through the texture variant gives the plain volume's image (the same arithmetic on
// the density: x 1.0 exactly).
TEST_F(GpuDensityTexture, StrengthZeroIsThePlainVolume) {
    ASSERT_TRUE(noiseGrid);
    const Scene zero = scene(false, 0.0f);
    Scene plain = zero;
    plain.volumes[0].density_texture.reset();
    auto a = renderer->render(zero, request());
    auto b = renderer->render(plain, request());
    ASSERT_TRUE(a.ok() && b.ok());
    const double err = relativeMeanAbsError(a.value().image, b.value().image);
    std::printf("[gpu texture] strength 0 vs plain %.2e\n", err);
    EXPECT_LT(err, 1e-6);
}

// The detail layer (shared/density_texture.h detailCell, detailDensityFactor): a second, finer,
// sharpened and scrolled copy of the noise multiplied in, on the box and on the vdb ball. Besides
// the texture's share, the detail's own share of sigma_t (against the texture alone) must be far
// above the tolerance.
TEST_F(GpuDensityTexture, DetailLayerMatchesCpu) {
    ASSERT_TRUE(noiseGrid && ballGrid);
    Scene s = scene(true, 1.0f);
    Scene alone = s;
    for (Volume& v : s.volumes) {
        TextureLayer d = makeDetailLayer();
        d.tile_size_m = 1.3f;
        d.strength = 0.8f;
        d.exponent = 2.0f;
        d.scroll_mps = {-0.4f, 0.2f, 0.6f};
        d.density = noiseGrid;
        d.mean = static_cast<float>(noiseGrid->activeBoxMean(d.exponent));
        v.density_texture->detail = d;
    }
    expectMatchesCpu(s, "box + vdb, detail");
    const double share = relativeMeanAbsError(asImage(renderFroxelCpu(alone, request()).volumes.mediaExtinction),
                                              asImage(renderFroxelCpu(s, request()).volumes.mediaExtinction));
    std::printf("[gpu texture] the detail's share of sigma_t %.2f\n", share);
    EXPECT_GT(share, 10.0 * kTolerance);
}

// A detail of strength 0 through the GPU's two-layer loop is the texture alone.
TEST_F(GpuDensityTexture, DetailStrengthZeroIsTheTextureAlone) {
    ASSERT_TRUE(noiseGrid);
    Scene s = scene(false, 1.0f);
    const Scene alone = s;
    TextureLayer d = makeDetailLayer();
    d.strength = 0.0f;
    d.density = noiseGrid;
    d.mean = static_cast<float>(noiseGrid->activeBoxMean());
    s.volumes[0].density_texture->detail = d;
    auto a = renderer->render(s, request());
    auto b = renderer->render(alone, request());
    ASSERT_TRUE(a.ok() && b.ok());
    const double err = relativeMeanAbsError(a.value().image, b.value().image);
    std::printf("[gpu texture] detail strength 0 vs the texture alone %.2e\n", err);
    EXPECT_LT(err, 1e-6);
}

// height_falloff inside a vdb volume (issue 15: "inside any local volume"): the GPU's vdbDensity
// (voxelize and the vdb fog shadow march) against the CPU, without a texture (the vdb variant) and
// with one; the falloff's share of sigma_t is far above the tolerance.
TEST_F(GpuDensityTexture, VdbHeightFalloffMatchesCpu) {
    ASSERT_TRUE(ballGrid);
    Scene s = scene(true, 1.0f);
    s.volumes.erase(s.volumes.begin());  // the ball alone
    s.volumes[0].density_texture.reset();
    s.volumes[0].medium.scattering = glm::vec3(3.0f);
    const Scene flat = s;
    s.volumes[0].height_falloff = 1.5f;
    const FroxelResult cpu = renderFroxelCpu(s, request());
    auto gpu = renderer->render(s, request(), true);
    ASSERT_TRUE(gpu.ok()) << gpu.error().message;
    const double mediaErr = relativeMeanAbsError(asImage(gpu.value().volumes.mediaExtinction), asImage(cpu.volumes.mediaExtinction));
    const double imageErr = relativeMeanAbsError(gpu.value().image, cpu.image);
    const double share = relativeMeanAbsError(asImage(renderFroxelCpu(flat, request()).volumes.mediaExtinction),
                                              asImage(cpu.volumes.mediaExtinction));
    std::printf("[gpu-vs-cpu vdb height_falloff] sigma_t %.2e image %.2e (the falloff's share %.2f)\n", mediaErr, imageErr, share);
    EXPECT_LT(mediaErr, kTolerance);
    EXPECT_LT(imageErr, kTolerance);
    EXPECT_GT(share, 10.0 * kTolerance);
    s.volumes[0].density_texture = texture(noiseGrid, 1.0f, 1.0f, {0.0f, 0.5f, 0.0f});
    expectMatchesCpu(s, "vdb, height_falloff");
}
