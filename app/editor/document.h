// The editor's document: the scene being edited, its file, undo/redo and the action layer that
// every UI path (mouse, keyboard, script) goes through. An Action is one line of text
// ("set volumes[0].medium.phase_g 0.5"), so a session can be recorded and replayed by tests.
//
// Edits of parameters go through the scene's JSON form and the strict reader (parseScene), so an
// edit is validated exactly like a scene file: a value out of the range in core/settings.h is an
// Error naming the JSON path, and the scene is left unchanged. Undo keeps whole-scene snapshots
// (scenes are a few KiB); a group (begin ... end, e.g. a mouse drag) is one undo step.
#pragma once

#include <string>
#include <vector>

#include "core/result.h"
#include "core/scene.h"

namespace brume::editor {

struct Action {
    std::string verb;
    std::vector<std::string> args;
};

// Splits a script line into words; "double quotes" keep spaces, \" and \\ escape inside them.
// Empty lines and lines starting with '#' give an Action with an empty verb.
Result<Action> parseAction(const std::string& line);
// The line parseAction reads back to the same Action (what a recording writes).
std::string formatAction(const Action& action);

class Document {
public:
    Document() = default;
    // The scene as loaded from `path` (empty path: a new, untitled scene).
    Document(Scene scene, std::string path);

    const Scene& scene() const { return scene_; }
    const std::string& path() const { return path_; }
    // Whether the scene differs from the last one saved or loaded (undoing back to it is clean).
    // Hiding is not saved, so it does not make the scene dirty.
    bool dirty() const;
    // Increases with every change (edits, undo, redo); renderers and autosave compare it.
    uint64_t revision() const { return revision_; }
    // Inside begin ... end: a drag (gizmo, camera, slider) or a fly is under way.
    bool grouping() const { return groupDepth_ > 0; }
    bool canUndo() const { return !undo_.empty(); }
    bool canRedo() const { return !redo_.empty(); }

    // Applies one document action; an error leaves the document unchanged. Verbs:
    //   add volume|light|geometry|influencer TYPE [NAME]     (vdb: add volume vdb NAME FILE)
    //   delete|duplicate KIND INDEX, rename KIND INDEX NAME   (KIND: volume, light, geometry, influencer)
    //   hide|show KIND INDEX   (editor view state: undoable, never saved, see Volume::hidden)
    //   set PATH VALUE...   (PATH like volumes[0].transform.translation; vec3 takes 3 numbers)
    //   begin, end          (everything in between is one undo step)
    //   undo, redo, save [PATH]   (save PATH is Save As; atomic)
    //   key PATH SECONDS    (PATH like volumes[0].medium.scattering: a key with the setting's
    //                       current value at that scene time; replaces a key at the same time)
    //   unkey PATH SECONDS  (removes that key; the last key of a setting removes its track)
    //   interpolate PATH linear|smooth   (how that keyed setting moves between its keys)
    Result<void> apply(const Action& action);
    static bool isDocumentVerb(const std::string& verb);

    // Replaces the scene as one undoable edit (used by recovery and the camera).
    void replaceScene(const Scene& scene);
    // Starts over with `scene` from `path` (File > New, Open): nothing to undo, not dirty; the
    // revision still increases, so the viewport re-renders.
    void reset(Scene scene, std::string path);
    // Marks `scene` as what is on disk (after recovery: the file's scene), keeping the current one.
    void setSavedScene(const Scene& scene) { saved_ = scene; }

    // The current value at a settings path as JSON text ("[1,2,3]", "0.5", "\"box\""), or an Error.
    Result<std::string> valueText(const std::string& path) const;

private:
    Result<void> add(const std::vector<std::string>& a);
    Result<void> removeOrDuplicate(const std::string& verb, const std::vector<std::string>& a);
    Result<void> rename(const std::vector<std::string>& a);
    Result<void> hide(const std::string& verb, const std::vector<std::string>& a);
    Result<void> set(const std::vector<std::string>& a);
    Result<void> save(const std::vector<std::string>& a);
    Result<void> key(const std::string& verb, const std::vector<std::string>& a);  // key_edit.cpp
    Result<void> interpolate(const std::vector<std::string>& a);                   // key_edit.cpp
    void commit(Scene next);
    void undo();
    void redo();
    void followFolder();

    Scene scene_;
    Scene saved_;
    std::string path_;
    std::vector<Scene> undo_;
    std::vector<Scene> redo_;
    int groupDepth_ = 0;  // begin/end nest: a camera move inside a drag stays in the drag's step
    bool groupSnapshotTaken_ = false;
    uint64_t revision_ = 0;
};

}  // namespace brume::editor
