// Presets (io/preset.h) and `brume preset save|apply|list`: the format reads as strictly as a scene,
// paths follow the files wherever they move, versions are checked, and bad input is one sentence and
// exit code 2 with nothing written.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/render.h"
#include "io/image_io.h"
#include "io/vdb_import.h"
#include "io/preset.h"
#include "io/scene_json.h"
#include "test_support.h"

namespace fs = std::filesystem;

namespace {

using brume::test::quoted;
using brume::test::readText;
using brume::test::TempDir;
using namespace brume;

struct CliRun {
    int exitCode = -1;
    std::string out, err;
};

CliRun brumeIn(const fs::path& cwd, const std::string& args) {
    const fs::path out = cwd / ".out", err = cwd / ".err";
    const std::string cmd = "cd " + quoted(cwd.string()) + " && " + quoted(BRUME_EXE) + " " + args + " >" +
                            quoted(out.string()) + " 2>" + quoted(err.string());
    const int status = std::system(cmd.c_str());
    CliRun r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = readText(out);
    r.err = readText(err);
    fs::remove(out);
    fs::remove(err);
    return r;
}

void writeText(const fs::path& p, const std::string& text) {
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
}

void expectOneLineError(const CliRun& r, const std::string& mention) {
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(mention), std::string::npos) << "should mention '" << mention << "': " << r.err;
}

// A small scene: camera, ground, a sun, a box of fog and, when vdb is given, a vdb volume and a
// density texture using that file (path as written in the scene).
std::string sceneText(const std::string& vdb = "", const std::string& encoding = "float") {
    std::string volumes = R"({"type": "box", "name": "bank", "transform": {"scale": [4, 2, 4]},
        "medium": {"scattering": [0.5, 0.5, 0.5], "absorption": [0.01, 0.02, 0.03], "phase_g": 0.3}})";
    if (!vdb.empty())
        volumes += R"(, {"type": "vdb", "name": "puff", "file": ")" + vdb + R"(", "encoding": ")" + encoding + R"(",
        "transform": {"translation": [0, 1, 0]}, "medium": {"scattering": [2, 2, 2]},
        "density_texture": {"file": ")" + vdb + R"(", "tile_size_m": 3}})";
    return R"({"brume_scene": 1, "camera": {"position": [0, 1.5, 8], "target": [0, 1, 0]},
      "render": {"width": 64, "height": 36, "quality": "low"}, "ambient": [0.1, 0.12, 0.15],
      "lights": [{"type": "directional", "name": "sun", "direction": [0.3, -1, 0.2], "intensity": 2}],
      "volumes": [)" + volumes + R"(], "geometry": [{"type": "plane", "name": "ground"}]})";
}

// A tiny real grid (8^3 noise) written by brume itself.
void makeGrid(const fs::path& path) {
    fs::create_directories(path.parent_path());
    const CliRun r = brumeIn(path.parent_path(), "noise " + quoted(path.string()) + " --size 8");
    ASSERT_EQ(r.exitCode, 0) << r.err;
}

TEST(Preset, JsonRoundTripKeepsEveryVolumeAndLight) {
    Result<Scene> scene = parseScene(sceneText("grids/g.vdb"), "s.json");
    ASSERT_TRUE(scene) << scene.error().message;
    scene.value().baseDir = "/tmp/a/scenes";
    Preset p = presetFromScene(scene.value(), "look", true);
    p.description = "a test look";
    p.tags = {"mist", "test"};
    EXPECT_EQ(p.volumes[1].file, "/tmp/a/scenes/grids/g.vdb");
    const std::string text = presetToJson(p, "/tmp/a/looks");
    EXPECT_NE(text.find("\"../scenes/grids/g.vdb\""), std::string::npos) << text;
    Result<Preset> back = parsePreset(text, "look.json", "/tmp/a/looks");
    ASSERT_TRUE(back) << back.error().message;
    EXPECT_EQ(back.value().name, "look");
    EXPECT_EQ(back.value().description, "a test look");
    EXPECT_EQ(back.value().tags, p.tags);
    EXPECT_EQ(back.value().ambient, scene.value().ambient);
    ASSERT_TRUE(back.value().lights);
    EXPECT_EQ(*back.value().lights, scene.value().lights);
    EXPECT_EQ(back.value().volumes, p.volumes);
}

TEST(Preset, ReadsAsStrictlyAsAScene) {
    const std::string head = R"({"brume_preset": 1, "name": "x", )";
    struct Case {
        std::string text, mention;
    };
    const std::vector<Case> cases = {
        {head + R"("volumes": [], "colour": 1})", "colour: unknown key"},
        {head + R"("volumes": [{"type": "box", "medium": {"scattering": [-1, 0, 0]}}]})",
         "volumes[0].medium.scattering[0]: -1 1/m is out of range"},
        {head + R"("volumes": [{"type": "blob"}]})", "volumes[0].type: unknown choice"},
        {head + R"("volumes": [], "lights": [{"type": "spot", "inner_deg": 40, "outer_deg": 30}]})", "lights[0].inner_deg"},
        {head + R"("volumes": [], "ambient": [1, 2]})", "ambient: expected an array of 3 numbers"},
        {head + R"("volumes": [], "tags": ["a", 3]})", "tags[1]"},
        {R"({"brume_preset": 1, "volumes": []})", "name: missing required key"},
        {head + R"("ambient": [0, 0, 0]})", "volumes: missing required key"},
        {head + R"("volumes": [], "name": "y"})", "name: duplicate key"},
        {R"({"name": "x", "volumes": []})", "brume_preset: missing required key"},
        {R"({"brume_preset": 2, "name": "x", "volumes": []})", "version 2 is newer than this build of Brume reads (1)"},
        {R"({"brume_preset": 0, "name": "x", "volumes": []})", "unsupported version 0"},
        {R"({"brume_preset": 1.5, "name": "x", "volumes": []})", "expected an integer version"},
        {R"({"brume_preset": 1, "name": "x", "volumes": [)", "look.json: line 1"},
    };
    for (const Case& c : cases) {
        Result<Preset> p = parsePreset(c.text, "look.json", "/tmp");
        ASSERT_FALSE(p) << c.text;
        EXPECT_EQ(p.error().message.rfind("look.json: ", 0), 0u) << p.error().message;
        EXPECT_NE(p.error().message.find(c.mention), std::string::npos) << c.mention << " / " << p.error().message;
    }
}

TEST(Preset, ApplyReplaceAndAdd) {
    Result<Scene> target = parseScene(sceneText(), "t.json");
    ASSERT_TRUE(target);
    target.value().baseDir = "/tmp/t";
    Preset p;
    p.name = "p";
    p.ambient = {0.5f, 0.5f, 0.5f};
    Volume v;
    v.type = VolumeType::Height;
    v.medium.scattering = glm::vec3(0.02f);
    p.volumes = {v, v};
    Result<Scene> replaced = applyPreset(target.value(), p, PresetApply::Replace, "/tmp/t", "o.json");
    ASSERT_TRUE(replaced) << replaced.error().message;
    EXPECT_EQ(replaced.value().volumes, p.volumes);
    EXPECT_EQ(replaced.value().ambient, p.ambient);
    EXPECT_EQ(replaced.value().lights, target.value().lights) << "a preset without lights leaves them alone";
    EXPECT_EQ(replaced.value().camera, target.value().camera);
    EXPECT_EQ(replaced.value().geometry, target.value().geometry);

    p.lights = std::vector<Light>{makeLight(LightType::Point)};
    Result<Scene> added = applyPreset(target.value(), p, PresetApply::Add, "/tmp/t", "o.json");
    ASSERT_TRUE(added) << added.error().message;
    ASSERT_EQ(added.value().volumes.size(), 3u);
    EXPECT_EQ(added.value().volumes[0], target.value().volumes[0]);
    EXPECT_EQ(added.value().ambient, target.value().ambient) << "--add keeps the scene's ambient";
    ASSERT_EQ(added.value().lights.size(), 2u);
    EXPECT_EQ(added.value().lights[1].type, LightType::Point);
    Result<Scene> replacedLights = applyPreset(target.value(), p, PresetApply::Replace, "/tmp/t", "o.json");
    ASSERT_TRUE(replacedLights);
    EXPECT_EQ(replacedLights.value().lights, *p.lights);
}

TEST(Preset, AddingAVdbOfAnotherEncodingIsRefused) {
    Result<Scene> target = parseScene(sceneText("g.vdb", "fp16"), "t.json");
    ASSERT_TRUE(target);
    Result<Scene> source = parseScene(sceneText("g.vdb", "float"), "s.json");
    ASSERT_TRUE(source);
    const Preset p = presetFromScene(source.value(), "p", false);
    Result<Scene> r = applyPreset(target.value(), p, PresetApply::Add, "/tmp", "out.json");
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("out.json: volumes[3].encoding"), std::string::npos) << r.error().message;
}

// save in one folder, apply from another, write the scene to a third: every VDB path still names the
// same file, and the result renders.
TEST(PresetCli, PathsFollowTheFiles) {
    TempDir t("preset", "paths");
    makeGrid(t.path / "grids" / "g.vdb");
    writeText(t.path / "scenes" / "a.json", sceneText("../grids/g.vdb"));
    writeText(t.path / "targets" / "b.json", sceneText());
    fs::create_directories(t.path / "looks" / "mine");
    fs::create_directories(t.path / "out" / "deep");
    CliRun r = brumeIn(t.path, "preset save scenes/a.json -o looks/mine/look.json --name Puff --tag smoke --tag test");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string look = readText(t.path / "looks" / "mine" / "look.json");
    EXPECT_NE(look.find("\"../../grids/g.vdb\""), std::string::npos) << look;
    EXPECT_NE(look.find("\"brume_preset\": 1"), std::string::npos) << look;

    Result<Image> thumb = readPngLinear((t.path / "looks" / "mine" / "look.png").string());
    ASSERT_TRUE(thumb) << thumb.error().message;
    EXPECT_EQ(thumb.value().width, 160);
    EXPECT_EQ(thumb.value().height, 90);

    r = brumeIn(t.path / "looks", "preset apply mine/look.json ../targets/b.json -o ../out/deep/c.json --add");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    Result<Scene> c = loadSceneFile((t.path / "out" / "deep" / "c.json").string());
    ASSERT_TRUE(c) << c.error().message;
    ASSERT_EQ(c.value().volumes.size(), 3u);
    EXPECT_EQ(c.value().volumes[2].file, "../../grids/g.vdb");
    ASSERT_TRUE(c.value().volumes[2].density_texture);
    EXPECT_EQ(c.value().volumes[2].density_texture->file, "../../grids/g.vdb");
    r = brumeIn(t.path, "render out/deep/c.json -o c.png --cpu");
    EXPECT_EQ(r.exitCode, 0) << r.err;

    r = brumeIn(t.path, "preset list looks/mine");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("look.json\tPuff\t[smoke, test]\tthumbnail"), std::string::npos) << r.out;
}

TEST(PresetCli, BadInputIsOneSentenceAndWritesNothing) {
    TempDir t("preset", "bad");
    writeText(t.path / "a.json", sceneText());
    writeText(t.path / "novdb.json", sceneText("missing.vdb"));
    writeText(t.path / "bad.json", R"({"brume_preset": 1, "name": "x", "volumes": [{"type": "box", "edge_fade": 2}]})");
    writeText(t.path / "newer.json", R"({"brume_preset": 7, "name": "x", "volumes": []})");
    writeText(t.path / "lostvdb.json",
              R"({"brume_preset": 1, "name": "x", "volumes": [{"type": "vdb", "file": "gone/g.vdb"}]})");
    writeText(t.path / "afile", "x");
    const size_t before = brume::test::fileCount(t.path);
    expectOneLineError(brumeIn(t.path, "preset apply bad.json a.json -o o.json"), "bad.json: volumes[0].edge_fade");
    expectOneLineError(brumeIn(t.path, "preset apply newer.json a.json -o o.json"), "newer than this build");
    expectOneLineError(brumeIn(t.path, "preset apply lostvdb.json a.json -o o.json"), "lostvdb.json: volumes[0].file");
    expectOneLineError(brumeIn(t.path, "preset apply missing.json a.json -o o.json"), "missing.json");
    expectOneLineError(brumeIn(t.path, "preset save novdb.json -o o.json"), "novdb.json: volumes[1].file");
    expectOneLineError(brumeIn(t.path, "preset save a.json -o nofolder/o.json"), "nofolder");
    expectOneLineError(brumeIn(t.path, "preset save a.json -o afile/o.json"), "afile");
    expectOneLineError(brumeIn(t.path, "preset save a.json -o o.txt"), "o.txt");
    expectOneLineError(brumeIn(t.path, "preset save a.json -o o.json --thumbnail-width 2"), "--thumbnail-width");
    expectOneLineError(brumeIn(t.path, "preset apply bad.json a.json -o o.json --add --replace"), "--");
    expectOneLineError(brumeIn(t.path, "preset list nofolder"), "nofolder");
    EXPECT_EQ(brume::test::fileCount(t.path), before) << "a failed command must leave no file behind";
}

TEST(PresetCli, HelpNamesEveryOption) {
    TempDir t("preset", "help");
    const CliRun save = brumeIn(t.path, "preset save --help");
    for (const char* o : {"--output", "--name", "--description", "--tag", "--no-lights", "--no-thumbnail",
                          "--thumbnail-width", "--thumbnail-height"})
        EXPECT_NE(save.out.find(o), std::string::npos) << o << "\n" << save.out;
    const CliRun apply = brumeIn(t.path, "preset apply --help");
    for (const char* o : {"--output", "--replace", "--add"}) EXPECT_NE(apply.out.find(o), std::string::npos) << o;
    EXPECT_EQ(brumeIn(t.path, "preset list --help").exitCode, 0);
}

// The shipped library (assets/presets): at least 8 distinct looks, each one reads (its VDB files
// present), has its thumbnail beside it, and applied to a plain stage changes the image and renders
// finite.
TEST(PresetLibrary, EveryShippedPresetReadsAndRendersFinite) {
    const std::string dir = std::string(BRUME_SOURCE_DIR) + "/assets/presets";
    const std::vector<PresetListing> listings = listPresets(dir);
    ASSERT_GE(listings.size(), 8u);
    Scene stage = brume::test::sceneWithTestView();
    Geometry ground;
    ground.type = GeometryType::Plane;
    stage.geometry = {ground};
    stage.lights = {makeLight(LightType::Directional)};
    stage.baseDir = dir;
    RenderRequest request;
    request.width = 48;
    request.height = 27;
    request.quality = Quality::Low;
    request.threads = 2;
    const Image bare = renderFroxelCpu(stage, request).image;
    std::vector<std::vector<Volume>> seen;
    for (const PresetListing& l : listings) {
        SCOPED_TRACE(l.path);
        ASSERT_TRUE(l.preset) << l.error;
        EXPECT_TRUE(l.hasThumbnail);
        Result<Image> thumb = readPngLinear(presetThumbnailPath(l.path));
        ASSERT_TRUE(thumb) << thumb.error().message;
        EXPECT_EQ(thumb.value().width, 160);
        EXPECT_EQ(thumb.value().height, 90);
        EXPECT_FALSE(l.preset->name.empty());
        EXPECT_FALSE(l.preset->description.empty());
        EXPECT_FALSE(l.preset->volumes.empty());
        for (const std::vector<Volume>& other : seen) EXPECT_NE(other, l.preset->volumes) << "two presets, one look";
        seen.push_back(l.preset->volumes);
        Result<Scene> applied = applyPreset(stage, *l.preset, PresetApply::Replace, dir, "stage.json");
        ASSERT_TRUE(applied) << applied.error().message;
        std::vector<std::string> warnings;
        ASSERT_TRUE(loadSceneGrids(applied.value(), "stage.json", uint64_t(256) << 20, warnings));
        const Image img = renderFroxelCpu(applied.value(), request).image;
        EXPECT_TRUE(allFinite(img));
        EXPECT_GT(relativeMeanAbsError(img, bare), 0.01) << "the look should change the stage";
    }
}

}  // namespace
