// OpenVDB output: a dense block of float values as a fog-volume grid (used by `brume noise`).
#pragma once

#include <string>
#include <vector>

#include "core/result.h"

namespace brume {

// Writes values (size^3, x fastest) as the float fog-volume grid `gridName` on index box
// [0, size - 1]^3, every voxel active (zeros too, so the active box is the whole tile that a
// density_texture tiles), voxel size 1 / size m. Atomic: a reader sees the old file or the new one.
Result<void> writeDenseVdb(const std::string& path, const std::string& gridName, int size,
                           const std::vector<float>& values);

}  // namespace brume
