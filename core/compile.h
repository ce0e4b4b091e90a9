// Scene -> the shared per-volume and per-light records (shaders/shared/types.h) that the CPU froxel
// renderer, the CPU reference and the GPU all evaluate with the same shared functions.
#pragma once

#include <vector>

#include "../shaders/shared/brume.h"
#include "influence.h"
#include "quality.h"
#include "scene.h"

namespace brume {

struct CompiledScene {
    std::vector<shd::VolumeData> volumes;  // analytic volumes (vdb volumes are kept, kind VOLUME_VDB)
    // Per volume: the density grid of a vdb volume (null otherwise). The GPU uploads them back to back
    // in this order; VolumeData.kind.y is each grid's byte offset there.
    std::vector<DensityGridPtr> grids;
    // Per volume: its density texture's grid (null when none). The GPU uploads them after `grids`;
    // VolumeData.textureMin.w is each one's byte offset there.
    std::vector<DensityGridPtr> textures;
    // Per volume: its density texture's detail grid (null when none), uploaded after `textures`;
    // VolumeData.detailMin.w is each one's byte offset.
    std::vector<DensityGridPtr> details;
    std::vector<shd::LightData> lights;
    glm::vec3 ambient{0.0f};
    glm::vec3 cameraPosition{0.0f};
    float time = 0.0f;  // scene time [s]: density textures scroll with it
    // The influencers and their wakes at `time` (core/influence.h): every volume's density is
    // multiplied by influenceFactor in the camera's fog, not in fog shadows.
    InfluenceSet influence;
};

// The world-space box [lo, hi] holding the unit cube [-0.5, 0.5]^3 carried by worldFromLocal (a box
// volume's or a box surface's transform): the box of its 8 corners.
void unitCubeWorldBounds(const glm::mat4& worldFromLocal, glm::vec3& lo, glm::vec3& hi);

shd::VolumeData compileVolume(const Volume& v);
shd::LightData compileLight(const Light& l);
CompiledScene compileScene(const Scene& scene);

// Density of volume i at a world position, without bounds test: analytic or grid-sampled, times its
// density texture's factor.
float volumeDensity(const CompiledScene& cs, size_t i, glm::vec3 worldPos);

// The same without the density texture: what fog shadows see (the texture's mean factor is 1 for
// strength <= 1; docs/vdb.md).
float plainVolumeDensity(const CompiledScene& cs, size_t i, glm::vec3 worldPos);

// Volume i's density texture factor at a world position at cs.time (1 when it has none).
float densityTextureFactor(const CompiledScene& cs, size_t i, glm::vec3 worldPos);

// Sum of every volume's media at a world position (vdb volumes sample their grid), times the
// influencers' factor there.
shd::MediaSample mediaAt(const CompiledScene& cs, glm::vec3 worldPos);

// Closed-form fog of the height and depth volumes along the camera ray [s0, s1] (origin = camera
// position, dir unit), lit by the directional lights and the ambient: what lies past the froxel range
// (shaders/shared/distant.h). Accumulated onto `a`.
shd::Accumulated accumulateDistantFog(const CompiledScene& cs, shd::Accumulated a, glm::vec3 dir, float s0, float s1);
// One piece of it: [s0, s1] lit by each directional light's fog transmittance at the piece's geometric
// middle (the renderers' distant fog table, shaders/shared/distant_table.h, is made of these).
shd::Accumulated accumulateDistantPiece(const CompiledScene& cs, shd::Accumulated a, glm::vec3 dir, float s0, float s1);

// The distant fog table's entries per corner for this scene and frame (shared/distant_table.h): 0
// where no height or depth fog goes on past the froxel far (no such volume, or the froxels reach the
// camera far). Both renderers tabulate exactly then (the GPU: SPEC_DISTANT_FOG).
int distantFogEntries(const CompiledScene& cs, const shd::FrameUniforms& frame);

// Per-frame constants for an image of width x height with the given froxel settings.
// jitter is the sample position inside each froxel, (0.5, 0.5, 0.5) = centres.
shd::FrameUniforms makeFrameUniforms(const Scene& scene, const CompiledScene& cs, int width, int height,
                                     const FroxelSettings& fs, glm::vec3 jitter = glm::vec3(0.5f));

}  // namespace brume
