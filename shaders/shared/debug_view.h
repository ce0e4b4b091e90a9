// Debug views: one depth slice of a froxel volume mapped to the image, written once for the CPU
// froxel renderer (core/debug_view.cpp) and the GPU (shaders/debug_view.comp).
//
// Pixel (x, y) shows froxel (x / tile, y / tile, slice) unfiltered, so froxel edges stay visible.
// The result is a display colour in [0, 1] (no exposure, no tone curve: it is the same whatever the
// scene's brightness), from a fixed range per view so that images can be compared:
//   density        mean rgb sigma_t [1/m], log ramp DEBUG_DENSITY_MIN..MAX, black = 0
//   scattering     mean rgb source S = in-scattered + emitted [radiance/m], log ramp
//                 DEBUG_SCATTERING_MIN..MAX
//   transmittance  mean rgb transmittance camera -> the slice's far side, linear grey, white = 1
// Non-finite or negative values show magenta: they are renderer bugs and must stand out.
#ifndef BRUME_SHARED_DEBUG_VIEW_H
#define BRUME_SHARED_DEBUG_VIEW_H

#include "common.h"

BRUME_NAMESPACE_BEGIN

BRUME_CONST int DEBUG_VIEW_FINAL = 0;  // the composited image
BRUME_CONST int DEBUG_VIEW_DENSITY = 1;
BRUME_CONST int DEBUG_VIEW_SCATTERING = 2;
BRUME_CONST int DEBUG_VIEW_TRANSMITTANCE = 3;

// Log ramps: the first value above black and the value that reaches white.
BRUME_CONST float DEBUG_DENSITY_MIN = 1.0e-3f;     // [1/m]
BRUME_CONST float DEBUG_DENSITY_MAX = 1.0e2f;      // [1/m]
BRUME_CONST float DEBUG_SCATTERING_MIN = 1.0e-4f;  // [radiance/m]
BRUME_CONST float DEBUG_SCATTERING_MAX = 1.0e2f;   // [radiance/m]

// Push constants of the GPU debug pass; 16 bytes.
struct DebugViewParams {
    ivec4 view;  // x: DEBUG_VIEW_*, y: slice index (clamped to the grid), zw: unused
};

BRUME_FUNC vec2 debugViewRange(int view) {
    if (view == DEBUG_VIEW_DENSITY) return vec2(DEBUG_DENSITY_MIN, DEBUG_DENSITY_MAX);
    if (view == DEBUG_VIEW_SCATTERING) return vec2(DEBUG_SCATTERING_MIN, DEBUG_SCATTERING_MAX);
    return vec2(0.0f, 1.0f);
}

BRUME_FUNC int debugSliceClamped(int slice, int sliceCount) { return clamp(slice, 0, sliceCount - 1); }

// Froxel column (x, y) that pixel px shows.
BRUME_FUNC ivec2 debugFroxelColumn(ivec2 px, ivec4 froxelDims) {
    return clamp(px / froxelDims.w, ivec2(0), ivec2(froxelDims.x - 1, froxelDims.y - 1));
}

// Position of v on the view's ramp in [0, 1]; any v > 0 sits at least at 0.02 so that thin media
// stay distinguishable from none.
BRUME_FUNC float debugRampPosition(float v, int view) {
    vec2 range = debugViewRange(view);
    if (view == DEBUG_VIEW_TRANSMITTANCE) return clamp(v, 0.0f, 1.0f);
    if (!(v > 0.0f)) return 0.0f;
    float t = (log(v) - log(range.x)) / (log(range.y) - log(range.x));
    return clamp(t, 0.02f, 1.0f);
}

// texel: the rgba of the view's volume at the froxel (rgb used).
BRUME_FUNC vec3 debugViewColor(vec4 texel, int view) {
    float v = (texel.x + texel.y + texel.z) / 3.0f;
    if (!(v >= 0.0f && v < BRUME_HUGE)) return vec3(1.0f, 0.0f, 1.0f);
    float t = debugRampPosition(v, view);
    if (view == DEBUG_VIEW_TRANSMITTANCE) return vec3(t);
    // Black -> blue -> cyan -> white: brightness grows monotonically with the value.
    return clamp(vec3(3.0f * t - 2.0f, 3.0f * t - 1.0f, 3.0f * t), vec3(0.0f), vec3(1.0f));
}

BRUME_NAMESPACE_END

#endif
