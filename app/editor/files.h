// The editor's files, without a window: New, Open, recent files, VDB import and the file browser's
// directory listing. Editor::run forwards the verbs `new`, `open PATH [--discard]` and
// `import vdb|mesh PATH` to Files::apply, so the menus, shortcuts, the browser, a dropped file and
// --script all take the same path, and tests drive it without a window.
#pragma once

#include <string>
#include <vector>

#include "core/result.h"
#include "core/scene.h"
#include "document.h"

namespace brume::editor {

// $XDG_CONFIG_HOME/brume/recent.json, or ~/.config/brume/recent.json.
std::string recentFilesPath();

// Most recently opened or saved scenes first, at most kMax, absolute paths, persisted as
// {"recent": [...]} in `store` (empty: kept in memory only).
class RecentFiles {
public:
    static constexpr size_t kMax = 10;
    explicit RecentFiles(std::string store = "") : store_(std::move(store)) {}

    // Reads the store (a missing store is an empty list); files that no longer exist are dropped,
    // returned one sentence each for a notification.
    std::vector<std::string> load();
    // Puts `path` first (absolute, once), drops the oldest past kMax and writes the store.
    Result<void> add(const std::string& path);
    // Drops the files that no longer exist (writing the store when that changed); one sentence each.
    std::vector<std::string> prune();
    const std::vector<std::string>& paths() const { return paths_; }

private:
    Result<void> write() const;

    std::string store_;
    std::vector<std::string> paths_;
};

// What File > New starts from: the default camera, a sun, a ground plane and ambient light, no fog.
Scene newScene();

struct OpenedScene {
    Scene scene;
    std::string path;                   // absolute
    std::vector<std::string> warnings;  // vdb volumes whose grid could not be read (left empty)
};
// Reads a scene file strictly (like `brume render`) and the grids of its vdb volumes; a grid that
// fails to load leaves that volume empty and becomes a warning, so the scene still opens to fix it.
Result<OpenedScene> openSceneFile(const std::string& path);

// A vdb volume for the file at `path` (absolute or relative to the working directory), its grid
// loaded: `file` is relative to `sceneDir` when the file lies inside it, else absolute; the grid's
// centre is placed at the camera's target (in front of the camera). Errors (missing file, not a
// VDB, no float grid, corrupt) name the file.
Result<Volume> importVdbVolume(const Scene& scene, const std::string& sceneDir, const std::string& path);

// A mesh volume (a fog hull, io/mesh_import.h) for the closed OBJ mesh at `path`, its grid made, placed
// and named like importVdbVolume's; a mesh with holes or a bad file is refused in one sentence.
Result<Volume> importMeshVolume(const Scene& scene, const std::string& sceneDir, const std::string& path);

// `scene` as saved into folder `dir` (Save As to another folder): each vdb volume's `file` names
// the same file as before, relative to `dir` when inside it, else absolute; baseDir = dir.
Scene rebasedTo(Scene scene, const std::string& dir);

struct DirEntry {
    std::string name;
    bool isDir = false;
};
// The folders and the files ending in `ext` (".json", ".vdb"; empty: every file) of `dir`, folders
// first, each group sorted by name; hidden entries (".name") left out.
Result<std::vector<DirEntry>> listDirectory(const std::string& dir, const std::string& ext);

class Files {
public:
    explicit Files(RecentFiles recent) : recent_(std::move(recent)) {}

    static bool isFileVerb(const std::string& verb);
    // new [--discard], open PATH [--discard], import vdb PATH. New and Open refuse while the
    // document has unsaved changes unless --discard says to drop them (the UI asks first); they
    // replace the document (no undo across files). Import is one undoable edit.
    Result<void> apply(Document& doc, const Action& a);
    // A scene was opened or saved at `path`: it goes first in the recent list.
    void noteRecent(const std::string& path);

    RecentFiles& recent() { return recent_; }
    // Sentences for the notification area (pruned recent files, grids that failed to load).
    std::vector<std::string> takeMessages();
    void message(std::string text) { messages_.push_back(std::move(text)); }

private:
    RecentFiles recent_;
    std::vector<std::string> messages_;
};

}  // namespace brume::editor
