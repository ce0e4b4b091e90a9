// `brume export --to blender`: a Python script for Blender 3.4+ (Debian's) that rebuilds the fog
// with Cycles materials and, run as
//   blender -b --factory-startup --python OUT.py -- --render OUT.exr [--samples N] [--width W --height H]
// also renders it at single scattering (volume bounces 0) into a linear EXR. docs/export.md has the
// mapping; every setting Blender cannot express is in `losses`, one sentence each (also written as
// comments at the top of the script).
#pragma once

#include <string>
#include <vector>

#include "io/fog_source.h"

namespace brume {

struct BlenderExport {
    std::string script;
    std::vector<std::string> losses;
};

BlenderExport exportBlender(const FogSource& source);

}  // namespace brume
