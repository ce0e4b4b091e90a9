// Occupancy culling of vdb volumes (shaders/shared/vdb.h, core/density_grid.cpp): the renderers skip
// the tree walk where the coarse cells say every trilinear tap is 0. The image must not change, and
// froxels inside a grid's bounds but in empty cells must be skipped.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "core/compile.h"
#include "core/render.h"
#include "io/vdb_import.h"
#include "test_support.h"
#include "vdb_test_util.h"

using namespace brume;
namespace fs = std::filesystem;

namespace {

// Two lumpy balls of 0.1 m voxels at opposite corners of one grid: its bounds are mostly empty.
DensityGridPtr twoBalls(const fs::path& dir) {
    auto ball = [](openvdb::Coord c, openvdb::Coord centre) {
        const double r = (c.asVec3d() - centre.asVec3d()).length();
        return static_cast<float>(std::max(0.0, 1.0 - r / 10.0) * (1.0 + 0.3 * std::sin(0.9 * c.x())));
    };
    auto g = test::makeGrid("density", -40, 40, [&](openvdb::Coord c) {
        return ball(c, openvdb::Coord(-28, -28, -28)) + ball(c, openvdb::Coord(28, 28, 28));
    }, openvdb::math::Transform::createLinearTransform(0.1));
    test::writeGrids(dir / "balls.vdb", {g});
    Result<VdbLoad> r = loadVdbDensity((dir / "balls.vdb").string(), {});
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
    return r.ok() ? r.value().grid : nullptr;
}

Scene ballsScene(const DensityGridPtr& grid) {
    Scene s = test::sceneWithTestView();
    Volume v;
    v.type = VolumeType::Vdb;
    v.density = grid;
    v.transform.translation = {0.0f, 1.2f, 0.0f};
    v.medium.scattering = glm::vec3(3.0f);
    v.medium.absorption = glm::vec3(0.3f);
    s.volumes = {v};
    Light sun = makeLight(LightType::Directional);
    sun.direction = glm::normalize(glm::vec3(0.5f, -1.0f, -0.3f));
    s.lights = {sun};
    s.geometry = {test::groundPlane(glm::vec3(0.5f))};
    return s;
}

RenderRequest request() {
    RenderRequest r;
    r.width = 160;
    r.height = 90;
    r.threads = 2;
    return r;
}

}  // namespace

// Culling on and off give the same image and media (the skipped walks would have returned 0).
TEST(VdbCulling, SameImageWithAndWithoutCulling) {
    test::TempDir dir("vdb_culling", "same");
    const Scene scene = ballsScene(twoBalls(dir.path));
    RenderRequest req = request();
    const FroxelResult on = renderFroxelCpu(scene, req);
    req.vdbCulling = false;
    const FroxelResult off = renderFroxelCpu(scene, req);
    const double err = relativeMeanAbsError(on.image, off.image);
    std::printf("culling on vs off: image %.3g\n", err);
    EXPECT_LT(err, 1e-6);
    EXPECT_EQ(on.volumes.mediaExtinction, off.volumes.mediaExtinction);
    EXPECT_GT(on.volumes.litFroxels, 20u);  // the balls show
}

// Of the froxels whose sample point lies inside the grid's bounds, those in empty cells skip the walk:
// here most of them (the bounds are mostly empty space), and each has density 0 when walked anyway.
// Every froxel with density > 0 lies in an occupied cell.
TEST(VdbCulling, FroxelsInEmptyCellsSkipTheWalk) {
    test::TempDir dir("vdb_culling", "skip");
    const DensityGridPtr grid = twoBalls(dir.path);
    ASSERT_TRUE(grid);
    ASSERT_NE(grid->occupancyOffset(), 0u);
    const Scene scene = ballsScene(grid);
    RenderRequest req = request();
    req.vdbCulling = false;
    const FroxelResult r = renderFroxelCpu(scene, req);
    const CompiledScene cs = compileScene(scene);
    const shd::VolumeData& v = cs.volumes[0];
    const FroxelVolumes& f = r.volumes;
    size_t inBounds = 0, skipped = 0, skippedNonZero = 0;
    for (int z = 0; z < f.dims.z; ++z)
        for (int y = 0; y < f.dims.y; ++y)
            for (int x = 0; x < f.dims.x; ++x) {
                const glm::vec3 p = shd::worldFromFroxelCoord(glm::vec3(x, y, z) + glm::vec3(f.frame.jitter), f.frame);
                if (!shd::insideBounds(v, p)) continue;
                ++inBounds;
                const size_t i = (static_cast<size_t>(z) * static_cast<size_t>(f.dims.y) + static_cast<size_t>(y)) *
                                     static_cast<size_t>(f.dims.x) + static_cast<size_t>(x);
                const bool occupied = grid->occupied(shd::vdbIndexPos(v, p));
                const bool nonZero = f.mediaExtinction[i].x > 0.0f;
                if (!occupied) ++skipped;
                if (!occupied && nonZero) ++skippedNonZero;
            }
    std::printf("froxels in the grid's bounds %zu, in empty cells (walk skipped) %zu\n", inBounds, skipped);
    EXPECT_GT(inBounds, 1000u);
    EXPECT_GT(skipped, inBounds / 2);
    EXPECT_EQ(skippedNonZero, 0u);
}

// The real smoke: culling changes nothing there either.
TEST(VdbCulling, GafferSmokeSameWithAndWithoutCulling) {
    BRUME_REQUIRE_SHARED_VDB();
    Result<VdbLoad> load = loadVdbDensity((test::sharedVdbDir() / "gaffer_smoke.vdb").string(), {});
    ASSERT_TRUE(load.ok()) << load.error().message;
    Scene s = ballsScene(load.value().grid);
    s.volumes[0].transform.scale = glm::vec3(0.05f);
    s.volumes[0].transform.translation = {0.0f, 0.5f, 0.0f};
    RenderRequest req = request();
    const FroxelResult on = renderFroxelCpu(s, req);
    req.vdbCulling = false;
    const FroxelResult off = renderFroxelCpu(s, req);
    EXPECT_LT(relativeMeanAbsError(on.image, off.image), 1e-6);
    EXPECT_EQ(on.volumes.mediaExtinction, off.volumes.mediaExtinction);
}
