// The editor's files without a window: New, Open and VDB import through the same Files::apply that
// Editor::run forwards `new`, `open` and `import` to, the recent-files list, and the browser's
// directory listing.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "app/editor/autosave.h"
#include "app/editor/files.h"
#include "app/editor/view.h"
#include "hostile_scenes.h"
#include "io/scene_json.h"
#include "mesh_test_util.h"
#include "vdb_test_util.h"

namespace fs = std::filesystem;
using namespace brume;
using namespace brume::editor;

namespace {

const std::string kDefaultScene = std::string(BRUME_SOURCE_DIR) + "/assets/scenes/default.json";

fs::path tempDir(const std::string& name) {
    fs::path d = fs::temp_directory_path() / ("brume_files_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

Result<void> run(Files& files, Document& doc, const std::string& line) {
    Result<Action> a = parseAction(line);
    if (!a) return a.error();
    if (Files::isFileVerb(a.value().verb)) return files.apply(doc, a.value());
    return doc.apply(a.value());
}

Document defaultAt(const fs::path& path) {
    fs::copy_file(kDefaultScene, path, fs::copy_options::overwrite_existing);
    Result<Scene> s = loadSceneFile(path.string());
    EXPECT_TRUE(s.ok());
    return Document(s.value(), path.string());
}

// A 16^3-voxel fog cube of density 1, 0.1 m voxels, written with the OpenVDB API.
void writeCube(const fs::path& path) {
    test::writeGrids(path, {test::makeGrid("density", 0, 15, [](openvdb::Coord) { return 1.0f; },
                                           openvdb::math::Transform::createLinearTransform(0.1))});
}

}  // namespace

TEST(EditorFiles, NewAndOpenRefuseUnsavedChangesUnlessDiscarded) {
    const fs::path dir = tempDir("open");
    Files files{RecentFiles()};
    Document doc = defaultAt(dir / "a.json");
    fs::copy_file(kDefaultScene, dir / "b.json");
    ASSERT_TRUE(run(files, doc, "set volumes[0].medium.phase_g 0.5").ok());
    const Scene edited = doc.scene();

    Result<void> r = run(files, doc, "open " + (dir / "b.json").string());
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("unsaved changes"), std::string::npos) << r.error().message;
    EXPECT_TRUE(doc.scene() == edited);  // refused: nothing changed
    EXPECT_EQ(doc.path(), (dir / "a.json").string());
    EXPECT_FALSE(run(files, doc, "new").ok());
    EXPECT_TRUE(doc.dirty());

    ASSERT_TRUE(run(files, doc, "open " + (dir / "b.json").string() + " --discard").ok());
    EXPECT_EQ(doc.path(), (dir / "b.json").string());
    EXPECT_FALSE(doc.dirty());
    EXPECT_FALSE(doc.canUndo());  // no undo across files
    EXPECT_EQ(doc.scene().volumes[0].medium.phase_g, loadSceneFile(kDefaultScene).value().volumes[0].medium.phase_g);

    // A clean document opens and starts anew without asking; New: a camera, a sun, a ground, no fog.
    ASSERT_TRUE(run(files, doc, "new").ok());
    EXPECT_EQ(doc.path(), "");
    EXPECT_FALSE(doc.dirty());
    ASSERT_EQ(doc.scene().lights.size(), 1u);
    EXPECT_EQ(doc.scene().lights[0].type, LightType::Directional);
    ASSERT_EQ(doc.scene().geometry.size(), 1u);
    EXPECT_EQ(doc.scene().geometry[0].type, GeometryType::Plane);
    EXPECT_TRUE(doc.scene().volumes.empty());
    // A bad file is an error naming it, and the document stays as it was.
    std::ofstream(dir / "bad.json") << "{ \"version\": 1, \"nonsense\": 3 }";
    r = run(files, doc, "open " + (dir / "bad.json").string());
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("bad.json"), std::string::npos) << r.error().message;
    EXPECT_EQ(doc.path(), "");
    fs::remove_all(dir);
}

TEST(EditorFiles, RecentFilesAreNewestFirstTenPersistedAndPruned) {
    const fs::path dir = tempDir("recent");
    ::setenv("XDG_CONFIG_HOME", (dir / "config").c_str(), 1);
    const std::string store = recentFilesPath();
    EXPECT_EQ(store, (dir / "config" / "brume" / "recent.json").string());
    Files files{RecentFiles(store)};
    Document doc;
    for (int i = 0; i < 12; ++i) {
        const fs::path p = dir / ("s" + std::to_string(i) + ".json");
        fs::copy_file(kDefaultScene, p);
        ASSERT_TRUE(run(files, doc, "open " + p.string()).ok());
    }
    files.noteRecent((dir / "s10.json").string());  // saved again: moves to the front, once
    const std::vector<std::string> want = {"s10", "s11", "s9", "s8", "s7", "s6", "s5", "s4", "s3", "s2"};
    auto names = [](const std::vector<std::string>& paths) {
        std::vector<std::string> out;
        for (const std::string& p : paths) out.push_back(fs::path(p).stem().string());
        return out;
    };
    EXPECT_EQ(names(files.recent().paths()), want);

    // Persisted: a new session reads the same list; a file deleted meanwhile is pruned with a message.
    fs::remove(dir / "s9.json");
    RecentFiles next(store);
    const std::vector<std::string> gone = next.load();
    ASSERT_EQ(gone.size(), 1u);
    EXPECT_NE(gone[0].find("s9.json"), std::string::npos) << gone[0];
    std::vector<std::string> pruned = want;
    std::erase(pruned, "s9");
    EXPECT_EQ(names(next.paths()), pruned);
    RecentFiles again(store);  // the pruning was written back
    EXPECT_TRUE(again.load().empty());
    EXPECT_EQ(names(again.paths()), pruned);
    ::unsetenv("XDG_CONFIG_HOME");
    fs::remove_all(dir);
}

TEST(EditorFiles, ImportVdbPlacesItInFrontOfTheCameraRelativeToTheScene) {
    const fs::path dir = tempDir("import");
    Files files{RecentFiles()};
    Document doc = defaultAt(dir / "scene.json");
    fs::create_directories(dir / "vdb");
    writeCube(dir / "vdb" / "cube.vdb");
    const size_t n = doc.scene().volumes.size();
    ASSERT_TRUE(run(files, doc, "import vdb " + (dir / "vdb" / "cube.vdb").string()).ok());
    ASSERT_EQ(doc.scene().volumes.size(), n + 1);
    const Volume v = doc.scene().volumes[n];
    EXPECT_EQ(v.type, VolumeType::Vdb);
    EXPECT_EQ(v.file, "vdb/cube.vdb");  // relative to the scene's folder
    ASSERT_TRUE(v.density && !v.density->empty());
    Result<Bounds> b = objectBounds(doc.scene(), "volume", n);
    ASSERT_TRUE(b.ok());
    EXPECT_LT(glm::length(b.value().center - doc.scene().camera.target), 1e-3f);  // centred on the target
    // The cube's 16 voxels of 0.1 m, give or take the voxel of trilinear support around them.
    EXPECT_NEAR(b.value().radius, 0.5f * std::sqrt(3.0f) * 1.6f, 0.5f * std::sqrt(3.0f) * 0.1f + 1e-4f);

    // An edit keeps the loaded grid (the JSON form does not carry it); undo removes the import.
    ASSERT_TRUE(run(files, doc, "set volumes[" + std::to_string(n) + "].transform.translation 0 1 0").ok());
    EXPECT_EQ(doc.scene().volumes[n].density, v.density);
    EXPECT_TRUE(objectBounds(doc.scene(), "volume", n).ok());
    ASSERT_TRUE(run(files, doc, "undo").ok());
    ASSERT_TRUE(run(files, doc, "undo").ok());
    EXPECT_EQ(doc.scene().volumes.size(), n);
    ASSERT_TRUE(run(files, doc, "redo").ok());

    // Saved and reopened, the grid is read again from the relative path.
    ASSERT_TRUE(run(files, doc, "save").ok());
    ASSERT_TRUE(run(files, doc, "open " + (dir / "scene.json").string()).ok());
    ASSERT_EQ(doc.scene().volumes.size(), n + 1);
    EXPECT_TRUE(doc.scene().volumes[n].density && !doc.scene().volumes[n].density->empty());
    EXPECT_TRUE(files.takeMessages().empty());

    // Save As into another folder keeps the relative path pointing at the same file.
    const fs::path elsewhere = tempDir("import_saveas");
    ASSERT_TRUE(run(files, doc, "save " + (elsewhere / "moved.json").string()).ok());
    Result<OpenedScene> moved = openSceneFile((elsewhere / "moved.json").string());
    ASSERT_TRUE(moved.ok()) << moved.error().message;
    EXPECT_EQ(moved.value().scene.volumes[n].file, (dir / "vdb" / "cube.vdb").string());
    EXPECT_TRUE(moved.value().warnings.empty());
    ASSERT_TRUE(run(files, doc, "save " + (dir / "back.json").string()).ok());  // and back: relative again
    EXPECT_EQ(loadSceneFile((dir / "back.json").string()).value().volumes[n].file, "vdb/cube.vdb");
    fs::remove_all(elsewhere);

    // Editing the file in the inspector reads the new one; a file that cannot be read refuses the edit.
    writeCube(dir / "vdb" / "other.vdb");
    const std::string file = "set volumes[" + std::to_string(n) + "].file ";
    const DensityGridPtr grid = doc.scene().volumes[n].density;
    ASSERT_TRUE(run(files, doc, file + "vdb/other.vdb").ok());
    EXPECT_TRUE(doc.scene().volumes[n].density && doc.scene().volumes[n].density != grid);
    const Scene beforeBadEdit = doc.scene();
    Result<void> bad = run(files, doc, file + "vdb/none.vdb");
    ASSERT_FALSE(bad.ok());
    EXPECT_NE(bad.error().message.find("none.vdb"), std::string::npos) << bad.error().message;
    EXPECT_TRUE(doc.scene() == beforeBadEdit);

    // A file outside the scene's folder is kept absolute.
    const fs::path outside = tempDir("import_outside") / "far.vdb";
    writeCube(outside);
    ASSERT_TRUE(run(files, doc, "import vdb " + outside.string()).ok());
    EXPECT_EQ(doc.scene().volumes.back().file, outside.string());
    fs::remove_all(outside.parent_path());
    fs::remove_all(dir);
}

TEST(EditorFiles, ImportingANonVdbOrAMissingFileIsAnErrorAndChangesNothing) {
    const fs::path dir = tempDir("badimport");
    Files files{RecentFiles()};
    Document doc = defaultAt(dir / "scene.json");
    const Scene before = doc.scene();
    std::ofstream(dir / "text.vdb") << "this is not an OpenVDB file\n";
    for (const std::string name : {"text.vdb", "missing.vdb"}) {
        Result<void> r = run(files, doc, "import vdb " + (dir / name).string());
        ASSERT_FALSE(r.ok()) << name;
        EXPECT_NE(r.error().message.find(name), std::string::npos) << r.error().message;
        EXPECT_TRUE(doc.scene() == before);
        EXPECT_FALSE(doc.dirty());
    }
    // A scene whose vdb file went missing still opens (to fix it), with the volume empty and a message.
    // (Adding a volume loads its grid, so the file exists until the scene is saved.)
    fs::copy_file(std::string(BRUME_SOURCE_DIR) + "/assets/noise/mist.vdb", dir / "missing.vdb");
    ASSERT_TRUE(run(files, doc, "add volume vdb smoke " + (dir / "missing.vdb").string()).ok());
    ASSERT_TRUE(run(files, doc, "save").ok());
    fs::remove(dir / "missing.vdb");
    ASSERT_TRUE(run(files, doc, "open " + (dir / "scene.json").string()).ok());
    const std::vector<std::string> messages = files.takeMessages();
    ASSERT_EQ(messages.size(), 1u);
    EXPECT_NE(messages[0].find("missing.vdb"), std::string::npos) << messages[0];
    EXPECT_FALSE(doc.scene().volumes.back().density);
    fs::remove_all(dir);
}

TEST(EditorFiles, TheBrowserListsFoldersFirstThenFilesOfTheExtension) {
    const fs::path dir = tempDir("list");
    fs::create_directories(dir / "zeta");
    fs::create_directories(dir / "alpha");
    fs::create_directories(dir / ".hidden");
    for (const char* f : {"b.json", "a.json", "c.vdb", "notes.txt"}) std::ofstream(dir / f) << "x";
    Result<std::vector<DirEntry>> json = listDirectory(dir.string(), ".json");
    ASSERT_TRUE(json.ok());
    std::vector<std::string> names;
    for (const DirEntry& e : json.value()) names.push_back(e.name + (e.isDir ? "/" : ""));
    EXPECT_EQ(names, (std::vector<std::string>{"alpha/", "zeta/", "a.json", "b.json"}));
    Result<std::vector<DirEntry>> vdb = listDirectory(dir.string(), ".vdb");
    ASSERT_TRUE(vdb.ok());
    EXPECT_EQ(vdb.value().back().name, "c.vdb");
    EXPECT_EQ(vdb.value().size(), 3u);
    EXPECT_FALSE(listDirectory((dir / "nope").string(), "").ok());
    fs::remove_all(dir);
}

// `import mesh PATH` (the browser's Import Mesh and a dropped .obj run it): a fog hull placed like an
// imported VDB; an edit of edge_fade_m makes the grid again; a mesh with holes is refused.
TEST(EditorFiles, ImportMeshMakesAHullAndEditsRemakeItsGrid) {
    const fs::path dir = tempDir("import_mesh");
    Files files{RecentFiles()};
    Document doc = defaultAt(dir / "scene.json");
    test::writeText(dir / "meshes" / "cube.obj", test::cubeObj(0.5f));
    test::writeText(dir / "meshes" / "open.obj", test::cubeObj(0.5f, 3));
    const size_t n = doc.scene().volumes.size();
    const Result<void> open = run(files, doc, "import mesh " + (dir / "meshes" / "open.obj").string());
    ASSERT_FALSE(open.ok());
    EXPECT_NE(open.error().message.find("not closed"), std::string::npos) << open.error().message;
    EXPECT_EQ(doc.scene().volumes.size(), n);
    ASSERT_TRUE(run(files, doc, "import mesh " + (dir / "meshes" / "cube.obj").string()).ok());
    ASSERT_EQ(doc.scene().volumes.size(), n + 1);
    const Volume v = doc.scene().volumes[n];
    EXPECT_EQ(v.type, VolumeType::Mesh);
    EXPECT_EQ(v.file, "meshes/cube.obj");
    ASSERT_TRUE(v.density && !v.density->empty());
    Result<Bounds> b = objectBounds(doc.scene(), "volume", n);
    ASSERT_TRUE(b.ok());
    EXPECT_LT(glm::length(b.value().center - doc.scene().camera.target), 0.05f);
    ASSERT_TRUE(run(files, doc, "set volumes[" + std::to_string(n) + "].edge_fade_m 0.3").ok());
    ASSERT_TRUE(doc.scene().volumes[n].density);
    EXPECT_NE(doc.scene().volumes[n].density, v.density);  // made again for the new fade
    ASSERT_TRUE(run(files, doc, "save").ok());
    ASSERT_TRUE(run(files, doc, "open " + (dir / "scene.json").string()).ok());
    EXPECT_TRUE(doc.scene().volumes[n].density && !doc.scene().volumes[n].density->empty());
    EXPECT_TRUE(files.takeMessages().empty());
    fs::remove_all(dir);
}

// Save As into another folder rebases a density texture's file and its detail layer's like a vdb
// volume's: the saved scene still names the same files.
TEST(EditorFiles, SaveAsIntoAnotherFolderKeepsTextureAndDetailFiles) {
    const fs::path dir = tempDir("texture_saveas"), elsewhere = tempDir("texture_saveas_other");
    fs::create_directories(dir / "vdb");
    writeCube(dir / "vdb" / "cube.vdb");
    Scene s = defaultAt(dir / "scene.json").scene();
    ASSERT_FALSE(s.volumes.empty());
    DensityTexture t;
    t.file = "vdb/cube.vdb";
    t.detail = makeDetailLayer();
    t.detail->file = "vdb/cube.vdb";
    s.volumes[0].density_texture = t;
    Document doc(s, (dir / "scene.json").string());
    Files files{RecentFiles()};
    ASSERT_TRUE(run(files, doc, "save " + (elsewhere / "moved.json").string()).ok());
    Result<Scene> moved = loadSceneFile((elsewhere / "moved.json").string());
    ASSERT_TRUE(moved.ok()) << moved.error().message;
    const std::string cube = (dir / "vdb" / "cube.vdb").string();
    EXPECT_EQ(moved.value().volumes[0].density_texture->file, cube);
    EXPECT_EQ(moved.value().volumes[0].density_texture->detail->file, cube);
    fs::remove_all(dir);
    fs::remove_all(elsewhere);
}

// Found by the crash-safety review (issue 17): Save As moved the document but not its autosave, so
// edits after it went on being autosaved beside the old file, where a restart on the new file
// never looks. The autosave follows the path; a stale recovery file at the new place is removed.
TEST(EditorFiles, AutosaveFollowsSaveAsIntoAnotherFolder) {
    const fs::path dir = tempDir("autosave_saveas");
    fs::create_directories(dir / "a");
    fs::create_directories(dir / "b");
    Files files{RecentFiles()};
    Document doc = defaultAt(dir / "a" / "scene.json");
    Autosave autosave(recoveryPathFor(doc.path()), 1.0);
    ASSERT_TRUE(autosave.tick(doc, 0.0).ok());
    std::ofstream(dir / "b" / "moved.json.recovery.json") << "{ a stale recovery file }";
    ASSERT_TRUE(run(files, doc, "set ambient 0.1 0.2 0.3").ok());
    ASSERT_TRUE(autosave.tick(doc, 10.0).ok());
    EXPECT_TRUE(fs::exists(dir / "a" / "scene.json.recovery.json"));
    ASSERT_TRUE(run(files, doc, "save " + (dir / "b" / "moved.json").string()).ok());
    ASSERT_TRUE(autosave.tick(doc, 11.0).ok());
    EXPECT_FALSE(fs::exists(dir / "a" / "scene.json.recovery.json"));
    EXPECT_FALSE(fs::exists(dir / "b" / "moved.json.recovery.json"));  // the stale one
    ASSERT_TRUE(run(files, doc, "set ambient 0.4 0.5 0.6").ok());
    ASSERT_TRUE(autosave.tick(doc, 20.0).ok());
    EXPECT_EQ(autosave.path(), (dir / "b" / "moved.json.recovery.json").string());
    Result<Scene> recovered = loadSceneFile((dir / "b" / "moved.json.recovery.json").string());
    ASSERT_TRUE(recovered.ok()) << recovered.error().message;
    EXPECT_FLOAT_EQ(recovered.value().ambient.x, 0.4f);
    EXPECT_FALSE(fs::exists(dir / "a" / "scene.json.recovery.json"));
    fs::remove_all(dir);
}

// The project's notes (issue 17): undoing past a Save As into another folder restored the VDB
// path relative to the old folder, and the next save wrote a path naming a file that is not there.
TEST(EditorFiles, UndoPastSaveAsIntoAnotherFolderKeepsVdbPathsPointingAtTheSameFile) {
    const fs::path dir = tempDir("undo_saveas");
    fs::create_directories(dir / "a" / "vdb");
    fs::create_directories(dir / "b");
    writeCube(dir / "a" / "vdb" / "cube.vdb");
    Files files{RecentFiles()};
    Document doc = defaultAt(dir / "a" / "scene.json");
    ASSERT_TRUE(run(files, doc, "import vdb " + (dir / "a" / "vdb" / "cube.vdb").string()).ok());
    const size_t n = doc.scene().volumes.size() - 1;
    ASSERT_EQ(doc.scene().volumes[n].file, "vdb/cube.vdb");
    ASSERT_TRUE(run(files, doc, "save " + (dir / "b" / "moved.json").string()).ok());
    const std::string absolute = (dir / "a" / "vdb" / "cube.vdb").string();
    EXPECT_EQ(doc.scene().volumes[n].file, absolute);
    ASSERT_TRUE(run(files, doc, "undo").ok());  // the save's rebase: back to the snapshot relative to a/
    EXPECT_EQ(doc.scene().volumes[n].file, absolute);
    ASSERT_TRUE(run(files, doc, "undo").ok());  // before the import
    ASSERT_EQ(doc.scene().volumes.size(), n);
    ASSERT_TRUE(run(files, doc, "redo").ok());
    ASSERT_EQ(doc.scene().volumes.size(), n + 1);
    EXPECT_EQ(doc.scene().volumes[n].file, absolute);
    ASSERT_TRUE(run(files, doc, "save").ok());
    Result<OpenedScene> saved = openSceneFile((dir / "b" / "moved.json").string());
    ASSERT_TRUE(saved.ok()) << saved.error().message;
    EXPECT_EQ(saved.value().scene.volumes[n].file, absolute);
    EXPECT_TRUE(saved.value().warnings.empty()) << saved.value().warnings.front();
    fs::remove_all(dir);
}

// A kill -9 during a save leaves the atomic write's temporary (io/atomic_file.h) beside the scene;
// the next session removes those of processes that are gone, never those of a running one.
TEST(EditorFiles, TemporariesLeftByAKilledSaveAreRemovedByTheNextSession) {
    const fs::path dir = tempDir("stale_tmp");
    Document doc = defaultAt(dir / "scene.json");
    const fs::path dead = dir / ".scene.json.2147483600.0.0.tmp";  // above any pid Linux hands out
    const fs::path deadRecovery = dir / ".scene.json.recovery.json.2147483600.3.0.tmp";
    const fs::path alive = dir / (".scene.json." + std::to_string(::getpid()) + ".0.0.tmp");
    const fs::path other = dir / ".other.json.2147483600.0.0.tmp";
    for (const fs::path& p : {dead, deadRecovery, alive, other}) std::ofstream(p) << "{ half a sce";
    Autosave autosave(recoveryPathFor(doc.path()), 1.0);
    ASSERT_TRUE(autosave.tick(doc, 0.0).ok());
    EXPECT_FALSE(fs::exists(dead));
    EXPECT_FALSE(fs::exists(deadRecovery));
    EXPECT_TRUE(fs::exists(alive));  // a save under way in a running process
    EXPECT_TRUE(fs::exists(other));  // another file's
    EXPECT_TRUE(loadSceneFile(doc.path()).ok());
    fs::remove_all(dir);
}

// The editor never crashes on a file the command line refuses (issue 17): mutated scenes (keys
// deleted, values of the wrong type, huge and tiny numbers, flipped bytes; tests/hostile_scenes.h)
// are checked by `brume validate`, then opened through the editor's Open. A refused file is one
// sentence naming it, and the open document stays as it was (or, where only a grid or mesh file
// failed, the scene opens with that warning, as the editor does for any unreadable grid); an
// accepted file opens. Nothing throws.
TEST(EditorFiles, MutatedScenesTheCommandLineRefusesNeverCrashTheEditor) {
    const fs::path dir = tempDir("hostile");
    const std::vector<fs::path> mutants = test::writeMutatedScenes(dir, 60, 17u);
    Files files{RecentFiles()};
    Document doc = defaultAt(dir / "base.json");
    int accepted = 0, refused = 0;
    for (const fs::path& m : mutants) {
        const std::string cmd = std::string(BRUME_EXE) + " validate " + test::quoted(m.string()) + " > /dev/null 2>&1";
        const int status = std::system(cmd.c_str());
        ASSERT_TRUE(WIFEXITED(status)) << m << ": brume validate did not exit";
        const int code = WEXITSTATUS(status);
        ASSERT_TRUE(code == 0 || code == 2) << m << ": brume validate exit code " << code;
        const std::string before = doc.path();
        files.takeMessages();
        Result<void> r{};
        EXPECT_NO_THROW(r = run(files, doc, "open \"" + m.string() + "\" --discard")) << m;
        if (code == 0) {
            ++accepted;
            EXPECT_TRUE(r.ok()) << m << ": the CLI accepts it, the editor says: " << (r.ok() ? "" : r.error().message);
            continue;
        }
        ++refused;
        if (r.ok()) {
            // Only a grid or a mesh could not be read: a warning, as for any unreadable grid.
            EXPECT_FALSE(files.takeMessages().empty()) << m << ": refused by the CLI, opened silently by the editor";
            continue;
        }
        const std::string& msg = r.error().message;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << m << ": not one line: " << msg;
        EXPECT_NE(msg.find(m.filename().string()), std::string::npos) << m << ": does not name the file: " << msg;
        EXPECT_EQ(doc.path(), before) << m;
    }
    EXPECT_GT(accepted, 0);
    EXPECT_GT(refused, 0);
    std::printf("mutated scenes: %d accepted, %d refused by brume validate\n", accepted, refused);
    fs::remove_all(dir);
}
