// Volumetric shadows on the CPU froxel renderer: the loop over volumes around the shared closed
// forms of shaders/shared/shadows.h (the GPU's light and geometry shaders run the same loop).
#pragma once

#include <glm/glm.hpp>

#include "compile.h"
#include "quality.h"

namespace brume {

// Whether the froxel renderers evaluate fog transmittance toward point and spot lights at this
// quality (FrameUniforms.shadows.x); the sun's is always evaluated. Off in low: it costs one
// closed form per volume per local light per froxel.
bool localLightFogShadows(Quality q);

// exp(-optical depth) from p along unit toLight over `distance` (BRUME_HUGE for a directional
// light) through every analytic volume except depth fog; 1 for a light shd::fogShadowsLight skips.
glm::vec3 lightFogTransmittance(const CompiledScene& cs, const shd::LightData& l, glm::vec3 p, glm::vec3 toLight,
                                float distance, int localLightsToo);

}  // namespace brume
