// Tileable 3D noise for density textures (`brume noise`): fBm of gradient (Perlin) noise whose
// lattice wraps, so the field is exactly periodic over one tile and the density_texture wrap
// (docs/vdb.md) shows no seam. Pure math: the OpenVDB file is written by io/vdb_export.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

namespace brume {

// Gradient noise at p [lattice cells] whose lattice repeats every `period` cells along each axis:
// noise(p + period e_i) == noise(p) exactly. Zero at lattice points, roughly in [-1, 1].
float periodicGradientNoise(glm::vec3 p, int period, uint32_t seed);

struct NoiseTileParams {
    int size = 64;       // voxels per side of the tile
    int octaves = 4;     // octave o has frequency << o cells per tile and amplitude 0.5^o
    int frequency = 4;   // lattice cells per tile in the first octave
    uint32_t seed = 1;
};

// The tile's values, x fastest then y then z (size^3), sampled at voxel centres (i + 0.5) / size of
// the tile, then mapped affinely so the mean is 0.5 and the largest deviation reaches 0 or 1: every
// value is in [0, 1]. Periodic with period `size` voxels. `progress` (optional, thread-safe) gets
// the fraction done.
std::vector<float> makeNoiseTile(const NoiseTileParams& params, int threads,
                                 const std::function<void(float)>& progress = nullptr);

}  // namespace brume
