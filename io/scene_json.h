// Scene file format v1 (docs/scene-format.md): a strict reader and a lossless writer.
// Strict: an unknown key, a wrong type, a value outside the range in core/settings.h or an
// inconsistent pair of values is an Error "FILE: JSON-PATH: what is wrong", never a silent default.
// Lossless: parseScene(sceneToJson(s)) == s for every scene the reader accepts.
#pragma once

#include <string>
#include <string_view>

#include "core/result.h"
#include "core/scene.h"

namespace brume {

// `fileName` only names the source in error messages; scene.baseDir is left empty.
Result<Scene> parseScene(std::string_view json, const std::string& fileName);

// Reads and parses the file; sets scene.baseDir to the file's folder (absolute).
Result<Scene> loadSceneFile(const std::string& path);

// Pretty JSON in a stable key order, with every key of each object's type (froxel overrides only
// when set). Floats are written with the fewest digits that read back to the same float.
std::string sceneToJson(const Scene& scene);

// Writes sceneToJson(scene) atomically.
Result<void> saveSceneFile(const Scene& scene, const std::string& path);

// The docs' settings table (| key | unit | default | range | description |) from settings::kAll.
std::string settingsMarkdownTable();

}  // namespace brume
