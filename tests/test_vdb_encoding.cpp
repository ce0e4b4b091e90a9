// The float / Fp16 / Fp8 NanoVDB trade on a real smoke (gaffer_smoke.vdb, 1.05 M active voxels):
// memory, per-voxel error against the float grid and lookup time (docs/vdb.md, "Encodings"); then
// the `encoding` volume key itself: the grids it loads, the CPU froxel images they give against
// float, the scene format's strictness. Timings are printed, never asserted.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sys/wait.h>

#include <nanovdb/util/OpenToNanoVDB.h>
#include <openvdb/openvdb.h>

#include "core/render.h"
#include "io/scene_json.h"
#include "io/vdb_import.h"
#include "test_support.h"
#include "vdb_test_util.h"

namespace {

struct Measured {
    uint64_t bytes = 0;
    double relMeanAbsError = 0.0;  // sum |q - f| / sum |f| over the active voxels
    double maxAbsError = 0.0;      // in the grid's units (smoke density 0..5.71)
    double nsPerLookup = 0.0;
};

template <class BuildT>
Measured measure(const openvdb::FloatGrid& grid) {
    auto handle = nanovdb::openToNanoVDB<nanovdb::HostBuffer, openvdb::FloatTree, BuildT>(grid);
    const auto* nano = handle.template grid<BuildT>();
    EXPECT_NE(nano, nullptr);
    Measured m;
    if (!nano) return m;
    m.bytes = handle.size();
    auto acc = nano->getAccessor();
    double sumErr = 0.0, sum = 0.0, checksum = 0.0;
    uint64_t n = 0;
    const auto start = std::chrono::steady_clock::now();
    for (auto it = grid.cbeginValueOn(); it.test(); ++it) {
        const openvdb::Coord c = it.getCoord();
        const float q = acc.getValue(nanovdb::Coord(c.x(), c.y(), c.z()));
        checksum += q;
        sumErr += std::abs(double(q) - double(*it));
        sum += std::abs(double(*it));
        m.maxAbsError = std::max(m.maxAbsError, std::abs(double(q) - double(*it)));
        ++n;
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    m.relMeanAbsError = sumErr / std::max(sum, 1e-30);
    m.nsPerLookup = seconds * 1e9 / double(std::max<uint64_t>(n, 1));
    EXPECT_GT(checksum, 0.0);
    return m;
}

}  // namespace

TEST(VdbEncoding, Fp16AndFp8TradeMemoryForErrorOnARealSmoke) {
    const std::filesystem::path file = brume::test::sharedVdbDir() / "gaffer_smoke.vdb";
    if (!std::filesystem::exists(file)) GTEST_SKIP() << "../shared/vdb is absent; encoding measurement skipped";
    openvdb::initialize();
    openvdb::io::File f(file.string());
    f.open(false);
    auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(f.readGrid("density"));
    f.close();
    ASSERT_TRUE(grid);
    const Measured fp32 = measure<float>(*grid), fp16 = measure<nanovdb::Fp16>(*grid), fp8 = measure<nanovdb::Fp8>(*grid);
    for (const auto& [name, m] : {std::pair{"float", fp32}, std::pair{"Fp16", fp16}, std::pair{"Fp8", fp8}})
        std::printf("%-5s %8.3f MiB  rel. mean abs error %.2e  max abs error %.2e  %.1f ns/lookup\n", name,
                    double(m.bytes) / (1024.0 * 1024.0), m.relMeanAbsError, m.maxAbsError, m.nsPerLookup);
    EXPECT_EQ(fp32.relMeanAbsError, 0.0);  // the float grid is the reference itself
    EXPECT_LT(fp16.bytes, fp32.bytes * 7 / 10);
    EXPECT_LT(fp8.bytes, fp16.bytes);
    // Quantization per 8^3 leaf between its min and max: 16 bits keep ~1e-5 of a leaf's range, 8 bits ~4e-3.
    EXPECT_LT(fp16.relMeanAbsError, 1e-3);
    EXPECT_LT(fp8.relMeanAbsError, 2e-2);
    EXPECT_GT(fp8.relMeanAbsError, fp16.relMeanAbsError);  // the measurement sees the quantization
}

namespace {

using namespace brume;

DensityGridPtr load(const std::filesystem::path& file, VdbEncoding e) {
    VdbImportOptions options;
    options.encoding = e;
    Result<VdbLoad> r = loadVdbDensity(file.string(), options);
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
    return r.ok() ? r.value().grid : nullptr;
}

// The grid fitted into a 3 m cube 3 m up, seen by the test view, lit by a sun whose fog shadows
// march the grid (vdb shadows are on by default) and a point light.
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
    const glm::vec3 lo = glm::vec3(grid->gridFromIndex() * glm::vec4(grid->indexMin(), 1.0f));
    const glm::vec3 hi = glm::vec3(grid->gridFromIndex() * glm::vec4(grid->indexMax(), 1.0f));
    const glm::vec3 size = glm::abs(hi - lo);
    const float fit = 3.0f / std::max(size.x, std::max(size.y, size.z));
    v.transform.scale = glm::vec3(fit);
    v.transform.translation = glm::vec3(0.0f, 3.0f, 0.0f) - fit * 0.5f * (lo + hi);
    s.volumes = {v};
    Light sun = makeLight(LightType::Directional);
    sun.direction = glm::normalize(glm::vec3(0.4f, -1.0f, 0.2f));
    Light point = makeLight(LightType::Point);
    point.position = {0.5f, 5.0f, 1.5f};
    point.range = 12.0f;
    s.lights = {sun, point};
    return s;
}

// Loads `file` in the three encodings and checks what the key promises: the grid is stored so,
// memory falls, the occupancy cells are built (culling changes nothing), and the CPU froxel image
// stays within 0.1% (fp16) and 2% (fp8) of float's.
void expectEncodingsTrade(const std::filesystem::path& file, float densityScale, const char* what) {
    const DensityGridPtr f32 = load(file, VdbEncoding::Float), f16 = load(file, VdbEncoding::Fp16),
                         f8 = load(file, VdbEncoding::Fp8);
    ASSERT_TRUE(f32 && f16 && f8);
    EXPECT_EQ(f32->encoding(), VdbEncoding::Float);
    EXPECT_EQ(f16->encoding(), VdbEncoding::Fp16);
    EXPECT_EQ(f8->encoding(), VdbEncoding::Fp8);
    EXPECT_LT(f16->nanoVdbSize(), f32->nanoVdbSize()) << what;
    EXPECT_LT(f8->nanoVdbSize(), f16->nanoVdbSize()) << what;
    EXPECT_EQ(f32->activeVoxels(), f8->activeVoxels()) << what;
    RenderRequest request;
    request.width = 160;
    request.height = 90;
    request.threads = 2;
    const Image ref = renderFroxelCpu(sceneWith(f32, densityScale), request).image;
    double err[2] = {0.0, 0.0};
    for (int i = 0; i < 2; ++i) {
        const DensityGridPtr& g = i == 0 ? f16 : f8;
        EXPECT_NE(g->occupancyOffset(), 0u) << what << ": no occupancy cells for the quantized grid";
        const Scene s = sceneWith(g, densityScale);
        const Image img = renderFroxelCpu(s, request).image;
        err[i] = relativeMeanAbsError(img, ref);
        RenderRequest unculled = request;
        unculled.vdbCulling = false;
        EXPECT_LT(relativeMeanAbsError(renderFroxelCpu(s, unculled).image, img), 1e-6) << what;
    }
    RenderRequest without = request;
    without.vdbShadows = false;
    const double share = relativeMeanAbsError(renderFroxelCpu(Scene{sceneWith(f32, densityScale)}, without).image, ref);
    std::printf("[vdb encoding] %-14s float %.2f MiB, fp16 %.2f MiB (image error %.2e), fp8 %.2f MiB (%.2e); "
                "vdb shadows change the image by %.3f\n",
                what, double(f32->nanoVdbSize()) / 1048576.0, double(f16->nanoVdbSize()) / 1048576.0, err[0],
                double(f8->nanoVdbSize()) / 1048576.0, err[1], share);
    EXPECT_LT(err[0], 1e-3) << what;
    EXPECT_LT(err[1], 2e-2) << what;
    EXPECT_GT(err[1], err[0]) << what << ": the images do not see the quantization";
    EXPECT_GT(err[0], 0.0) << what << ": the fp16 image equals float's, the grid was not re-encoded";
}

Result<Scene> parseVdbScene(const std::string& encodings) {
    return parseScene(R"({"brume_scene": 1, "volumes": [)" + encodings + "]}", "s.json");
}

}  // namespace

TEST(VdbEncoding, SyntheticGridEncodingsTradeMemoryForImageError) {
    test::TempDir dir("vdb_encoding", "synthetic");
    // Values that vary inside every 8^3 leaf, so quantization shows.
    auto g = test::makeGrid("density", -15, 14, [](openvdb::Coord c) {
        return 0.6f + 0.4f * std::sin(0.7f * static_cast<float>(c.x())) * std::cos(0.5f * static_cast<float>(c.z()));
    }, test::skewedTransform());
    test::writeGrids(dir.path / "bumpy.vdb", {g});
    expectEncodingsTrade(dir.path / "bumpy.vdb", 1.0f, "synthetic");
}

TEST(VdbEncoding, GafferSmokeEncodingsTradeMemoryForImageError) {
    const std::filesystem::path file = brume::test::sharedVdbDir() / "gaffer_smoke.vdb";
    if (!std::filesystem::exists(file)) GTEST_SKIP() << "../shared/vdb is absent; real-file test skipped";
    expectEncodingsTrade(file, 40.0f, "gaffer_smoke");
}

TEST(VdbEncoding, SceneKeyIsStrictAndRoundTrips) {
    const std::string vdb = R"({"type": "vdb", "file": "a.vdb")";
    Result<Scene> s = parseVdbScene(vdb + R"(, "encoding": "fp8"}, )" + vdb + R"(, "encoding": "fp8"})");
    ASSERT_TRUE(s.ok()) << s.error().message;
    EXPECT_EQ(s.value().volumes[1].encoding, VdbEncoding::Fp8);
    Result<Scene> again = parseScene(sceneToJson(s.value()), "again.json");
    ASSERT_TRUE(again.ok()) << again.error().message;
    EXPECT_EQ(again.value().volumes[0].encoding, VdbEncoding::Fp8);
    EXPECT_EQ(parseVdbScene(vdb + "}").value().volumes[0].encoding, VdbEncoding::Float);  // the default

    Result<Scene> bad = parseVdbScene(vdb + R"(, "encoding": "fp32"})");
    ASSERT_FALSE(bad.ok());
    EXPECT_NE(bad.error().message.find("s.json: volumes[0].encoding: unknown choice"), std::string::npos)
        << bad.error().message;
    EXPECT_NE(bad.error().message.find("fp16"), std::string::npos) << "lists the choices: " << bad.error().message;

    Result<Scene> mixed = parseVdbScene(vdb + R"(, "encoding": "fp16"}, {"type": "box"}, )" + vdb + "}");
    ASSERT_FALSE(mixed.ok());
    EXPECT_NE(mixed.error().message.find("volumes[2].encoding"), std::string::npos) << mixed.error().message;
    EXPECT_NE(mixed.error().message.find("same encoding"), std::string::npos) << mixed.error().message;
    // Only vdb volumes take the key.
    EXPECT_FALSE(parseVdbScene(R"({"type": "box", "encoding": "fp16"})").ok());
}

TEST(VdbEncoding, BadEncodingExitsWithCodeTwoAndOneSentence) {
    test::TempDir dir("vdb_encoding", "cli");
    std::ofstream(dir.path / "bad.json")
        << R"({"brume_scene": 1, "volumes": [{"type": "vdb", "file": "a.vdb", "encoding": "half"}]})";
    const std::string err = (dir.path / "err").string();
    const int status = std::system(("\"" + std::string(BRUME_EXE) + "\" validate \"" + (dir.path / "bad.json").string() +
                                    "\" 2>\"" + err + "\" >/dev/null").c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 2);
    std::ifstream in(err);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << text;
    EXPECT_NE(text.find("volumes[0].encoding: unknown choice \"half\""), std::string::npos) << text;
}

// The key reaches the grid: a scene file's vdb volumes load in the encoding they name.
TEST(VdbEncoding, SceneGridsLoadInTheirEncoding) {
    test::TempDir dir("vdb_encoding", "scene");
    test::writeGrids(dir.path / "cube.vdb", {test::makeGrid("density", 0, 15, [](openvdb::Coord c) {
        return 0.5f + 0.03f * static_cast<float>(c.x());
    }, openvdb::math::Transform::createLinearTransform(0.1))});
    for (const char* e : {"float", "fp16", "fp8"}) {
        Result<Scene> s = parseVdbScene(R"({"type": "vdb", "file": "cube.vdb", "encoding": ")" + std::string(e) +
                                        R"("}, {"type": "vdb", "file": "cube.vdb", "encoding": ")" + e + "\"}");
        ASSERT_TRUE(s.ok()) << s.error().message;
        s.value().baseDir = dir.path.string();
        std::vector<std::string> warnings;
        Result<void> r = loadSceneGrids(s.value(), "s.json", VdbImportOptions{}.memoryLimitBytes, warnings);
        ASSERT_TRUE(r.ok()) << r.error().message;
        for (const Volume& v : s.value().volumes) {
            ASSERT_TRUE(v.density);
            EXPECT_STREQ(toString(v.density->encoding()), e);
        }
    }
}
