// VDB volumes in the fog shadows on the GPU: the shadow volume pass's vdb variant marches the grids
// (shaders/vdb_shadow.glsl) at the same points as the CPU froxel renderer (core/vdb_shadow.cpp), and
// both read the vdb layer with the same blend. GPU vs CPU within the GPU tests' 1% relative mean
// absolute error; the vdb shadow's own effect must be far larger, or the comparison proves nothing.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <filesystem>

#include "core/compile.h"
#include "core/media_region.h"
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

// A 3 x 1 x 3 m block (0.1 m voxels) of a bumpy density, so that the march's sample points matter.
DensityGridPtr bumpyBlock(const fs::path& dir) {
    auto g = test::makeGrid("density", -15, 14, [](openvdb::Coord c) {
        return 0.6f + 0.4f * std::sin(0.7f * static_cast<float>(c.x())) * std::cos(0.5f * static_cast<float>(c.z()));
    }, openvdb::math::Transform::createLinearTransform(0.1));
    test::writeGrids(dir / "bumpy.vdb", {g});
    Result<VdbLoad> r = loadVdbDensity((dir / "bumpy.vdb").string(), {});
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
    return r.ok() ? r.value().grid : nullptr;
}

// The block 3 m up over height haze and the ground, a slanted sun and a point light beside it.
Scene blockScene(const DensityGridPtr& grid) {
    Scene s = test::sceneWithTestView();
    s.camera.position = {5.0f, 2.5f, 9.0f};
    s.camera.target = {0.0f, 1.5f, 0.0f};
    Volume v;
    v.type = VolumeType::Vdb;
    v.density = grid;
    v.transform.translation = {0.0f, 3.0f, 0.0f};
    v.transform.scale = {1.0f, 0.5f, 1.0f};
    v.medium.scattering = {2.0f, 2.2f, 2.4f};
    v.medium.absorption = glm::vec3(0.5f);
    Volume haze;
    haze.type = VolumeType::Height;
    haze.base_height = 0.5f;
    haze.falloff = 0.8f;
    haze.medium.scattering = glm::vec3(0.15f);
    s.volumes = {v, haze};
    Light sun = makeLight(LightType::Directional);
    sun.direction = glm::normalize(glm::vec3(0.4f, -1.0f, 0.2f));
    sun.intensity = 3.0f;
    Light point = makeLight(LightType::Point);
    point.position = {0.5f, 4.5f, 0.5f};
    point.intensity = 20.0f;
    point.range = 12.0f;
    s.lights = {sun, point};
    s.geometry = {test::groundPlane(glm::vec3(0.6f))};
    return s;
}

class GpuVdbShadow : public test::ValidatedGpuTest {
protected:

    // GPU vs CPU: the source (the light pass, which reads the vdb layer), integrated scattering and
    // the image (the ground reads it too); the CPU without vdb shadows must differ by far more.
    void expectMatchesCpu(const Scene& scene, Quality q, const char* what, int shadowReduction = 0) {
        RenderRequest request;
        request.shadowReduction = shadowReduction;
        request.width = 160;
        request.height = 90;
        request.quality = q;
        request.threads = 2;
        const FroxelResult cpu = renderFroxelCpu(scene, request);
        auto gpu = renderer->render(scene, request, true);
        ASSERT_TRUE(gpu.ok()) << gpu.error().message;
        const FroxelVolumes& g = gpu.value().volumes;
        const double sourceErr = relativeMeanAbsError(asImage(g.source), asImage(cpu.volumes.source));
        const double scatErr =
            relativeMeanAbsError(asImage(g.integratedScattering), asImage(cpu.volumes.integratedScattering));
        const double imageErr = relativeMeanAbsError(gpu.value().image, cpu.image);
        request.vdbShadows = false;
        const FroxelResult without = renderFroxelCpu(scene, request);
        const double share = relativeMeanAbsError(without.image, cpu.image);
        std::printf("[gpu-vs-cpu vdb shadow] %-22s source %.2e scattering %.2e image %.2e (vdb shadows change "
                    "the image by %.3f)\n",
                    what, sourceErr, scatErr, imageErr, share);
        EXPECT_TRUE(allFinite(gpu.value().image)) << what;
        EXPECT_LT(sourceErr, kTolerance) << what;
        EXPECT_LT(scatErr, kTolerance) << what;
        EXPECT_LT(imageErr, kTolerance) << what;
        // A GPU that ignored the vdb layer would be off by `share`: over twice the tolerance.
        EXPECT_GT(share, 2.0 * kTolerance) << what << ": the vdb shadow barely shows, the test could not fail";
    }

};

}  // namespace

// High: sun and point light shadowed (reduction 2); low: the sun only, here at reduction 2 (low's own
// 4 puts cells ~6 m apart at this size, and the block's shadow falls between them: docs/shadows.md).
TEST_F(GpuVdbShadow, BlockShadowsMatchCpu) {
    test::TempDir dir("gpu_vdb_shadow", "block");
    const Scene scene = blockScene(bumpyBlock(dir.path));
    expectMatchesCpu(scene, Quality::High, "bumpy block, high");
    expectMatchesCpu(scene, Quality::Low, "bumpy block, low", 2);
}

// The done-when: the smoke lit and shadowed, GPU matching CPU.
TEST_F(GpuVdbShadow, GafferSmokeShadowsMatchCpu) {
    BRUME_REQUIRE_SHARED_VDB();
    Result<VdbLoad> load = loadVdbDensity((test::sharedVdbDir() / "gaffer_smoke.vdb").string(), {});
    ASSERT_TRUE(load.ok()) << load.error().message;
    Volume v;
    v.type = VolumeType::Vdb;
    v.density = load.value().grid;
    v.density_scale = 0.5f;
    v.medium.scattering = glm::vec3(1.0f);
    v.medium.absorption = glm::vec3(0.1f);
    Scene s;
    s.camera.target = {-7.0f, 40.0f, 0.5f};
    s.camera.position = {-7.0f, 40.0f, 130.0f};
    s.camera.far = 300.0f;
    s.froxels.far = 200.0f;
    s.ambient = {0.02f, 0.025f, 0.03f};
    Light sun = makeLight(LightType::Directional);
    sun.direction = glm::normalize(glm::vec3(-1.0f, -0.4f, -0.3f));
    sun.intensity = 3.0f;
    s.lights = {sun};
    s.volumes = {v};
    expectMatchesCpu(s, Quality::High, "gaffer_smoke.vdb, high");

    // Occupancy culling (the voxelize pass and the shadow march skip empty cells) changes nothing.
    RenderRequest request;
    request.width = 160;
    request.height = 90;
    auto on = renderer->render(s, request, true);
    request.vdbCulling = false;
    auto off = renderer->render(s, request, true);
    ASSERT_TRUE(on.ok() && off.ok());
    const double err = relativeMeanAbsError(on.value().image, off.value().image);
    const double mediaErr = relativeMeanAbsError(asImage(on.value().volumes.mediaExtinction),
                                                 asImage(off.value().volumes.mediaExtinction));
    std::printf("[gpu vdb culling] on vs off: image %.3g, sigma_t %.3g\n", err, mediaErr);
    EXPECT_LT(err, 1e-6);
    EXPECT_LT(mediaErr, 1e-6);
}

// The shadow volume pass computes only the cells some reader needs (core/media_region.h
// shadowCellRegion): around the block's froxels for the light pass, and the whole volume once the
// ground reads the vdb layer. A renderer that fills its volume with NaN before every frame
// (GpuOptions::poisonShadowVolume) must give the same froxel volumes and image, byte for byte, as one
// over the whole grid, with and without the ground (without it the pass did skip cells).
TEST(GpuVdbShadowRegion, ShadowVolumeRegionWritesEveryCellItsReadersRead) {
    test::TempDir dir("gpu_vdb_shadow", "region");
    test::PoisonedRegionAndWholeGrid pair;
    pair.create();
    if (HasFatalFailure()) return;
    Scene scene = blockScene(bumpyBlock(dir.path));
    scene.volumes.pop_back();  // no unbounded haze: the media region is the block's
    for (bool ground : {true, false}) {
        if (!ground) scene.geometry.clear();
        RenderRequest request;
        request.width = 160;
        request.height = 90;
        request.quality = Quality::High;
        auto g = pair.region->render(scene, request, true);
        ASSERT_TRUE(g.ok()) << g.error().message;
        auto w = pair.whole->render(scene, request, true);
        ASSERT_TRUE(w.ok()) << w.error().message;
        const FroxelVolumes& gv = g.value().volumes;
        const FroxelVolumes& wv = w.value().volumes;
        ASSERT_EQ(gv.source.size(), wv.source.size());
        EXPECT_EQ(std::memcmp(gv.source.data(), wv.source.data(), gv.source.size() * sizeof(glm::vec4)), 0) << ground;
        const Image& gi = g.value().image;
        const Image& wi = w.value().image;
        ASSERT_EQ(gi.pixels.size(), wi.pixels.size());
        EXPECT_EQ(std::memcmp(gi.pixels.data(), wi.pixels.data(), gi.pixels.size() * sizeof(glm::vec3)), 0) << ground;
        EXPECT_GT(g.value().litFroxels, 0u);
        const FroxelRegion cells = shadowCellRegion(mediaFroxelRegion(compileScene(scene), gv.frame), gv.frame, ground);
        const glm::ivec3 all = shd::shadowVolumeDims(gv.dims, gv.frame.shadowReduction);
        if (ground) EXPECT_EQ(cells.froxels(), int64_t(all.x) * all.y * all.z);
        else EXPECT_LT(cells.froxels() * 3, int64_t(all.x) * all.y * all.z);
    }
    pair.expectNoValidationMessages();
}
