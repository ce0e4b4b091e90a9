// Preset files (docs/presets.md): a named fog look without camera or geometry, shared between
// scenes. A preset holds volumes (media, shapes, placement, density textures, VDB files), the
// ambient and, optionally, lights; it is read as strictly as a scene, by the scene's own readers
// (io/scene_json_parts.h), so every key has the same unit, default and range (core/settings.h).
//
// File paths: in a preset file, VDB and density texture files are relative to the preset's folder;
// in memory (Preset) they are absolute; applying a preset makes them relative to the output
// scene's folder again, so the preset, its grids and the scene may each live anywhere.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/image.h"
#include "core/result.h"
#include "core/scene.h"

namespace brume {

// The version this build writes; it reads this one and migrates older ones (io/preset.cpp).
inline constexpr int kPresetVersion = 1;

struct Preset {
    std::string name;
    std::string description;
    std::vector<std::string> tags;
    glm::vec3 ambient{0.0f};
    // Absent: the preset carries no lights and applying it leaves the scene's lights alone.
    std::optional<std::vector<Light>> lights;
    std::vector<Volume> volumes;  // file paths absolute
};

// The scene's fog (volumes, ambient, and lights when withLights), with paths made absolute from
// scene.baseDir (the working folder when empty).
Preset presetFromScene(const Scene& scene, const std::string& name, bool withLights);

// Reads a preset; relative file paths are resolved against `baseDir`. Errors "FILE: PATH: what".
Result<Preset> parsePreset(std::string_view text, const std::string& fileName, const std::string& baseDir);

// Reads the file, resolves its paths against its folder and checks that each VDB file exists.
Result<Preset> loadPresetFile(const std::string& path);

// The preset file's text with paths relative to `presetDir`.
std::string presetToJson(const Preset& preset, const std::string& presetDir);

// Checks each VDB file exists (errors name `fileName` and the volume's JSON path), then writes
// presetToJson atomically.
Result<void> savePresetFile(const Preset& preset, const std::string& path, const std::string& sourceName);

// Every VDB or density texture file of the volumes exists: "FILE: volumes[i].file: ... does not exist".
Result<void> checkVolumeFiles(const std::vector<Volume>& volumes, const std::string& baseDir, const std::string& fileName);

enum class PresetApply { Replace, Add };

// Replace: the scene's volumes (and lights, when the preset has them) become the preset's, and its
// ambient the preset's. Add: the preset's volumes (and lights) are appended; the ambient stays.
// Paths of the result are relative to `outDir` (the scene's own ones rebased from scene.baseDir),
// and the result is checked as a scene (one encoding for all vdb volumes); errors name `outName`.
Result<Scene> applyPreset(const Scene& scene, const Preset& preset, PresetApply mode, const std::string& outDir,
                          const std::string& outName);

// LOOK.json -> LOOK.png: the thumbnail beside a preset.
std::string presetThumbnailPath(const std::string& presetPath);

// The thumbnail of a look: `scene` (its camera, geometry and fog; VDB grids and density textures
// already loaded) at width x height by the reference renderer: no device needed, the same on every
// machine, and sharp where a froxel grid at thumbnail size would blur small volumes.
Result<Image> renderPresetThumbnail(const Scene& scene, int width, int height);

// savePresetFile with the thumbnail PNG beside it (none: no thumbnail written). Each file is
// written atomically, the PNG first, so a listing never shows the new preset without its
// thumbnail; if the preset cannot be written, a PNG this call created is removed again.
Result<void> savePresetWithThumbnail(const Preset& preset, const std::string& path, const std::string& sourceName,
                                     const Image* thumbnail);

struct PresetListing {
    std::string path;
    std::optional<Preset> preset;  // empty when the file did not read
    std::string error;             // the reason then
    bool hasThumbnail = false;
};

// The presets in `dir`, sorted by file name; not recursive. Every .json file is listed (one that
// does not read has its sentence in `error`) except valid JSON without a "brume_preset" key (a
// scene kept beside the looks).
std::vector<PresetListing> listPresets(const std::string& dir);

// $XDG_DATA_HOME/brume/presets, or ~/.local/share/brume/presets ("" when neither is known).
std::string userPresetDir();

}  // namespace brume
