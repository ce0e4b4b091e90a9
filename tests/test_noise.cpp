// `brume noise`: tileable 3D noise for density textures. The field is exactly periodic (the seam a
// density_texture wraps across looks like any interior step), the written grid is the whole tile
// with values in [0, 1] and mean 0.5, the seed decides the noise, the grid loads as a texture, and
// bad flags are one sentence with exit code 2.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>

#include <openvdb/openvdb.h>

#include "core/noise.h"
#include "io/image_io.h"
#include "io/scene_json.h"
#include "io/vdb_import.h"
#include "test_support.h"

using namespace brume;
namespace fs = std::filesystem;

namespace {

using brume::test::quoted;
using brume::test::readText;

struct CliRun {
    int exitCode = -1;
    std::string out, err;
};

// A tile read back with the OpenVDB API: n^3 values, x fastest.
struct Tile {
    int n = 0;
    std::vector<float> v;
    openvdb::CoordBBox activeBox;
    openvdb::Index64 activeVoxels = 0;
    float at(int i, int j, int k) const {
        return v[(static_cast<size_t>(k) * static_cast<size_t>(n) + static_cast<size_t>(j)) * static_cast<size_t>(n) +
                 static_cast<size_t>(i)];
    }
};

Tile readTile(const fs::path& file, const std::string& gridName) {
    openvdb::initialize();
    openvdb::io::File f(file.string());
    f.open();
    openvdb::FloatGrid::Ptr g = openvdb::gridPtrCast<openvdb::FloatGrid>(f.readGrid(gridName));
    f.close();
    Tile t;
    t.activeBox = g->evalActiveVoxelBoundingBox();
    t.activeVoxels = g->activeVoxelCount();
    t.n = t.activeBox.dim().x();
    auto acc = g->getConstAccessor();
    for (int k = 0; k < t.n; ++k)
        for (int j = 0; j < t.n; ++j)
            for (int i = 0; i < t.n; ++i) t.v.push_back(acc.getValue(openvdb::Coord(i, j, k)));
    return t;
}

// RMS of the step v(i+1) - v(i) along `axis` over the interior (i < period - 1), and across the seam
// from voxel period - 1 to voxel 0, treating the first `period` voxels as one tile.
struct Steps {
    double interior = 0.0, seam = 0.0;
};

Steps stepRms(const Tile& t, int axis, int period) {
    double interior = 0.0, seam = 0.0;
    long ni = 0, ns = 0;
    auto value = [&](int a, int b, int c) {
        return axis == 0 ? t.at(a, b, c) : axis == 1 ? t.at(b, a, c) : t.at(b, c, a);
    };
    for (int c = 0; c < t.n; ++c)
        for (int b = 0; b < t.n; ++b) {
            for (int a = 0; a + 1 < period; ++a, ++ni) interior += std::pow(value(a + 1, b, c) - value(a, b, c), 2.0);
            seam += std::pow(value(0, b, c) - value(period - 1, b, c), 2.0);
            ++ns;
        }
    return {std::sqrt(interior / static_cast<double>(ni)), std::sqrt(seam / static_cast<double>(ns))};
}

class Noise : public ::testing::Test {
protected:
    CliRun brume(const std::string& args) const {
        const std::string cmd = "cd " + quoted(dir_.path.string()) + " && " + quoted(BRUME_EXE) + " " + args +
                                " >out.log 2>err.log";
        const int status = std::system(cmd.c_str());
        CliRun r;
        r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        r.out = readText(dir_.path / "out.log");
        r.err = readText(dir_.path / "err.log");
        return r;
    }
    fs::path path(const std::string& name) const { return dir_.path / name; }

    test::TempDir dir_{"noise", ::testing::UnitTest::GetInstance()->current_test_info()->name()};
};

}  // namespace

// The lattice wraps, so the continuous noise repeats every `period` cells along each axis.
TEST(NoiseField, GradientNoiseRepeatsWithItsPeriod) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 5.0f);
    double largest = 0.0;
    for (int s = 0; s < 200; ++s) {
        const glm::vec3 p(u(rng), u(rng), u(rng));
        const float v = periodicGradientNoise(p, 5, 11u);
        largest = std::max(largest, static_cast<double>(std::abs(v)));
        for (int axis = 0; axis < 3; ++axis) {
            glm::vec3 q = p;
            q[axis] += 5.0f;
            EXPECT_NEAR(periodicGradientNoise(q, 5, 11u), v, 2e-5) << "axis " << axis;
        }
    }
    EXPECT_GT(largest, 0.2) << "the noise should not be flat";
}

TEST_F(Noise, TileIsWholeInRangeWithMeanOneHalf) {
    const CliRun r = brume("noise tile.vdb --size 32 --octaves 3 --frequency 4 --seed 5");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Tile t = readTile(path("tile.vdb"), "density");
    EXPECT_EQ(t.activeVoxels, 32u * 32u * 32u) << "every voxel of the tile is active, zeros too";
    EXPECT_EQ(t.activeBox, openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(31)));
    double mean = 0.0;
    float lo = 1.0f, hi = 0.0f;
    for (float v : t.v) {
        mean += v;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    mean /= static_cast<double>(t.v.size());
    EXPECT_NEAR(mean, 0.5, 1e-4);
    EXPECT_GE(lo, 0.0f);
    EXPECT_LE(hi, 1.0f);
    EXPECT_TRUE(lo < 1e-4f || hi > 1.0f - 1e-4f) << "the largest deviation reaches 0 or 1: " << lo << ".." << hi;
    EXPECT_LT(lo, 0.25f);
    EXPECT_GT(hi, 0.75f);
}

// The seam the density_texture wraps across (voxel n - 1 to voxel 0) is a step like any other.
// Control: cut the same field at 3/4 of the tile and the seam step is several times the interior's.
TEST_F(Noise, OppositeFacesContinueAcrossTheSeam) {
    const CliRun r = brume("noise tile.vdb --size 48 --frequency 3 --seed 9");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Tile t = readTile(path("tile.vdb"), "density");
    ASSERT_EQ(t.n, 48);
    for (int axis = 0; axis < 3; ++axis) {
        const Steps whole = stepRms(t, axis, 48);
        EXPECT_GT(whole.interior, 0.0);
        const double ratio = whole.seam / whole.interior;
        EXPECT_GT(ratio, 0.75) << "axis " << axis;
        EXPECT_LT(ratio, 1.33) << "axis " << axis << ": seam step " << whole.seam << " vs " << whole.interior;
        const Steps cut = stepRms(t, axis, 36);
        EXPECT_GT(cut.seam / cut.interior, 3.0) << "axis " << axis << ": the statistic must see a real seam";
    }
}

TEST_F(Noise, SeedDecidesTheNoiseAndFrequencyItsScale) {
    ASSERT_EQ(brume("noise a.vdb --size 24 --seed 42").exitCode, 0);
    ASSERT_EQ(brume("noise b.vdb --size 24 --seed 42").exitCode, 0);
    ASSERT_EQ(brume("noise c.vdb --size 24 --seed 43").exitCode, 0);
    ASSERT_EQ(brume("noise d.vdb --size 24 --seed 42 --frequency 2 --octaves 1").exitCode, 0);
    ASSERT_EQ(brume("noise e.vdb --size 24 --seed 42 --frequency 6 --octaves 1").exitCode, 0);
    const Tile a = readTile(path("a.vdb"), "density"), b = readTile(path("b.vdb"), "density");
    const Tile c = readTile(path("c.vdb"), "density");
    EXPECT_EQ(a.v, b.v) << "the same seed gives the same grid";
    double diff = 0.0;
    for (size_t i = 0; i < a.v.size(); ++i) diff += std::abs(a.v[i] - c.v[i]);
    EXPECT_GT(diff / static_cast<double>(a.v.size()), 0.05) << "another seed gives other noise";
    // Three times the cells per tile: the field changes about three times faster per voxel.
    const double coarse = stepRms(readTile(path("d.vdb"), "density"), 0, 24).interior;
    const double fine = stepRms(readTile(path("e.vdb"), "density"), 0, 24).interior;
    EXPECT_GT(fine / coarse, 1.5);
    EXPECT_LT(fine / coarse, 4.5);
}

TEST_F(Noise, GridLoadsAsDensityTexture) {
    ASSERT_EQ(brume("noise mist.vdb --size 16 --grid mist").exitCode, 0);
    std::ofstream(path("scene.json")) << R"({"brume_scene": 1, "volumes": [{"type": "box", "density_texture":
        {"file": "mist.vdb", "grid": "mist", "tile_size_m": 4, "scroll_mps": [1, 0, 0], "strength": 1}}]})";
    Result<Scene> scene = loadSceneFile(path("scene.json").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    std::vector<std::string> warnings;
    Result<void> loaded = loadSceneGrids(scene.value(), path("scene.json").string(), uint64_t(64) << 20, warnings);
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    ASSERT_TRUE(scene.value().volumes.at(0).density_texture);
    const DensityTexture& tex = *scene.value().volumes.at(0).density_texture;
    ASSERT_TRUE(tex.density);
    EXPECT_NEAR(tex.mean, 0.5f, 1e-4f);
    EXPECT_EQ(brume("validate scene.json").exitCode, 0);
}

TEST_F(Noise, LargeTilesShowProgress) {
    const CliRun r = brume("noise big.vdb --size 128 --octaves 1");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("100%"), std::string::npos) << r.err;
    EXPECT_EQ(brume("noise small.vdb --size 16").err, "") << "small tiles are quiet";
}

TEST_F(Noise, BadFlagsAreOneSentenceAndWriteNothing) {
    const std::pair<std::string, std::string> cases[] = {
        {"x.vdb --size 7", "--size"},        {"x.vdb --size 257", "--size"},
        {"x.vdb --octaves 0", "--octaves"},  {"x.vdb --frequency 65", "--frequency"},
        {"x.vdb --seed -1", "--seed"},       {"x.vdb --seed 1000000", "--seed"},
        {"x.vdb --grid 'a#1'", "--grid"},    {"x.vdb --grid ''", "--grid"},
        {"x.vdb --size many", "--size"},     {"x.png", "x.png"},
        {"nowhere/x.vdb", "nowhere"},        {"", "OUT"},
    };
    for (const auto& [args, mention] : cases) {
        const CliRun r = brume("noise " + args);
        EXPECT_EQ(r.exitCode, 2) << args << ": " << r.err;
        EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << args << ": " << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
        EXPECT_NE(r.err.find(mention), std::string::npos) << args << ": " << r.err;
    }
    EXPECT_FALSE(fs::exists(path("x.vdb")));
    EXPECT_FALSE(fs::exists(path("x.png")));
}

TEST_F(Noise, HelpNamesEveryFlagWithItsRange) {
    const CliRun r = brume("noise --help");
    EXPECT_EQ(r.exitCode, 0);
    for (const char* s : {"--size", "8..256", "--octaves", "--frequency", "--seed", "--grid", "density", "OUT"})
        EXPECT_NE(r.out.find(s), std::string::npos) << s << " missing from:\n" << r.out;
}

// The shipped asset: a small tile, and a scene whose mist visibly drifts with the scene time.
TEST_F(Noise, DriftingMistSceneRendersFiniteAndDrifts) {
    const fs::path assets = fs::path(BRUME_SOURCE_DIR) / "assets";
    EXPECT_LT(fs::file_size(assets / "noise" / "mist.vdb"), 300u * 1024u) << "keep the asset small";
    const Tile mist = readTile(assets / "noise" / "mist.vdb", "density");
    EXPECT_EQ(mist.activeVoxels, 32u * 32u * 32u);
    const std::string scene = quoted((assets / "scenes" / "drifting_mist.json").string());
    ASSERT_EQ(brume("validate " + scene).exitCode, 0);
    const std::string small = std::string(" --width 96 --height 54 --quality low") + test::defaultRendererFlag();
    const CliRun r0 = brume("render " + scene + " -o t0.exr --time 0 --frames 4 --fps 24" + small);
    ASSERT_EQ(r0.exitCode, 0) << r0.err;
    const CliRun r2 = brume("render " + scene + " -o t2.exr --time 2 --frames 4 --fps 24" + small);
    ASSERT_EQ(r2.exitCode, 0) << r2.err;
    Result<Image> a = readExr(path("t0.exr").string()), b = readExr(path("t2.exr").string());
    ASSERT_TRUE(a.ok() && b.ok());
    double diff = 0.0, sum = 0.0;
    for (size_t i = 0; i < a.value().pixels.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            ASSERT_TRUE(std::isfinite(a.value().pixels[i][c]) && std::isfinite(b.value().pixels[i][c]));
            diff += std::abs(a.value().pixels[i][c] - b.value().pixels[i][c]);
            sum += a.value().pixels[i][c];
        }
    }
    EXPECT_GT(sum, 0.0);
    // 2 s of 0.85 m/s wind moves the box's 3 m noise tile by more than half a tile.
    EXPECT_GT(diff / sum, 0.01) << "the mist should drift between time 0 and time 2";
}
