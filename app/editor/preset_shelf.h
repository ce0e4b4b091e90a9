// The editor's presets (docs/presets.md) without a window: the shelf of looks from the shipped
// library (assets/presets) and the user's folder ($XDG_DATA_HOME/brume/presets), applying one to
// the document as one undo step, and saving the document's fog as a new look with its thumbnail.
// The file format, the apply rules and the thumbnail render are io/preset.h's, shared with
// `brume preset`.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "document.h"
#include "io/preset.h"

namespace brume::editor {

struct ShelfEntry {
    std::string path;
    bool shipped = false;           // from the library, not the user's folder
    std::optional<Preset> preset;   // empty when the file does not read
    std::string error;              // then the one sentence why
    bool hasThumbnail = false;      // a PNG beside it (presetThumbnailPath)
};

// The shipped library the build found (assets/presets), or "" when there is none.
std::string presetLibraryDir();

// The looks in `libraryDir` then `userDir` (either may be empty or missing), each sorted by file
// name. A file that does not read is an entry with its error: listed, never thrown.
std::vector<ShelfEntry> scanPresetShelf(const std::string& libraryDir, const std::string& userDir);

// Applies the preset file to the document: Replace swaps the fog (volumes, ambient, and lights
// where the preset has them), Add appends the preset's volumes (and lights). The preset's VDB grids
// and density textures are loaded first; one undo step. A preset that does not read, or whose grids
// do not load, leaves the document unchanged and is an Error naming the file.
Result<void> applyPresetToDocument(Document& doc, const std::string& presetPath, PresetApply mode);

struct PresetMeta {
    std::string name;
    std::string description;
    std::vector<std::string> tags;
};

// "Valley mist!" -> "valley-mist": the file name a look is saved under (lowercase letters, digits
// and dashes; "preset" when nothing is left).
std::string presetFileStem(const std::string& name);

// Saves the scene's fog (volumes, ambient, lights) as DIR/<presetFileStem(name)>.json with its
// thumbnail (renderPresetThumbnail of the scene at thumbnailSize) beside it, creating DIR. Refuses
// an empty name or tag and a file that exists already. Returns the preset's path.
Result<std::string> saveFogAsPreset(const Scene& scene, const std::string& dir, const PresetMeta& meta,
                                    glm::ivec2 thumbnailSize);

// The editor's preset verbs (Editor::run, scripts):
//   preset apply FILE replace|add
//   preset save NAME [DESCRIPTION [TAG...]]   (into userPresetDir(), thumbnail 160x90)
Result<void> runPresetAction(Document& doc, const Action& action);

}  // namespace brume::editor
