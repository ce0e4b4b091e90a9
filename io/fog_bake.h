// `brume bake`: every volume of a scene evaluated into sparse world-space OpenVDB grids
// (docs/export.md, "OpenVDB bake"):
//   density   float  sigma_t [1/m] (the mean of its RGB channels)
//   Cd        vec3s  single-scattering albedo sigma_s / sigma_t per channel
//   emission  vec3s  emitted radiance per meter [W/(m^2 sr m)]
// Voxel (i, j, k) is centred at world (i, j, k) x voxel size. Only voxels with sigma_t > 0 (or some
// emission) are active: empty space stays empty. Depth fog is evaluated from the scene's camera.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "core/result.h"
#include "core/scene.h"

namespace brume {

struct WorldBox {
    glm::vec3 min{0.0f}, max{0.0f};
};

struct BakeOptions {
    float voxelSize = 0.1f;            // [m]
    std::optional<WorldBox> bounds;    // clips the bake; required for unbounded (height, depth) volumes
    int threads = 0;                   // 0 = every core
    uint64_t maxVoxels = uint64_t(1) << 28;  // voxels of the baked box, empty ones included (2^28: ~13 GB of samples at most)
    std::function<void(float)> progress;     // fraction done, from the calling thread
};

struct BakeResult {
    WorldBox box;             // the world box baked
    glm::ivec3 voxels{0};     // its size in voxels
    uint64_t activeVoxels = 0;
};

// The box a bake covers: the union of the volumes' bounds, clipped to options.bounds; an error
// naming `sceneName` and the unbounded volume when it has no --bounds.
Result<WorldBox> bakeBox(const Scene& scene, const BakeOptions& options, const std::string& sceneName);

// Bakes the scene (its vdb volumes' grids and density textures loaded) and writes `path` atomically.
Result<BakeResult> bakeFogVdb(const Scene& scene, const BakeOptions& options, const std::string& sceneName,
                              const std::string& path);

}  // namespace brume
