// Volumetric shadows on the CPU froxel renderer: the loop over volumes around the shared closed
// forms of shaders/shared/shadows.h (the GPU's light and geometry shaders run the same loop).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "compile.h"
#include "media_region.h"
#include "quality.h"
#include "render.h"

namespace brume {

// Whether the froxel renderers evaluate fog transmittance toward point and spot lights at this
// quality (FrameUniforms.localFogShadows); the sun's is always evaluated. On at every quality today (a
// light must not shine through fog it cannot cross); kept as a switch for measurements.
bool localLightFogShadows(Quality q);

// exp(-optical depth) from p along unit toLight over `distance` (BRUME_HUGE for a directional
// light) through every analytic volume except depth fog; 1 for a light shd::fogShadowsLight skips.
glm::vec3 lightFogTransmittance(const CompiledScene& cs, const shd::LightData& l, glm::vec3 p, glm::vec3 toLight,
                                float distance, int localLightsToo);

// Transmittance volume reduction r (shaders/shared/shadow_volume.h) at this quality: the light pass
// evaluates 1/r^3 of the closed forms, plus the froxels at shadow edges. Measured trade in
// docs/shadows.md.
int shadowVolumeReduction(Quality q);

// Sets frame.shadows (local-light fog shadows, transmittance-volume reduction) for a request:
// the one place both froxel renderers take these from.
void applyShadowSettings(shd::FrameUniforms& frame, const RenderRequest& request);

// Each shadowing light's transmittance on the reduced grid, light after light: index
// ((light * d.z + z) * d.y + y) * d.x + x, d = shd::shadowVolumeDims (the GPU's image stacks the
// lights along z the same way). Lights shd::fogShadowsLight skips hold 1. With vdb shadows on
// (frame.vdbShadowSamples > 0, core/vdb_shadow.h) layers lights..2*lights-1 follow with each light's vdb
// transmittance (shd::vdbShadowLayer), which froxelFogTransmittance and surfaceFogTransmittance
// multiply in.
struct ShadowVolume {
    glm::ivec3 dims{0};
    int reduction = 1;
    std::vector<glm::vec4> transmittance;  // rgb transmittance, a unused
};

// layers: per light, 0 = skip its layer (core/light_reach.h; nobody reads it); null: every one.
// cells: per light, only these cells of its layer are computed (core/media_region.h shadowCellRegion of
// core/light_reach.h listedFroxelRegions: the ones some reader needs), the others hold 1 like a skipped
// layer; null: every cell.
ShadowVolume computeShadowVolume(const CompiledScene& cs, const shd::FrameUniforms& frame, int reduction,
                                 int threads, const std::vector<int>* layers = nullptr,
                                 const std::vector<FroxelRegion>* cells = nullptr);

// The light pass's transmittance toward light `light` for the froxel whose shd::shadowLookup is k
// (sample point p): the volume's trilinear blend where its 8 cells agree, the exact closed form
// where they do not.
glm::vec3 froxelFogTransmittance(const CompiledScene& cs, const ShadowVolume& sv, const shd::FrameUniforms& frame,
                                 int light, const shd::ShadowLookup& k, glm::vec3 p, glm::vec3 toLight,
                                 float distance);

// The same for a surface point p (the shadow ray's origin): the exact closed form everywhere (as the
// GPU's geometry pass, where the volume's blend cost more than it saved: docs/performance.md,
// "perfgeo"), times the vdb layer's blend at p's froxel coordinates.
glm::vec3 surfaceFogTransmittance(const CompiledScene& cs, const ShadowVolume& sv, const shd::FrameUniforms& frame,
                                  int light, glm::vec3 p, glm::vec3 toLight, float distance);

}  // namespace brume
