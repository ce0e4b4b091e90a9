// The editor's action layer without a window: every edit the UI makes is an Action line, so these
// tests drive the document exactly as the mouse, keyboard and --script do.
#include <gtest/gtest.h>

#include <filesystem>

#include "app/editor/autosave.h"
#include "app/editor/document.h"
#include "io/scene_json.h"

namespace fs = std::filesystem;
using namespace brume;
using namespace brume::editor;

namespace {

const std::string kDefaultScene = std::string(BRUME_SOURCE_DIR) + "/assets/scenes/default.json";

Document loadDefault(const std::string& path = kDefaultScene) {
    Result<Scene> s = loadSceneFile(kDefaultScene);
    EXPECT_TRUE(s.ok());
    return Document(s.value(), path);
}

void run(Document& doc, const std::string& line) {
    Result<Action> a = parseAction(line);
    ASSERT_TRUE(a.ok()) << a.error().message;
    Result<void> r = doc.apply(a.value());
    ASSERT_TRUE(r.ok()) << line << ": " << r.error().message;
}

fs::path tempDir(const std::string& name) {
    fs::path d = fs::temp_directory_path() / ("brume_editor_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

}  // namespace

TEST(EditorActions, ScriptedSessionSavesTheNewValuesAndUndoRestoresThem) {
    const fs::path dir = tempDir("session");
    Document doc = loadDefault((dir / "scene.json").string());
    const Scene before = doc.scene();
    const size_t n = before.volumes.size();
    run(doc, "add volume box \"my fog\"");
    run(doc, "set volumes[" + std::to_string(n) + "].transform.translation 1.5 0.25 -2");
    run(doc, "set volumes[" + std::to_string(n) + "].medium.scattering 0.75 0.5 0.25");
    EXPECT_TRUE(doc.dirty());
    run(doc, "save");
    EXPECT_FALSE(doc.dirty());

    Result<Scene> saved = loadSceneFile((dir / "scene.json").string());
    ASSERT_TRUE(saved.ok()) << saved.error().message;
    ASSERT_EQ(saved.value().volumes.size(), n + 1);
    const Volume& v = saved.value().volumes[n];
    EXPECT_EQ(v.name, "my fog");
    EXPECT_EQ(v.type, VolumeType::Box);
    EXPECT_EQ(v.transform.translation, glm::vec3(1.5f, 0.25f, -2.0f));
    EXPECT_EQ(v.medium.scattering, glm::vec3(0.75f, 0.5f, 0.25f));

    run(doc, "undo");
    EXPECT_EQ(doc.scene().volumes[n].medium.scattering, Volume{}.medium.scattering);
    run(doc, "undo");
    EXPECT_EQ(doc.scene().volumes[n].transform.translation, glm::vec3(0.0f));
    run(doc, "undo");
    EXPECT_TRUE(doc.scene() == before);
    EXPECT_FALSE(doc.canUndo());
    run(doc, "redo");
    run(doc, "redo");
    run(doc, "redo");
    EXPECT_TRUE(doc.scene() == saved.value());
    EXPECT_FALSE(doc.dirty());
    fs::remove_all(dir);
}

TEST(EditorActions, ADragIsOneUndoStep) {
    Document doc = loadDefault();
    const Scene before = doc.scene();
    run(doc, "begin");
    for (int i = 1; i <= 20; ++i) run(doc, "set volumes[0].transform.translation " + std::to_string(0.1 * i) + " 1 0");
    run(doc, "end");
    run(doc, "set volumes[0].medium.phase_g 0.7");
    run(doc, "undo");
    EXPECT_NEAR(doc.scene().volumes[0].transform.translation.x, 2.0f, 1e-6f);
    run(doc, "undo");
    EXPECT_TRUE(doc.scene() == before);
    EXPECT_FALSE(doc.dirty());
    EXPECT_FALSE(doc.canUndo());
}

TEST(EditorActions, AnOutOfRangeValueIsAnErrorNamingThePathAndChangesNothing) {
    Document doc = loadDefault();
    const Scene before = doc.scene();
    Result<void> r = doc.apply({"set", {"volumes[0].medium.phase_g", "1.5"}});
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("volumes[0].medium.phase_g"), std::string::npos) << r.error().message;
    for (const Action& bad : {Action{"set", {"volumes[0].medium.scattering", "1", "2"}},
                              Action{"set", {"volumes[9].name", "x"}}, Action{"set", {"camera.nonsense", "1"}},
                              Action{"delete", {"light", "7"}}, Action{"add", {"volume", "cone"}},
                              Action{"frobnicate", {}}}) {
        Result<void> e = doc.apply(bad);
        EXPECT_FALSE(e.ok()) << formatAction(bad);
        if (!e.ok()) {
            EXPECT_FALSE(e.error().message.empty());
        }
    }
    EXPECT_TRUE(doc.scene() == before);
    EXPECT_FALSE(doc.canUndo());
}

TEST(EditorActions, DeleteDuplicateRenameAndAddEveryKind) {
    Document doc = loadDefault();
    const Scene before = doc.scene();
    run(doc, "duplicate light 1");
    ASSERT_EQ(doc.scene().lights.size(), before.lights.size() + 1);
    EXPECT_EQ(doc.scene().lights[2].name, before.lights[1].name + " copy");
    EXPECT_EQ(doc.scene().lights[2].position, before.lights[1].position);
    run(doc, "rename light 2 \"warm \\\"glow\\\"\"");
    EXPECT_EQ(doc.scene().lights[2].name, "warm \"glow\"");
    run(doc, "delete volume 0");
    EXPECT_EQ(doc.scene().volumes.size(), before.volumes.size() - 1);
    for (const char* line : {"add volume height", "add volume depth", "add light directional", "add light point",
                             "add light spot", "add geometry plane", "add geometry box", "add geometry sphere"})
        run(doc, line);
    EXPECT_EQ(doc.scene().lights.back().type, LightType::Spot);
    EXPECT_EQ(doc.scene().geometry.back().type, GeometryType::Sphere);
    // The result is still a valid scene file.
    Result<Scene> back = parseScene(sceneToJson(doc.scene()), "roundtrip");
    ASSERT_TRUE(back.ok()) << back.error().message;
    EXPECT_TRUE(back.value() == doc.scene());
}

TEST(EditorActions, ActionsFormatAndParseBackExactly) {
    for (const Action& a : {Action{"rename", {"volume", "0", "a \"quoted\" name\\ # x"}}, Action{"undo", {}},
                            Action{"set", {"camera.position", "1", "-2.5", "3e-4"}}}) {
        Result<Action> back = parseAction(formatAction(a));
        ASSERT_TRUE(back.ok()) << formatAction(a);
        EXPECT_EQ(back.value().verb, a.verb);
        EXPECT_EQ(back.value().args, a.args);
    }
    EXPECT_TRUE(parseAction("   # a comment").value().verb.empty());
    EXPECT_FALSE(parseAction("rename volume 0 \"open").ok());
}

TEST(EditorAutosave, WritesWhileDirtyAtMostOncePerIntervalAndRemovesWhenSaved) {
    const fs::path dir = tempDir("autosave");
    const std::string scenePath = (dir / "scene.json").string();
    Document doc = loadDefault(scenePath);
    ASSERT_TRUE(doc.apply({"save", {}}).ok());
    Autosave autosave(recoveryPathFor(scenePath), 2.0);
    ASSERT_TRUE(autosave.tick(doc, 0.0).ok());
    EXPECT_FALSE(fs::exists(autosave.path()));  // clean: nothing to recover

    run(doc, "set volumes[0].medium.phase_g -0.25");
    ASSERT_TRUE(autosave.tick(doc, 10.0).ok());
    ASSERT_TRUE(fs::exists(autosave.path()));
    run(doc, "set volumes[0].edge_fade 0.5");
    ASSERT_TRUE(autosave.tick(doc, 11.0).ok());  // within the interval: not yet
    EXPECT_EQ(autosave.writes(), 1);
    ASSERT_TRUE(autosave.tick(doc, 12.0).ok());
    EXPECT_EQ(autosave.writes(), 2);
    Result<Scene> recovered = loadSceneFile(autosave.path());
    ASSERT_TRUE(recovered.ok()) << recovered.error().message;
    EXPECT_TRUE(recovered.value() == doc.scene());
    ASSERT_TRUE(autosave.tick(doc, 20.0).ok());  // unchanged since: no rewrite
    EXPECT_EQ(autosave.writes(), 2);

    run(doc, "save");
    ASSERT_TRUE(autosave.tick(doc, 21.0).ok());
    EXPECT_FALSE(fs::exists(autosave.path()));
    fs::remove_all(dir);
}
