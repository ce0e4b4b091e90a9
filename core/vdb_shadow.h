// VDB volumes in the froxel renderers' fog shadows: the CPU side of shaders/shared/vdb_shadow.h (the
// GPU's is shaders/vdb_shadow.glsl). The transmittance volume (core/shadows.h) holds one extra layer
// per light with the vdb volumes' transmittance; this file fills it and says how finely to march.
#pragma once

#include <glm/glm.hpp>

#include "compile.h"
#include "quality.h"
#include "render.h"

namespace brume {

// Samples per shortest voxel edge along a shadow ray (FrameUniforms.vdbShadowSamples): 1 in low, medium and
// high, 2 in ultra. Measured trade in docs/shadows.md, "VDB volumes".
int vdbShadowSamplesPerVoxel(Quality q);

// Sets frame.vdbShadowSamples: the quality's samples per voxel when the scene has a vdb volume with a grid
// and request.vdbShadows is on, else 0 (no vdb layer in the transmittance volume). Call after
// applyShadowSettings, in both froxel renderers.
void applyVdbShadowSettings(shd::FrameUniforms& frame, const CompiledScene& cs, const RenderRequest& request);

// With request.vdbCulling off, clears every vdb volume's occupancy offset (VolumeData.kind.w), so
// that both froxel renderers walk the tree wherever they sample (to measure the culling; the image is
// the same either way). Call right after compileScene.
void applyVdbCullingSettings(CompiledScene& cs, const RenderRequest& request);

// Optical depth of the vdb volumes alone from p along unit toLight over `distance`, marched at
// frame.vdbShadowSamples samples per voxel (what the transmittance volume's vdb layer holds); 0 when that is
// 0 or shd::fogShadowsLight skips the light.
glm::vec3 vdbFogOpticalDepth(const CompiledScene& cs, const shd::FrameUniforms& frame, const shd::LightData& l,
                             glm::vec3 p, glm::vec3 toLight, float distance);

}  // namespace brume
