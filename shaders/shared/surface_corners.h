// The surfaces' fog transmittance toward each light, evaluated exactly at the corners of 8x8 pixel
// tiles and interpolated per pixel where that is safe (docs/performance.md, "geotile"). The exact
// closed form (shadows.h) per pixel and light was ~60% of the geometry pass on lavapipe, which runs
// it for every pixel whether a branch skips it or not; so the GPU evaluates it in three passes:
//   surface corners (one invocation per corner): the corner pixel's surface point, exact;
//   surface light (every pixel): the corners' bilinear blend where it is trusted (below); a pixel
//     with some untrusted light is listed instead;
//   surface exact (indirect, the listed pixels only): the same sum, the exact form where untrusted.
// The CPU froxel renderer ray casts the same corner pixels and applies the same rule per pixel.
//
// A corner sits on the centre of pixel min(8 c, size - 1), so its value is the exact value of a real
// pixel. A pixel's light l takes the blend of its tile's 4 corners when
//   - every corner holds a surface, and the pixel lies on the surface through them: 1 / view depth
//     (affine in the screen on a plane) blended from the corners matches the pixel's within
//     SURFACE_DEPTH_TOLERANCE (relative). Silhouettes and the sky fail this;
//   - the 4 corners' transmittances toward l differ by at most SURFACE_CORNER_SPREAD in every
//     channel (a fog shadow edge across the tile fails this).
// The blend is a convex combination of the corners, so a trusted value lies within the corners'
// range; measured error: docs/performance.md, "geotile".
#ifndef BRUME_SHARED_SURFACE_CORNERS_H
#define BRUME_SHARED_SURFACE_CORNERS_H

#include "common.h"

BRUME_NAMESPACE_BEGIN

BRUME_CONST int SURFACE_TILE_PX = 8;
BRUME_CONST float SURFACE_CORNER_SPREAD = 0.02f;
BRUME_CONST float SURFACE_DEPTH_TOLERANCE = 1.0e-3f;
// Invocations per workgroup of the surface exact pass (one per listed pixel).
BRUME_CONST int SURFACE_EXACT_GROUP = 64;

// Corners per row and column for an image of `size` pixels.
BRUME_FUNC ivec2 surfaceCornerDims(ivec2 size) {
    return ivec2((size.x - 1) / SURFACE_TILE_PX + 2, (size.y - 1) / SURFACE_TILE_PX + 2);
}

// The pixel whose centre corner c sits on.
BRUME_FUNC ivec2 surfaceCornerPixel(ivec2 c, ivec2 size) {
    return ivec2(min(c.x * SURFACE_TILE_PX, size.x - 1), min(c.y * SURFACE_TILE_PX, size.y - 1));
}

// Corner records: (1 + lights) vec4 each: entry 0 = (view depth [m], 0 for the sky; 0, 0, 0), entry
// 1 + l = (light l's analytic fog transmittance; 0). Only the lights the surfaces see are filled.
BRUME_FUNC int surfaceCornerIndex(ivec2 dims, ivec2 c, int lights, int entry) {
    return (c.y * dims.x + c.x) * (1 + lights) + entry;
}

// Where pixel `pixel` (integer coordinates) reads the corners.
struct SurfaceCornerLookup {
    ivec4 corners;  // x0, y0, x1, y1
    vec2 weights;   // toward x1, y1
};

BRUME_FUNC float surfaceCornerWeight(int p, int p0, int p1) {
    return p1 > p0 ? float(p - p0) / float(p1 - p0) : 0.0f;
}

BRUME_FUNC SurfaceCornerLookup surfaceCornerLookup(ivec2 pixel, ivec2 size) {
    ivec2 c0 = ivec2(pixel.x / SURFACE_TILE_PX, pixel.y / SURFACE_TILE_PX);
    ivec2 c1 = c0 + ivec2(1, 1);
    ivec2 p0 = surfaceCornerPixel(c0, size);
    ivec2 p1 = surfaceCornerPixel(c1, size);
    SurfaceCornerLookup k;
    k.corners = ivec4(c0.x, c0.y, c1.x, c1.y);
    k.weights = vec2(surfaceCornerWeight(pixel.x, p0.x, p1.x), surfaceCornerWeight(pixel.y, p0.y, p1.y));
    return k;
}

// a + (b - a) w: equal corners give their value exactly (a transmittance of 1 stays 1).
BRUME_FUNC float surfaceLerp(float a, float b, float w) { return a + (b - a) * w; }
BRUME_FUNC vec3 surfaceLerp3(vec3 a, vec3 b, float w) { return a + (b - a) * w; }

// Whether the pixel at `viewDepth` lies on the surface through its 4 corners (view depths d00, d10,
// d01, d11; 0 = sky): the rule of the header comment.
BRUME_FUNC bool surfaceCornersCover(float d00, float d10, float d01, float d11, vec2 w, float viewDepth) {
    if (!(min(min(d00, d10), min(d01, d11)) > 0.0f)) return false;
    float inv = surfaceLerp(surfaceLerp(1.0f / d00, 1.0f / d10, w.x), surfaceLerp(1.0f / d01, 1.0f / d11, w.x), w.y);
    return abs(inv * viewDepth - 1.0f) <= SURFACE_DEPTH_TOLERANCE;
}

// Whether 4 corners' transmittances agree (the rule of the header comment).
BRUME_FUNC bool surfaceCornersAgree(vec3 t00, vec3 t10, vec3 t01, vec3 t11) {
    vec3 spread = max(max(t00, t10), max(t01, t11)) - min(min(t00, t10), min(t01, t11));
    return max(spread.x, max(spread.y, spread.z)) <= SURFACE_CORNER_SPREAD;
}

BRUME_FUNC vec3 surfaceCornerBlend(vec3 t00, vec3 t10, vec3 t01, vec3 t11, vec2 w) {
    return surfaceLerp3(surfaceLerp3(t00, t10, w.x), surfaceLerp3(t01, t11, w.x), w.y);
}

BRUME_NAMESPACE_END

#endif
