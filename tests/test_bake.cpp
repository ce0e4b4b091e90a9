// `brume bake` (io/fog_bake.h): a scene's fog as world-space OpenVDB grids. The round trip is the
// physics check: a single-medium scene, baked and imported back as a vdb volume with the matching
// medium, renders (reference) within 2% of the analytic scene. The grids hold sigma_t, the albedo and
// the emission at voxel centres, empty space stays inactive, and unbounded fog needs --bounds.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <openvdb/openvdb.h>

#include "core/render.h"
#include "io/fog_bake.h"
#include "io/scene_json.h"
#include "io/vdb_import.h"
#include "test_support.h"

namespace fs = std::filesystem;

namespace {

using namespace brume;
using brume::test::TempDir;

constexpr glm::vec3 kSigmaS{1.8f, 1.5f, 1.2f};
constexpr glm::vec3 kSigmaA{0.45f, 0.75f, 1.05f};  // sigma_t 2.25 in every channel
constexpr float kSigmaT = 2.25f;
constexpr glm::vec3 kEmission{0.03f, 0.015f, 0.0f};

Scene boxScene() {
    Scene s = test::sceneWithTestView();
    s.camera.position = {0.0f, 1.6f, 5.0f};
    s.camera.target = {0.0f, 1.0f, 0.0f};
    Volume v = test::boxFog({0.0f, 1.0f, 0.0f}, {2.4f, 1.6f, 2.0f}, 0.5f, kSigmaS, kSigmaA);
    v.medium.emission = kEmission;
    v.medium.phase_g = 0.3f;
    s.volumes = {v};
    s.lights = {makeLight(LightType::Directional)};
    s.lights[0].shadows = false;
    s.geometry = {test::groundPlane(glm::vec3(0.5f))};
    return s;
}

RenderRequest smallRequest() {
    RenderRequest r;
    r.width = 64;
    r.height = 36;
    r.threads = 2;
    return r;
}

openvdb::GridPtrVecPtr readGrids(const fs::path& p, openvdb::MetaMap::Ptr& meta) {
    openvdb::initialize();
    openvdb::io::File f(p.string());
    f.open();
    openvdb::GridPtrVecPtr grids = f.getGrids();
    meta = f.getMetadata();
    f.close();
    return grids;
}

template <class GridT>
typename GridT::Ptr find(const openvdb::GridPtrVecPtr& grids, const std::string& name) {
    for (const auto& g : *grids)
        if (g->getName() == name) return openvdb::gridPtrCast<GridT>(g);
    return nullptr;
}

TEST(Bake, RoundTripRendersLikeTheAnalyticScene) {
    TempDir t("bake", "roundtrip");
    const Scene analytic = boxScene();
    BakeOptions o;
    o.voxelSize = 0.05f;
    o.threads = 2;
    const fs::path vdb = t.path / "fog.vdb";
    Result<BakeResult> r = bakeFogVdb(analytic, o, "box.json", vdb.string());
    ASSERT_TRUE(r) << r.error().message;

    // The matching medium: density = sigma_t, so sigma_s = albedo, sigma_a = 1 - albedo and the
    // emission per unit of density is emission / sigma_t.
    const float sigmaT = kSigmaT;
    Scene imported = analytic;
    Volume v;
    v.type = VolumeType::Vdb;
    v.file = vdb.string();
    v.medium.scattering = kSigmaS / sigmaT;
    v.medium.absorption = kSigmaA / sigmaT;
    v.medium.emission = kEmission / sigmaT;
    v.medium.phase_g = 0.3f;
    imported.volumes = {v};
    std::vector<std::string> warnings;
    ASSERT_TRUE(loadSceneGrids(imported, "imported.json", uint64_t(256) << 20, warnings));

    const Image ref = renderReference(analytic, smallRequest());
    const Image back = renderReference(imported, smallRequest());
    Scene empty = analytic;
    empty.volumes.clear();
    const double err = relativeMeanAbsError(back, ref);
    const double errEmpty = relativeMeanAbsError(renderReference(empty, smallRequest()), ref);
    std::printf("baked vs analytic %.4f (no fog vs analytic %.4f)\n", err, errEmpty);
    EXPECT_LT(err, 0.02);
    EXPECT_GT(errEmpty, 0.1) << "the fog must matter for the comparison to mean anything";
}

TEST(Bake, GridsHoldSigmaTAlbedoEmissionAndStaySparse) {
    TempDir t("bake", "grids");
    Scene s = boxScene();
    s.volumes[0].edge_fade = 0.0f;
    Volume far = s.volumes[0];
    far.transform.translation = {20.0f, 1.0f, 0.0f};
    far.transform.scale = glm::vec3(1.0f);
    s.volumes.push_back(far);
    BakeOptions o;
    o.voxelSize = 0.1f;
    const fs::path vdb = t.path / "fog.vdb";
    Result<BakeResult> r = bakeFogVdb(s, o, "two.json", vdb.string());
    ASSERT_TRUE(r) << r.error().message;
    openvdb::MetaMap::Ptr meta;
    const openvdb::GridPtrVecPtr grids = readGrids(vdb, meta);
    const auto density = find<openvdb::FloatGrid>(grids, "density");
    const auto cd = find<openvdb::Vec3SGrid>(grids, "Cd");
    const auto emission = find<openvdb::Vec3SGrid>(grids, "emission");
    ASSERT_TRUE(density && cd && emission);
    EXPECT_NEAR(density->voxelSize().x(), 0.1, 1e-7);
    // Voxel (0, 10, 0) is centred at (0, 1, 0), inside the first box.
    const openvdb::Coord inside(0, 10, 0);
    EXPECT_NEAR(density->tree().getValue(inside), kSigmaT, 1e-5f);
    const openvdb::Vec3s a = cd->tree().getValue(inside);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], kSigmaS[i] / kSigmaT, 1e-5f);
    const openvdb::Vec3s e = emission->tree().getValue(inside);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(e[i], kEmission[i], 1e-6f);
    // Between the boxes: empty and inactive. The active voxels are the two boxes' alone.
    const openvdb::Coord between(100, 10, 0);
    EXPECT_FALSE(density->tree().isValueOn(between));
    EXPECT_EQ(density->tree().getValue(between), 0.0f);
    const double boxes = (2.4 * 1.6 * 2.0 + 1.0) / (0.1 * 0.1 * 0.1);
    EXPECT_NEAR(double(density->activeVoxelCount()), boxes, 0.25 * boxes);
    EXPECT_LT(double(density->activeVoxelCount()), 0.2 * double(r.value().voxels.x) * r.value().voxels.y * r.value().voxels.z);
    ASSERT_TRUE((*meta)["brume_version"]);
    EXPECT_NE((*meta)["units"]->str().find("1/m"), std::string::npos);
    EXPECT_EQ(density->metaValue<std::string>("units"), "sigma_t [1/m]");
}

TEST(Bake, UnboundedFogNeedsBounds) {
    TempDir t("bake", "bounds");
    Scene s = boxScene();
    Volume h;
    h.type = VolumeType::Height;
    h.name = "mist";
    h.falloff = 1.0f;
    s.volumes = {h};
    BakeOptions o;
    o.voxelSize = 0.25f;
    Result<BakeResult> r = bakeFogVdb(s, o, "mist.json", (t.path / "m.vdb").string());
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("mist.json: volumes[0] \"mist\" is a height fog without bounds"), std::string::npos)
        << r.error().message;
    EXPECT_FALSE(fs::exists(t.path / "m.vdb"));
    o.bounds = WorldBox{{-2.0f, 0.0f, -2.0f}, {2.0f, 3.0f, 2.0f}};
    r = bakeFogVdb(s, o, "mist.json", (t.path / "m.vdb").string());
    ASSERT_TRUE(r) << r.error().message;
    EXPECT_EQ(r.value().voxels, glm::ivec3(17, 13, 17));
    openvdb::MetaMap::Ptr meta;
    const auto density = find<openvdb::FloatGrid>(readGrids(t.path / "m.vdb", meta), "density");
    ASSERT_TRUE(density);
    // Height fog at y = 2 (voxel j = 8): e^(-falloff y) x sigma_t of the default medium.
    EXPECT_NEAR(density->tree().getValue(openvdb::Coord(0, 8, 0)), std::exp(-2.0f) * 0.11f, 1e-5f);
    EXPECT_FALSE(density->tree().isValueOn(openvdb::Coord(0, 8, 9)));  // z = 2.25: outside --bounds
}

TEST(Bake, CommandLineErrorsAreOneSentence) {
    TempDir t("bake", "cli");
    std::ofstream(t.path / "h.json") << R"({"brume_scene": 1, "volumes": [{"type": "height"}]})";
    struct Case {
        std::string args, mention;
    };
    for (const Case& c : std::vector<Case>{{"bake h.json -o h.vdb --voxel-size 0.5", "--bounds"},
                                           {"bake h.json -o h.vdb --voxel-size 0", "--voxel-size"},
                                           {"bake h.json -o h.txt --voxel-size 0.5", "h.txt"},
                                           {"bake h.json -o no/h.vdb --voxel-size 0.5", "no"},
                                           {"bake h.json -o h.vdb --voxel-size 0.5 --bounds 0 0 0 1 -1 1", "--bounds"},
                                           {"bake missing.json -o h.vdb --voxel-size 0.5", "missing.json"}}) {
        const std::string cmd = "cd " + test::quoted(t.path.string()) + " && " + test::quoted(BRUME_EXE) + " " + c.args +
                                " >/dev/null 2>err.txt";
        const int status = std::system(cmd.c_str());
        const std::string err = test::readText(t.path / "err.txt");
        EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 2) << c.args << ": " << err;
        EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
        EXPECT_NE(err.find(c.mention), std::string::npos) << c.args << ": " << err;
    }
    EXPECT_FALSE(fs::exists(t.path / "h.vdb"));
    const std::string ok = "cd " + test::quoted(t.path.string()) + " && " + test::quoted(BRUME_EXE) +
                           " bake h.json -o h.vdb --voxel-size 0.5 --bounds -2 0 -2 2 2 2 >/dev/null 2>&1";
    EXPECT_EQ(std::system(ok.c_str()), 0);
    EXPECT_TRUE(fs::exists(t.path / "h.vdb"));
}

}  // namespace
