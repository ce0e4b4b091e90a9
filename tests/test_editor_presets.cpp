// The editor's presets (app/editor/preset_shelf.h) through its action layer, without a window:
// the shelf lists the shipped looks and the user's, a file that does not read is listed with one
// sentence, Replace and Add are one undo step each and bring the look's grids, and "Save fog as
// preset" writes the JSON and its thumbnail into the user's folder, reads back as the same fog and
// never overwrites a look.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "app/editor/document.h"
#include "app/editor/preset_shelf.h"
#include "io/image_io.h"
#include "io/scene_json.h"
#include "test_support.h"

namespace fs = std::filesystem;
using namespace brume;
using namespace brume::editor;
using brume::test::TempDir;

namespace {

const std::string kLibrary = std::string(BRUME_SOURCE_DIR) + "/assets/presets";

Document loadDefault() {
    Result<Scene> s = loadSceneFile(std::string(BRUME_SOURCE_DIR) + "/assets/scenes/default.json");
    EXPECT_TRUE(s.ok());
    return Document(s.value(), "");
}

Result<void> act(Document& doc, const std::string& line) {
    Result<Action> a = parseAction(line);
    if (!a) return a.error();
    return runPresetAction(doc, a.value());
}

// A small scene whose reference thumbnail renders in well under a second.
Scene smallFogScene() {
    Scene s;
    s.camera.position = {0, 1, 5};
    s.camera.target = {0, 1, 0};
    Light sun = makeLight(LightType::Directional);
    sun.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, -0.4f));
    s.lights.push_back(sun);
    s.volumes.push_back(test::boxFog({0, 1, 0}, {3, 2, 3}, 0.2f, 0.6f, 0.05f));
    s.volumes.back().name = "test box";
    s.ambient = {0.05f, 0.05f, 0.06f};
    return s;
}

}  // namespace

TEST(EditorPresets, ShelfListsTheLibraryAndExplainsBadFiles) {
    TempDir t("brume_editor_presets", "shelf");
    const fs::path user = t.path / "user";
    fs::create_directories(user);
    std::ofstream(user / "broken.json") << R"({"brume_preset": 1, "name": "x", "volumes": [)";
    std::ofstream(user / "notjson.json") << "hello";
    std::ofstream(user / "typo.json") << R"({"brume_preset": 1, "name": "t", "volumes": [], "ambeint": [0, 0, 0]})";
    std::ofstream(user / "future.json") << R"({"brume_preset": 99, "name": "f", "volumes": []})";
    std::ofstream(user / "a_scene.json") << R"({"brume_scene": 1})";  // not a preset: left out
    const std::vector<ShelfEntry> shelf = scanPresetShelf(presetLibraryDir(), user.string());
    ASSERT_EQ(presetLibraryDir(), kLibrary);
    size_t shipped = 0;
    std::vector<const ShelfEntry*> bad;
    for (const ShelfEntry& e : shelf) {
        if (e.shipped) {
            ++shipped;
            EXPECT_TRUE(e.preset.has_value()) << e.path << ": " << e.error;
            EXPECT_TRUE(e.hasThumbnail) << e.path;
        } else {
            EXPECT_FALSE(e.preset.has_value()) << e.path;
            bad.push_back(&e);
        }
    }
    EXPECT_GE(shipped, 8u);
    ASSERT_EQ(bad.size(), 4u) << "every bad file is listed, the scene is not";
    for (const ShelfEntry* e : bad) {
        EXPECT_FALSE(e->error.empty()) << e->path;
        EXPECT_EQ(e->error.find('\n'), std::string::npos) << "one sentence: " << e->error;
        EXPECT_NE(e->error.find(fs::path(e->path).filename().string()), std::string::npos) << "names the file: " << e->error;
    }
    EXPECT_NE(bad[3]->error.find("ambeint"), std::string::npos) << bad[3]->error;  // sorted: typo.json last
}

TEST(EditorPresets, ReplaceAndAddAreOneUndoStepEach) {
    Document doc = loadDefault();
    const Scene before = doc.scene();
    Result<Preset> look = loadPresetFile(kLibrary + "/valley_morning_mist.json");
    ASSERT_TRUE(look.ok()) << look.error().message;

    ASSERT_TRUE(act(doc, "preset apply " + kLibrary + "/valley_morning_mist.json replace").ok());
    ASSERT_EQ(doc.scene().volumes.size(), look.value().volumes.size());
    EXPECT_EQ(doc.scene().volumes[0].name, look.value().volumes[0].name);
    EXPECT_EQ(doc.scene().volumes[0].medium, look.value().volumes[0].medium);
    EXPECT_EQ(doc.scene().ambient, look.value().ambient);
    EXPECT_EQ(doc.scene().lights.size(), look.value().lights->size()) << "the look carries its lights";
    EXPECT_EQ(doc.scene().camera, before.camera) << "a look has no camera";
    ASSERT_TRUE(doc.apply({"undo", {}}).ok());
    EXPECT_EQ(doc.scene(), before) << "Replace is one undo step";
    EXPECT_FALSE(doc.canUndo());

    ASSERT_TRUE(act(doc, "preset apply " + kLibrary + "/valley_morning_mist.json add").ok());
    EXPECT_EQ(doc.scene().volumes.size(), before.volumes.size() + look.value().volumes.size());
    EXPECT_EQ(doc.scene().ambient, before.ambient) << "Add keeps the scene's ambient";
    ASSERT_TRUE(doc.apply({"undo", {}}).ok());
    EXPECT_EQ(doc.scene(), before) << "Add is one undo step";
}

TEST(EditorPresets, ApplyBringsTheLooksGridsAndRefusesBadFiles) {
    Document doc = loadDefault();
    ASSERT_TRUE(act(doc, "preset apply " + kLibrary + "/vdb_smoke_plume.json add").ok());
    bool sawVdb = false;
    for (const Volume& v : doc.scene().volumes) {
        if (v.type != VolumeType::Vdb) continue;
        sawVdb = true;
        EXPECT_NE(v.density, nullptr) << "the plume's grid is loaded";
    }
    EXPECT_TRUE(sawVdb);
    ASSERT_TRUE(act(doc, "preset apply " + kLibrary + "/drifting_noise_mist.json replace").ok());
    for (const Volume& v : doc.scene().volumes) {
        if (v.density_texture) {
            EXPECT_NE(v.density_texture->density, nullptr) << "the density texture is loaded";
        }
    }

    TempDir t("brume_editor_presets", "bad");
    std::ofstream(t.path / "bad.json") << R"({"brume_preset": 1, "name": "b", "volumes": [{"type": "box", "medium": {"phase_g": 3}}]})";
    const Scene before = doc.scene();
    const uint64_t revision = doc.revision();
    Result<void> r = act(doc, "preset apply " + (t.path / "bad.json").string() + " replace");
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("bad.json"), std::string::npos) << r.error().message;
    EXPECT_NE(r.error().message.find("phase_g"), std::string::npos) << r.error().message;
    EXPECT_EQ(doc.scene(), before);
    EXPECT_EQ(doc.revision(), revision);
    EXPECT_FALSE(act(doc, "preset apply " + (t.path / "missing.json").string() + " add").ok());
    EXPECT_FALSE(act(doc, "preset apply " + kLibrary + "/valley_morning_mist.json merge").ok()) << "replace|add only";
}

TEST(EditorPresets, SaveWritesTheLookAndItsThumbnailIntoTheUsersFolder) {
    TempDir t("brume_editor_presets", "save");
    ::setenv("XDG_DATA_HOME", (t.path / "data").c_str(), 1);
    const fs::path dir = t.path / "data" / "brume" / "presets";
    ASSERT_EQ(userPresetDir(), dir.string());
    Document doc(smallFogScene(), "");
    ASSERT_TRUE(act(doc, "preset save \"Test Mist!\" \"A box of mist.\" indoor thick").ok());
    const fs::path json = dir / "test-mist.json", png = dir / "test-mist.png";
    ASSERT_TRUE(fs::exists(json) && fs::exists(png));
    EXPECT_EQ(test::fileCount(dir), 2u) << "no temporary files left";
    Result<Preset> saved = loadPresetFile(json.string());
    ASSERT_TRUE(saved.ok()) << saved.error().message;
    EXPECT_EQ(saved.value().name, "Test Mist!");
    EXPECT_EQ(saved.value().description, "A box of mist.");
    EXPECT_EQ(saved.value().tags, (std::vector<std::string>{"indoor", "thick"}));
    Result<Image> thumb = readPngLinear(png.string());
    ASSERT_TRUE(thumb.ok());
    EXPECT_EQ(thumb.value().width, 160);
    EXPECT_EQ(thumb.value().height, 90);
    // The thumbnail is the fog, rendered: it differs from a render of the scene without it.
    Scene empty = smallFogScene();
    empty.volumes.clear();
    Result<Image> bare = renderPresetThumbnail(empty, 160, 90);
    ASSERT_TRUE(bare.ok());
    double difference = 0.0;
    for (size_t i = 0; i < thumb.value().pixels.size(); ++i)
        difference += std::abs(thumb.value().pixels[i].g - bare.value().pixels[i].g);
    EXPECT_GT(difference / static_cast<double>(thumb.value().pixels.size()), 0.01) << "the thumbnail shows the fog";

    // The saved look, applied to a new scene, is the same fog.
    Document other = loadDefault();
    ASSERT_TRUE(act(other, "preset apply " + json.string() + " replace").ok());
    ASSERT_EQ(other.scene().volumes.size(), 1u);
    EXPECT_EQ(other.scene().volumes[0].medium, doc.scene().volumes[0].medium);
    EXPECT_EQ(other.scene().volumes[0].transform, doc.scene().volumes[0].transform);
    EXPECT_EQ(other.scene().ambient, doc.scene().ambient);

    // A look is never overwritten; empty names and tags are refused; nothing is written then.
    const std::string before = test::readText(json);
    Result<void> again = act(doc, "preset save \"test mist\"");
    ASSERT_FALSE(again.ok());
    EXPECT_NE(again.error().message.find("exists"), std::string::npos) << again.error().message;
    EXPECT_FALSE(act(doc, "preset save \"\"").ok());
    EXPECT_FALSE(act(doc, "preset save named desc \"\"").ok());
    EXPECT_EQ(test::readText(json), before);
    EXPECT_EQ(test::fileCount(dir), 2u);
    const std::vector<ShelfEntry> shelf = scanPresetShelf("", dir.string());
    ASSERT_EQ(shelf.size(), 1u);
    EXPECT_TRUE(shelf[0].preset && shelf[0].hasThumbnail);
    ::unsetenv("XDG_DATA_HOME");
}

TEST(EditorPresets, FileStemsAreSafe) {
    EXPECT_EQ(presetFileStem("Valley Morning Mist"), "valley-morning-mist");
    EXPECT_EQ(presetFileStem("../../etc/passwd"), "etc-passwd");
    EXPECT_EQ(presetFileStem("???"), "preset");
}
