// What `brume export` and `brume bake` read: a scene file or a preset file, told apart by their
// version key ("brume_scene" or "brume_preset"). A preset becomes a scene without camera and
// geometry (hasCamera false), its file paths absolute.
#pragma once

#include <string>

#include "core/result.h"
#include "core/scene.h"

namespace brume {

struct FogSource {
    Scene scene;            // baseDir set: relative file paths resolve against it
    bool isPreset = false;  // a preset: the camera and geometry are defaults, not the user's
    std::string name;       // the preset's name, or the scene file's stem
};

Result<FogSource> loadFogSource(const std::string& path);

}  // namespace brume
