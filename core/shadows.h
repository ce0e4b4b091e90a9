// Volumetric shadows on the CPU froxel renderer: the loop over volumes around the shared closed
// forms of shaders/shared/shadows.h (the GPU's light and geometry shaders run the same loop).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "compile.h"
#include "quality.h"
#include "render.h"
#include "shaders/shared/surface_corners.h"

namespace brume {

class GeometrySet;

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
ShadowVolume computeShadowVolume(const CompiledScene& cs, const shd::FrameUniforms& frame, int reduction,
                                 int threads, const std::vector<int>* layers = nullptr);

// The light pass's transmittance toward light `light` for the froxel whose shd::shadowLookup is k
// (sample point p): the volume's trilinear blend where its 8 cells agree, the exact closed form
// where they do not.
glm::vec3 froxelFogTransmittance(const CompiledScene& cs, const ShadowVolume& sv, const shd::FrameUniforms& frame,
                                 int light, const shd::ShadowLookup& k, glm::vec3 p, glm::vec3 toLight,
                                 float distance);

// The surfaces' tile corners (shaders/shared/surface_corners.h): per corner, its view depth (0 =
// sky) and each light's analytic fog transmittance at the corner pixel's surface point (w: 1 where
// the tile the corner opens may blend that light: surfaceTileClear), in
// shd::surfaceCornerIndex order (froxel_renderer.cpp fills it by ray casting the corner pixels; the
// GPU's surface corners pass reads them from its G-buffer).
struct SurfaceCorners {
    glm::ivec2 size{0};  // image [px]
    glm::ivec2 dims{0};  // shd::surfaceCornerDims(size)
    int lights = 0;
    std::vector<glm::vec4> values;
};

// Whether no box-kind volume can shade any shadow ray of tile t toward light `light`
// (shd::surfaceTileMayMeetVolume for every volume); true for a light without fog shadows.
bool surfaceTileClear(const CompiledScene& cs, const shd::SurfaceTile& t, int light, int localLightsToo);

// One pixel's view of the corners: where it blends them, and whether it lies on their surface
// (shd::surfaceCornersCover; the same for every light).
struct SurfaceCornerPixel {
    const SurfaceCorners* corners = nullptr;
    shd::SurfaceCornerLookup k{};
    bool covered = false;
};
SurfaceCornerPixel surfaceCornerPixel(const SurfaceCorners& corners, glm::ivec2 pixel, float viewDepth);

// The corners of an image of `size` pixels: each corner pixel's centre ray cast against the geometry
// (the sky: view depth 0), every light's exact fog transmittance at the hit's shadow-ray origin.
SurfaceCorners computeSurfaceCorners(const CompiledScene& cs, const GeometrySet& geometry, const shd::FrameUniforms& frame,
                                     glm::ivec2 size, int threads);

// The fog's transmittance toward light `light` at a surface point p (the shadow ray's origin) of the
// pixel `px`: the blend of its tile's corners where trusted (shd::surfaceCornersAgree), the exact
// closed form elsewhere, as the GPU's surface passes (surface_body.glsl); times the vdb layer's
// blend at p's froxel coordinates.
glm::vec3 surfaceFogTransmittance(const CompiledScene& cs, const ShadowVolume& sv, const shd::FrameUniforms& frame,
                                  int light, glm::vec3 p, glm::vec3 toLight, float distance,
                                  const SurfaceCornerPixel& px);

}  // namespace brume
