// Quality presets and the froxel settings a render actually uses (preset, then the scene's
// "froxels" overrides, then clamping to the camera).
#pragma once

#include "scene.h"

namespace brume {

struct FroxelSettings {
    int tile_px;         // [px] screen tile per froxel column
    int slices;          // depth slices
    float near;          // [m] view depth where slice 0 begins
    float far;           // [m] view depth where the last slice ends
    float distribution;  // slice distribution exponent k
    bool operator==(const FroxelSettings&) const = default;
};

struct QualityPreset {
    Quality quality;
    int tile_px;
    int slices;
    float distribution;
    float far;  // [m], clamped to the camera's far
};

const QualityPreset& qualityPreset(Quality q);

// Preset values, overridden key by key by scene.froxels; near defaults to the camera's near; far is
// clamped to the camera's far and kept above near.
FroxelSettings resolveFroxelSettings(const Scene& scene, Quality quality);

// Froxel grid dimensions for an image: ceil(width / tile) x ceil(height / tile) x slices.
glm::ivec3 froxelGridDims(int width, int height, const FroxelSettings& s);

bool parseQuality(const std::string& text, Quality& out);

}  // namespace brume
