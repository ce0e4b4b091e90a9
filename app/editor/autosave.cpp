#include "autosave.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "io/atomic_file.h"
#include "io/scene_json.h"

namespace brume::editor {

std::string recoveryPathFor(const std::string& scenePath) {
    if (!scenePath.empty()) return scenePath + ".recovery.json";
    std::filesystem::path dir;
    if (const char* state = std::getenv("XDG_STATE_HOME"); state && *state) dir = state;
    else if (const char* home = std::getenv("HOME"); home && *home) dir = std::filesystem::path(home) / ".local/state";
    else dir = std::filesystem::temp_directory_path();
    dir /= "brume";
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    return (dir / "untitled.recovery.json").string();
}

Result<void> Autosave::tick(const Document& doc, double now, double nextTickIn) {
    if (!docPathKnown_ || doc.path() != docPath_) {
        const bool moved = docPathKnown_;
        docPath_ = doc.path();
        docPathKnown_ = true;
        // A kill -9 during an earlier save or autosave left a temporary beside the file.
        if (!docPath_.empty()) removeStaleTemporaries(docPath_);
        if (!moved) removeStaleTemporaries(path_);
        if (const std::string want = recoveryPathFor(docPath_); moved && want != path_) {
            retarget(want);  // Save As (New and Open have retargeted already)
            discard();
        }
    }
    if (!doc.dirty()) {
        if (fileExists_) discard();
        return {};
    }
    // Waiting is fine only if the next call still comes within the interval of the last write.
    if (doc.revision() == writtenRevision_ || now + std::max(nextTickIn, 0.0) - lastWrite_ < interval_) return {};
    lastWrite_ = now;
    writtenRevision_ = doc.revision();
    Result<void> r = saveSceneFile(doc.scene(), path_);
    if (!r) return Error{"Autosave failed: " + r.error().message};
    fileExists_ = true;
    ++writes_;
    return {};
}

void Autosave::discard() {
    std::error_code ec;
    std::filesystem::remove(path_, ec);
    fileExists_ = false;
    writtenRevision_ = ~uint64_t(0);
}

void Autosave::retarget(std::string recoveryPath) {
    discard();
    path_ = std::move(recoveryPath);
    removeStaleTemporaries(path_);
    lastWrite_ = -1.0e30;
}

}  // namespace brume::editor
