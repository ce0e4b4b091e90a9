// `brume export --to blender`: a Python script for Blender 3.4+ (Debian's) that rebuilds the fog
// with Cycles materials and, run as
//   blender -b --factory-startup --python OUT.py -- --render OUT.exr [--samples N] [--width W --height H]
// also renders it at single scattering (volume bounces 0) into a linear EXR. docs/export.md has the
// mapping; every setting Blender cannot express is in `losses`, one sentence each (also written as
// comments at the top of the script).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "core/result.h"
#include "io/fog_source.h"

namespace brume {

struct BlenderExport {
    std::string script;
    std::vector<std::string> losses;
};

// `baked`: volumes whose density texture was baked (bakeTexturedVolumes), by index: they become
// Volume objects reading that VDB instead of the analytic material.
BlenderExport exportBlender(const FogSource& source, const std::map<size_t, std::string>& baked = {});

// Blender cannot tile and scroll a 3D texture over a volume, so each box or vdb volume with a loaded
// density texture (and sigma_t > 0) is baked alone, with its placement, edge fade and texture at the
// scene time, into `SCRIPT_volumeI.vdb` beside `scriptPath` (io/fog_bake.h: density = sigma_t in
// 1/m), at a voxel of a 64th of the texture's tile (coarser where the box would pass 2^24
// voxels). Returns the files by volume index; errors name `sceneName`.
Result<std::map<size_t, std::string>> bakeTexturedVolumes(const Scene& scene, const std::string& scriptPath,
                                                         const std::string& sceneName);

}  // namespace brume
