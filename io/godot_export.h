// `brume export --to godot`: a Godot 4 text scene (.tscn) of the fog (docs/export.md has the mapping
// table). Box volumes become box FogVolumes, exponential height fog a world-shaped FogVolume, depth
// fog the Environment's global volumetric fog; lights and the camera become their Godot nodes.
// Whatever Godot cannot express is listed in `losses`, one sentence each, and also written as
// comments at the top of the file: nothing is dropped silently.
#pragma once

#include <string>
#include <vector>

#include "io/fog_source.h"

namespace brume {

struct GodotExport {
    std::string tscn;
    std::vector<std::string> losses;
};

GodotExport exportGodot(const FogSource& source);

}  // namespace brume
