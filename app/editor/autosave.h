// Autosave and crash recovery. While the document has unsaved changes, its scene is written
// (atomically) to a recovery file beside the scene every `interval` seconds at most, so a crash
// loses at most one interval of work. Saving or a clean exit removes the file; finding it at start
// means the last session ended without either, and the editor offers to recover it.
#pragma once

#include <string>

#include "document.h"

namespace brume::editor {

// "dir/scene.json" -> "dir/scene.json.recovery.json" (beside the scene, so relative VDB paths
// resolve the same); an untitled scene uses $XDG_STATE_HOME/brume (or ~/.local/state/brume).
std::string recoveryPathFor(const std::string& scenePath);

class Autosave {
public:
    Autosave(std::string recoveryPath, double intervalSeconds)
        : path_(std::move(recoveryPath)), interval_(intervalSeconds) {}

    // Call every frame with a monotonic clock in seconds. Writes when the document is dirty, has
    // changed since the last autosave and the interval has passed, or will have passed before the
    // next call: `nextTickInSeconds` is the caller's estimate of that wait (the last frame's time),
    // so a slow frame (a render under load) cannot hold an edit back for longer than the interval.
    // Removes the file once the document is clean.
    // The file follows the document's path: after a Save As it moves beside the new file (a
    // recovery file already there predates that save and is removed), so a restart on the file
    // being edited finds it. New and Open call retarget themselves (a recovery file beside the
    // opened scene is kept: the editor offers it).
    Result<void> tick(const Document& doc, double nowSeconds, double nextTickInSeconds = 0.0);
    // Removes the recovery file (clean exit).
    void discard();
    // Removes the recovery file and writes the next one to `recoveryPath` (another scene opened).
    void retarget(std::string recoveryPath);
    const std::string& path() const { return path_; }
    int writes() const { return writes_; }

private:
    std::string path_;
    std::string docPath_;  // the document path path_ was last checked against
    bool docPathKnown_ = false;
    double interval_;
    double lastWrite_ = -1.0e30;
    uint64_t writtenRevision_ = ~uint64_t(0);
    bool fileExists_ = false;
    int writes_ = 0;
};

}  // namespace brume::editor
