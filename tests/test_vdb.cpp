// OpenVDB import: the real files of ../shared/vdb behave as its README says, synthetic grids (known
// fields, rotated and non-uniformly scaled transforms) sample and render as their analytic
// equivalents, bad values are sanitized, and corrupt files give one-sentence errors, never a crash.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <sys/wait.h>
#include <fstream>
#include <iterator>
#include <unistd.h>

#include "core/compile.h"
#include "core/render.h"
#include "io/image_io.h"
#include "io/vdb_import.h"
#include "test_support.h"
#include "vdb_test_util.h"

using namespace brume;
namespace fs = std::filesystem;

namespace {

class Vdb : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("brume_vdb_" + std::to_string(getpid()) + "_" + info->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    static std::string real(const char* name) { return (test::sharedVdbDir() / name).string(); }

    static VdbLoad load(const std::string& path, const std::string& grid = "density") {
        VdbImportOptions o;
        o.grid = grid;
        Result<VdbLoad> r = loadVdbDensity(path, o);
        EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
        return r.ok() ? std::move(r).value() : VdbLoad{};
    }
    static std::string loadError(const std::string& path, const std::string& grid = "density", uint64_t limit = 1ull << 32) {
        VdbImportOptions o;
        o.grid = grid;
        o.memoryLimitBytes = limit;
        Result<VdbLoad> r = loadVdbDensity(path, o);
        EXPECT_FALSE(r.ok());
        return r.ok() ? "" : r.error().message;
    }
    static bool mentions(const std::vector<std::string>& warnings, const std::string& text) {
        for (const std::string& w : warnings)
            if (w.find(text) != std::string::npos) return true;
        return false;
    }

    fs::path dir_;
};

// 1 + 0.01 i + 0.02 j + 0.015 k: positive on [-16, 16]^3, and trilinear interpolation is exact for it.
float linearField(glm::dvec3 q) { return static_cast<float>(1.0 + 0.01 * q.x + 0.02 * q.y + 0.015 * q.z); }

}  // namespace

// ---- ../shared/vdb, row by row of its README table ----

TEST_F(Vdb, GafferSmokeIsAHalfFloatFogVolumeInTheOldFormat) {
    BRUME_REQUIRE_SHARED_VDB();
    const VdbLoad l = load(real("gaffer_smoke.vdb"));
    ASSERT_TRUE(l.grid);
    EXPECT_EQ(l.grid->activeVoxels(), 1049275u);
    EXPECT_TRUE(l.warnings.empty());
    EXPECT_NEAR(l.grid->gridFromIndex()[0][0], 0.476f, 1e-3f);
}

TEST_F(Vdb, GafferSphereLevelSetBecomesFogWithAWarning) {
    BRUME_REQUIRE_SHARED_VDB();
    const VdbLoad l = load(real("gaffer_sphere.vdb"));  // no "density": the only scalar grid, ls_sphere
    ASSERT_TRUE(l.grid);
    EXPECT_EQ(l.gridName, "ls_sphere");
    EXPECT_TRUE(mentions(l.warnings, "level set")) << ::testing::PrintToString(l.warnings);
    // Inside = 1 at the centre, 0 far outside (voxel 0.05 m, radius ~3 m).
    EXPECT_FLOAT_EQ(l.grid->sampleIndex(glm::vec3(0.0f)), 1.0f);
    EXPECT_FLOAT_EQ(l.grid->sampleIndex(glm::vec3(80.0f, 0.0f, 0.0f)), 0.0f);
}

TEST_F(Vdb, GafferArnoldSphereBloscFileLoads) {
    BRUME_REQUIRE_SHARED_VDB();
    const VdbLoad l = load(real("gaffer_arnold_sphere.vdb"));
    ASSERT_TRUE(l.grid);
    EXPECT_EQ(l.grid->activeVoxels(), 465u);
}

TEST_F(Vdb, OiioSphereIsDenseInsideAndEmptyOutside) {
    BRUME_REQUIRE_SHARED_VDB();
    const VdbLoad l = load(real("oiio_sphere.vdb"));
    ASSERT_TRUE(l.grid);
    EXPECT_EQ(l.grid->activeVoxels(), 9047u);
    EXPECT_GT(l.grid->sampleIndex(glm::vec3(0.0f)), 0.5f);
    EXPECT_EQ(l.grid->sampleIndex(glm::vec3(14.0f, 0.0f, 0.0f)), 0.0f);
}

TEST_F(Vdb, OiioSphereCdHasNoDensityAndTheErrorListsTheGrids) {
    BRUME_REQUIRE_SHARED_VDB();
    const std::string e = loadError(real("oiio_sphereCd.vdb"));
    EXPECT_NE(e.find("oiio_sphereCd.vdb"), std::string::npos) << e;
    EXPECT_NE(e.find("'Cd' (vec3s, unknown)"), std::string::npos) << e;
}

TEST_F(Vdb, UsdSmokeFirstFrameIsEmptyWithAWarning) {
    BRUME_REQUIRE_SHARED_VDB();
    const VdbLoad l = load(real("usd_smoke_000001.vdb"));
    ASSERT_TRUE(l.grid);
    EXPECT_TRUE(l.grid->empty());
    EXPECT_TRUE(mentions(l.warnings, "is empty"));
    Volume v;
    v.type = VolumeType::Vdb;
    v.density = l.grid;
    const shd::VolumeData d = compileVolume(v);
    EXPECT_FALSE(shd::insideBounds(d, glm::vec3(0.0f)));  // no point is inside an empty volume
}

TEST_F(Vdb, UsdSmokeSecondFrameKeepsItsNonUniformVoxels) {
    BRUME_REQUIRE_SHARED_VDB();
    const VdbLoad l = load(real("usd_smoke_000002.vdb"));
    ASSERT_TRUE(l.grid);
    EXPECT_EQ(l.grid->activeVoxels(), 71983u);
    const glm::mat4 m = l.grid->gridFromIndex();
    EXPECT_NEAR(m[0][0], 0.1326f, 1e-4f);
    EXPECT_NEAR(m[1][1], 0.1329f, 1e-4f);
    EXPECT_NEAR(m[2][2], 0.1317f, 1e-4f);
}

TEST_F(Vdb, PlasmaDxrNewestFormatWithEightGridsPicksDensity) {
    BRUME_REQUIRE_SHARED_VDB();
    const VdbLoad l = load(real("plasmadxr_fluid_data_0001.vdb"));
    ASSERT_TRUE(l.grid);
    EXPECT_EQ(l.gridName, "density");
    EXPECT_EQ(l.grid->activeVoxels(), 1016u);
    const VdbLoad t = load(real("plasmadxr_fluid_data_0001.vdb"), "temperature");
    ASSERT_TRUE(t.grid);
    EXPECT_EQ(t.grid->activeVoxels(), 1016u);
    EXPECT_NE(loadError(real("plasmadxr_fluid_data_0001.vdb"), "velocity").find("vec3s"), std::string::npos);
}

TEST_F(Vdb, InfoListsEveryGridWithItsNanoVdbSize) {
    BRUME_REQUIRE_SHARED_VDB();
    Result<std::vector<VdbGridInfo>> r = inspectVdb(real("plasmadxr_fluid_data_0001.vdb"));
    ASSERT_TRUE(r.ok()) << r.error().message;
    ASSERT_EQ(r.value().size(), 8u);
    for (const VdbGridInfo& g : r.value()) {
        if (g.name != "density") continue;
        EXPECT_EQ(g.activeVoxels, 1016u);
        EXPECT_GT(g.nanovdbBytes, g.nanovdbFp8Bytes);
        EXPECT_GE(g.valueMin, 0.0);
    }
}

// ---- synthetic grids ----

// A linear field under a rotated, non-uniformly scaled voxel transform, placed by a rotated and
// scaled volume transform: the density at world points (computed with OpenVDB's own transform, not
// Brume's matrices) is the field's value, to float precision.
TEST_F(Vdb, SkewedTransformsComposeAndTrilinearIsExactOnALinearField) {
    auto xform = test::skewedTransform();
    auto grid = test::makeGrid("density", -16, 16, [](openvdb::Coord c) {
        return linearField(glm::dvec3(c.x(), c.y(), c.z()));
    }, xform);
    test::writeGrids(dir_ / "linear.vdb", {grid});
    Volume v;
    v.type = VolumeType::Vdb;
    v.transform.translation = {2.0f, -1.0f, 0.5f};
    v.transform.rotation_deg = {10.0f, -40.0f, 25.0f};
    v.transform.scale = {1.5f, 0.7f, 1.2f};
    v.density_scale = 2.0f;
    v.density = load((dir_ / "linear.vdb").string()).grid;
    ASSERT_TRUE(v.density);
    Scene scene;
    scene.volumes.push_back(v);
    const CompiledScene cs = compileScene(scene);
    const glm::mat4 worldFromLocal = v.transform.worldFromLocal();
    double maxErr = 0.0;
    int n = 0;
    for (double a = -14.3; a <= 14.0; a += 3.7)
        for (double b = -13.9; b <= 14.0; b += 4.1)
            for (double c = -14.1; c <= 14.0; c += 3.3) {
                const openvdb::Vec3d g = xform->indexToWorld(openvdb::Vec3d(a, b, c));
                const glm::vec3 world = glm::vec3(worldFromLocal * glm::vec4(g.x(), g.y(), g.z(), 1.0f));
                ASSERT_TRUE(shd::insideBounds(cs.volumes[0], world));
                const double expected = 2.0 * linearField(glm::dvec3(a, b, c));
                maxErr = std::max(maxErr, std::abs(volumeDensity(cs, 0, world) - expected) / expected);
                ++n;
            }
    std::printf("skewed linear field: max relative error %.3g over %d points\n", maxErr, n);
    EXPECT_LT(maxErr, 1e-4);
}

TEST_F(Vdb, BoundsHoldEveryActiveVoxelAndNothingOutsideHasDensity) {
    auto xform = test::skewedTransform();
    auto grid = test::makeGrid("density", -6, 6, [](openvdb::Coord) { return 1.0f; }, xform);
    test::writeGrids(dir_ / "cube.vdb", {grid});
    Volume v;
    v.type = VolumeType::Vdb;
    v.density = load((dir_ / "cube.vdb").string()).grid;
    const shd::VolumeData d = compileVolume(v);
    // Trilinear support reaches one voxel past the active ones (just inside it, to stay off the rounding).
    for (double i : {-6.99, 6.99})
        for (double j : {-6.99, 6.99})
            for (double k : {-6.99, 6.99}) {
                const openvdb::Vec3d w = xform->indexToWorld(openvdb::Vec3d(i, j, k));
                EXPECT_TRUE(shd::insideBounds(d, glm::vec3(w.x(), w.y(), w.z())));
            }
    Scene s;
    s.volumes.push_back(v);
    const CompiledScene cs = compileScene(s);
    const glm::vec3 outside = glm::vec3(d.worldMax) + glm::vec3(0.01f);
    EXPECT_EQ(mediaAt(cs, outside).sigmaT, glm::vec3(0.0f));
}

TEST_F(Vdb, NanInfAndNegativeValuesBecomeZeroAndAreCounted) {
    auto grid = test::makeGrid("density", 0, 3, [](openvdb::Coord c) {
        if (c == openvdb::Coord(0, 0, 0)) return std::nanf("");
        if (c == openvdb::Coord(1, 0, 0)) return INFINITY;
        if (c == openvdb::Coord(2, 0, 0)) return -2.0f;
        return 0.5f;
    }, openvdb::math::Transform::createLinearTransform(0.1), /*keepAll=*/true);
    test::writeGrids(dir_ / "bad.vdb", {grid});
    const VdbLoad l = load((dir_ / "bad.vdb").string());
    ASSERT_TRUE(l.grid);
    EXPECT_TRUE(mentions(l.warnings, "3 NaN, infinite or negative values")) << ::testing::PrintToString(l.warnings);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(l.grid->sampleIndex(glm::vec3(float(i), 0.0f, 0.0f)), 0.0f);
    EXPECT_EQ(l.grid->sampleIndex(glm::vec3(3.0f, 0.0f, 0.0f)), 0.5f);
    EXPECT_EQ(l.grid->sampleIndex(glm::vec3(0.5f, 0.0f, 0.0f)), 0.0f);  // no NaN leaks through interpolation
}

TEST_F(Vdb, GridChoiceByNameIndexAndFallback) {
    auto xf = openvdb::math::Transform::createLinearTransform(0.1);
    auto one = test::makeGrid("density", 0, 1, [](openvdb::Coord) { return 1.0f; }, xf);
    auto two = test::makeGrid("density", 0, 1, [](openvdb::Coord) { return 2.0f; }, xf);
    test::writeGrids(dir_ / "dup.vdb", {one, two});
    const std::string dup = (dir_ / "dup.vdb").string();
    EXPECT_EQ(load(dup, "density#1").grid->sampleIndex(glm::vec3(0.0f)), 2.0f);
    EXPECT_EQ(load(dup, "density#0").grid->sampleIndex(glm::vec3(0.0f)), 1.0f);
    const VdbLoad first = load(dup);
    EXPECT_EQ(first.gridName, "density#0");
    EXPECT_TRUE(mentions(first.warnings, "several grids"));
    const std::string e = loadError(dup, "smoke");
    EXPECT_NE(e.find("'density#0' (float, fog volume), 'density#1' (float, fog volume)"), std::string::npos) << e;

    auto smoke = test::makeGrid("smoke", 0, 1, [](openvdb::Coord) { return 3.0f; }, xf);
    auto vel = openvdb::Vec3SGrid::create();
    vel->setName("vel");
    test::writeGrids(dir_ / "smoke.vdb", {smoke, vel});
    const VdbLoad fallback = load((dir_ / "smoke.vdb").string());
    EXPECT_EQ(fallback.gridName, "smoke");
    EXPECT_TRUE(mentions(fallback.warnings, "no grid named 'density'"));
}

TEST_F(Vdb, MemoryCapRefusesOversizedGrids) {
    auto grid = test::makeGrid("density", 0, 15, [](openvdb::Coord) { return 1.0f; },
                               openvdb::math::Transform::createLinearTransform(0.1));
    test::writeGrids(dir_ / "big.vdb", {grid});
    const std::string e = loadError((dir_ / "big.vdb").string(), "density", 1024);
    EXPECT_NE(e.find("over the limit"), std::string::npos) << e;
    EXPECT_NE(e.find("--vdb-memory-mb"), std::string::npos) << e;
}

// ---- rendering ----

namespace {

// Density 1 on index [0, 39]^3 with 0.05 m voxels: trilinear ramps to 0 over one voxel outside, so
// along any axis-aligned line its integral equals that of the hard box [-0.025, 1.975]^3 m (other
// lines differ near the edges, by about a voxel).
Scene cubeScene(const DensityGridPtr& grid, bool sun = true) {
    Scene s;
    s.camera.position = {0.95f, 1.5f, 3.6f};
    s.camera.target = {0.95f, 0.9f, 0.95f};
    s.camera.far = 50.0f;
    s.froxels.tile_px = 4;
    s.froxels.slices = 64;
    s.froxels.far = 12.0f;
    s.ambient = {0.02f, 0.025f, 0.03f};
    Light sunLight = makeLight(LightType::Directional);
    sunLight.direction = {0.0f, -1.0f, 0.0f};  // axis-aligned: shadow rays see the same integral in both
    sunLight.intensity = 3.0f;
    if (sun) s.lights.push_back(sunLight);
    Volume v;
    if (grid) {
        v.type = VolumeType::Vdb;
        v.density = grid;
    } else {
        v.type = VolumeType::Box;
        v.edge_fade = 0.0f;
        v.transform.translation = glm::vec3(0.975f);
        v.transform.scale = glm::vec3(2.0f);
    }
    v.medium.scattering = glm::vec3(1.6f);
    v.medium.absorption = glm::vec3(0.4f);
    v.medium.emission = glm::vec3(0.3f, 0.1f, 0.05f);
    s.volumes.push_back(v);
    return s;
}

DensityGridPtr writeAndLoadCube(const fs::path& dir) {
    auto g = test::makeGrid("density", 0, 39, [](openvdb::Coord) { return 1.0f; },
                            openvdb::math::Transform::createLinearTransform(0.05));
    test::writeGrids(dir / "cube.vdb", {g});
    Result<VdbLoad> r = loadVdbDensity((dir / "cube.vdb").string(), {});
    return r.ok() ? r.value().grid : nullptr;
}

RenderRequest smallRequest() {
    RenderRequest r;
    r.width = 80;
    r.height = 45;
    return r;
}

}  // namespace

// The reference renders a VDB cube as the analytic box it equals (sampling and shadow rays), and is
// far from the image without the volume (so the comparison can fail).
TEST_F(Vdb, ReferenceRendersAVdbCubeAsTheEquivalentBox) {
    const DensityGridPtr grid = writeAndLoadCube(dir_);
    ASSERT_TRUE(grid);
    const Image box = renderReference(cubeScene(nullptr), smallRequest());
    const Image vdb = renderReference(cubeScene(grid), smallRequest());
    Scene empty = cubeScene(nullptr);
    empty.volumes.clear();
    const double err = relativeMeanAbsError(vdb, box);
    const double errEmpty = relativeMeanAbsError(renderReference(empty, smallRequest()), box);
    std::printf("reference: vdb cube vs box %.3g (no volume vs box %.3g)\n", err, errEmpty);
    EXPECT_LT(err, 0.025);  // the edge difference: 4.7% at 0.1 m voxels, 1.3% at 0.05 m
    EXPECT_GT(errEmpty, 0.5);
}

// The CPU froxel renderer (the GPU's oracle) samples the same grid: it matches the reference about
// as well as it does for the analytic box. No sun: the froxel renderers have no volumetric shadows yet.
TEST_F(Vdb, FroxelCpuMatchesTheReferenceOnAVdbCube) {
    const DensityGridPtr grid = writeAndLoadCube(dir_);
    ASSERT_TRUE(grid);
    const Image ref = renderReference(cubeScene(grid, false), smallRequest());
    const Image froxel = renderFroxelCpu(cubeScene(grid, false), smallRequest()).image;
    const Image froxelBox = renderFroxelCpu(cubeScene(nullptr, false), smallRequest()).image;
    const double err = relativeMeanAbsError(froxel, ref);
    std::printf("froxel vs reference: vdb cube %.3g, analytic box %.3g\n", err, relativeMeanAbsError(froxelBox, ref));
    EXPECT_LT(err, 0.05);
}

// ---- corrupt files ----

namespace {

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

void writeBytes(const fs::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// One sentence naming the file.
void expectSentence(const std::string& message, const std::string& file) {
    EXPECT_EQ(message.rfind(file, 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

}  // namespace

// Every truncation is an error naming the file (byte flips, the crash, the truncated uncompressed
// file and the memory cap: tests/test_vdb_robust.cpp).
TEST_F(Vdb, TruncatedFilesGiveOneSentenceErrors) {
    BRUME_REQUIRE_SHARED_VDB();
    for (const char* name : {"gaffer_arnold_sphere.vdb", "usd_smoke_000002.vdb", "plasmadxr_fluid_data_0001.vdb"}) {
        const std::string bytes = readBytes(real(name));
        const fs::path bad = dir_ / name;
        for (int i = 0; i < 24; ++i) {
            const size_t cut = bytes.size() * static_cast<size_t>(i) / 24 + static_cast<size_t>(i % 5);
            writeBytes(bad, bytes.substr(0, cut));
            Result<VdbLoad> r = loadVdbDensity(bad.string(), {});
            EXPECT_FALSE(r.ok()) << name << " truncated at " << cut;
            if (!r.ok()) expectSentence(r.error().message, bad.string());
        }
    }
}

// The command line's contract on a corrupt file: exit code 2 and one line on stderr.
TEST_F(Vdb, CliInfoAndRenderExitTwoOnACorruptFile) {
    BRUME_REQUIRE_SHARED_VDB();
    const std::string bytes = readBytes(real("gaffer_arnold_sphere.vdb"));
    writeBytes(dir_ / "cut.vdb", bytes.substr(0, bytes.size() / 2));
    writeBytes(dir_ / "scene.json", R"({"brume_scene": 1, "volumes": [{"type": "vdb", "file": "cut.vdb"}]})");
    for (const std::string& args : {std::string("info cut.vdb"), std::string("render scene.json -o x.png --cpu")}) {
        const std::string cmd = "cd '" + dir_.string() + "' && '" + BRUME_EXE + "' " + args + " >/dev/null 2>err.txt";
        const int status = std::system(cmd.c_str());
        ASSERT_TRUE(WIFEXITED(status)) << args;
        EXPECT_EQ(WEXITSTATUS(status), 2) << args;
        const std::string err = readBytes((dir_ / "err.txt").string());
        EXPECT_EQ(err.rfind("error: ", 0), 0u) << err;
        EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
        EXPECT_NE(err.find("cut.vdb"), std::string::npos) << err;
    }
}

// `brume render` draws a vdb volume on the GPU as on the CPU, without the former "does not draw
// yet" warning (tests/test_gpu_vdb.cpp compares the two renderers' volumes closely; this is the CLI).
TEST_F(Vdb, GpuRenderDrawsVdbVolumesLikeTheCpu) {
    BRUME_REQUIRE_GPU_BUILD();
    BRUME_REQUIRE_SHARED_VDB();
    const std::string bytes = readBytes(real("gaffer_arnold_sphere.vdb"));
    writeBytes(dir_ / "sphere.vdb", bytes);
    writeBytes(dir_ / "scene.json",
               R"({"brume_scene": 1, "camera": {"position": [0, 2, 5], "target": [0, 2, 0]}, "ambient": [0.2, 0.2, 0.2],
                   "volumes": [{"type": "vdb", "name": "puff", "file": "sphere.vdb", "medium": {"emission": [1, 0.5, 0.2]}}]})");
    for (const std::string renderer : {"gpu", "cpu"}) {
        const std::string cmd = "cd '" + dir_.string() + "' && '" + BRUME_EXE + "' render scene.json -o " + renderer +
                                ".exr --width 64 --height 36" + (renderer == "cpu" ? " --cpu" : "") +
                                " >/dev/null 2>err.txt";
        const int status = std::system(cmd.c_str());
        ASSERT_TRUE(WIFEXITED(status));
        EXPECT_EQ(WEXITSTATUS(status), 0) << renderer;
        const std::string err = readBytes((dir_ / "err.txt").string());
        EXPECT_EQ(err.find("vdb volume"), std::string::npos) << renderer << ": " << err;
    }
    Result<Image> gpu = readExr((dir_ / "gpu.exr").string());
    Result<Image> cpu = readExr((dir_ / "cpu.exr").string());
    ASSERT_TRUE(gpu.ok() && cpu.ok());
    EXPECT_LT(relativeMeanAbsError(gpu.value(), cpu.value()), 0.01);
    // The sphere shows: pixels differ across the image (an empty volume gives the uniform sky).
    float lo = 1e30f, hi = -1e30f;
    for (const glm::vec3& p : gpu.value().pixels) {
        lo = std::min(lo, p.x + p.y + p.z);
        hi = std::max(hi, p.x + p.y + p.z);
    }
    EXPECT_GT(hi - lo, 0.05f * hi);
}
