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
//   - no bounded volume can shade any part of the tile toward l (surfaceTileMayMeetVolume below: the
//     tile's surface patch swept toward the light misses every box-kind volume's bounds). Corners
//     cannot see a shadow narrower than a tile (a dense block's shadow band between two sunlit
//     corner rows: docs/performance.md, "geotile"), so this is a proof, not a heuristic: where it
//     holds, every bounded volume adds exactly 0 to the optical depth of every covered pixel of the
//     tile and of its corners;
//   - the 4 corners' transmittances toward l differ by at most SURFACE_CORNER_SPREAD in every
//     channel. What is left after the rule above is the height fog (depth fog and vdb volumes are
//     not in the closed form: shadows.h), a function of height alone toward a directional light,
//     monotone in it: over a planar tile its extremes are at the corners, so the blend (a convex
//     combination of the corners) is within the spread of the exact value. Toward a point light it
//     is smooth along the surface; measured error: docs/performance.md, "geo".
#ifndef BRUME_SHARED_SURFACE_CORNERS_H
#define BRUME_SHARED_SURFACE_CORNERS_H

#include "types.h"

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

// ---- The conservative rule: no bounded volume between the tile and the light ----
//
// Every covered pixel of a tile lies within `margin` of the convex hull of its 4 corner points: its
// point is cam + (P - cam) z / z', P = a convex combination of the corners (1 / view depth blended
// bilinearly: the weights w_k / z_k, normalized) and z / z' within 1 +- SURFACE_DEPTH_TOLERANCE
// (surfaceCornersCover); the shadow ray's origin is off it by surfaceRayOffset. Its shadow ray ends
// at the light (point, spot) or goes on toward it (directional). So every shadow ray of the tile lies
// within `margin` of the sweep: the convex hull of the corners and the light's position, or of the
// corners and the corners moved `reach` toward a directional light, where `reach` is long enough to
// have passed the box. A volume whose bounds (grown by the margin) are separated from that hull by
// some axis adds nothing to any of these rays. Any set of axes is conservative (a convex hull's
// projection on an axis is the range of its points' projections); the ones tested: the world axes
// (the box's faces), the sweep direction and its cross products with the world axes (the sides of
// the shadow prism), and the patch normal.
struct SurfaceTile {
    vec3 p0;  // the 4 corner points (world)
    vec3 p1;
    vec3 p2;
    vec3 p3;
    float margin;  // [m], see above
    float scale;   // [m], the largest |coordinate| or distance involved: float rounding slack
};

// Relative float rounding slack on the projections (|x| 1e-5: ~170 ulps).
BRUME_CONST float SURFACE_SWEEP_SLACK = 1.0e-5f;

BRUME_FUNC float surfaceMaxAbs(vec3 p) { return max(abs(p.x), max(abs(p.y), abs(p.z))); }

// The tile through corner points p0..p3 seen from the camera at cam.
BRUME_FUNC SurfaceTile surfaceTileOf(vec3 p0, vec3 p1, vec3 p2, vec3 p3, vec3 cam) {
    SurfaceTile t;
    t.p0 = p0;
    t.p1 = p1;
    t.p2 = p2;
    t.p3 = p3;
    float camDist = max(max(length(p0 - cam), length(p1 - cam)), max(length(p2 - cam), length(p3 - cam)));
    float maxAbs = max(max(surfaceMaxAbs(p0), surfaceMaxAbs(p1)), max(surfaceMaxAbs(p2), surfaceMaxAbs(p3)));
    // Twice the depth tolerance's displacement and twice surfaceRayOffset (1e-4 + 2e-6 max|p|).
    t.margin = 2.0f * SURFACE_DEPTH_TOLERANCE * camDist + 2.0e-4f + 4.0e-6f * (maxAbs + camDist);
    t.scale = maxAbs + camDist;
    return t;
}

// Whether the axis a separates the hull of the tile's corners and far ends e0..e3 from the box
// (centre c, half size h) grown by m.
BRUME_FUNC bool surfaceSweepSeparated(SurfaceTile t, vec3 e0, vec3 e1, vec3 e2, vec3 e3, vec3 c, vec3 h, float m,
                                      vec3 a) {
    float d0 = dot(t.p0, a), d1 = dot(t.p1, a), d2 = dot(t.p2, a), d3 = dot(t.p3, a);
    float f0 = dot(e0, a), f1 = dot(e1, a), f2 = dot(e2, a), f3 = dot(e3, a);
    float lo = min(min(min(d0, d1), min(d2, d3)), min(min(f0, f1), min(f2, f3)));
    float hi = max(max(max(d0, d1), max(d2, d3)), max(max(f0, f1), max(f2, f3)));
    float centre = dot(c, a);
    float radius = dot(h, abs(a)) + m * length(a);
    return lo > centre + radius || hi < centre - radius;
}

// Whether some shadow ray of the tile toward light l may meet the box [lo, hi] (the header comment):
// false only where an axis separates them.
BRUME_FUNC bool surfaceTileMayMeetBox(SurfaceTile t, LightData l, vec3 lo, vec3 hi) {
    vec3 c = 0.5f * (lo + hi);
    vec3 h = 0.5f * (hi - lo);
    bool directional = l.kind.x == LIGHT_DIRECTIONAL;
    vec3 u = -vec3(l.direction);
    vec3 light = vec3(l.positionRange);
    // Past `reach` a ray from within the margin of the patch is outside the box's bounding ball.
    float reach = max(max(length(t.p0 - c), length(t.p1 - c)), max(length(t.p2 - c), length(t.p3 - c))) + length(h) +
                  2.0f * t.margin;
    vec3 e0 = directional ? t.p0 + u * reach : light;
    vec3 e1 = directional ? t.p1 + u * reach : light;
    vec3 e2 = directional ? t.p2 + u * reach : light;
    vec3 e3 = directional ? t.p3 + u * reach : light;
    vec3 w = directional ? u : light - 0.25f * (t.p0 + t.p1 + t.p2 + t.p3);
    float scale = t.scale + surfaceMaxAbs(c) + length(h) + reach + (directional ? 0.0f : surfaceMaxAbs(light));
    float m = t.margin + SURFACE_SWEEP_SLACK * scale;
    bool separated = surfaceSweepSeparated(t, e0, e1, e2, e3, c, h, m, vec3(1.0f, 0.0f, 0.0f)) ||
                     surfaceSweepSeparated(t, e0, e1, e2, e3, c, h, m, vec3(0.0f, 1.0f, 0.0f)) ||
                     surfaceSweepSeparated(t, e0, e1, e2, e3, c, h, m, vec3(0.0f, 0.0f, 1.0f)) ||
                     surfaceSweepSeparated(t, e0, e1, e2, e3, c, h, m, w) ||
                     surfaceSweepSeparated(t, e0, e1, e2, e3, c, h, m, cross(w, vec3(1.0f, 0.0f, 0.0f))) ||
                     surfaceSweepSeparated(t, e0, e1, e2, e3, c, h, m, cross(w, vec3(0.0f, 1.0f, 0.0f))) ||
                     surfaceSweepSeparated(t, e0, e1, e2, e3, c, h, m, cross(w, vec3(0.0f, 0.0f, 1.0f))) ||
                     surfaceSweepSeparated(t, e0, e1, e2, e3, c, h, m, cross(t.p3 - t.p0, t.p2 - t.p1));
    return !separated;
}

// Whether volume v may add to the fog's optical depth toward l along some shadow ray of the tile:
// the box kind (boxes, ellipsoids, cylinders: their world bounds hold every point of non-zero
// density, fade included) with some extinction whose bounds the sweep may meet. The other kinds the
// closed form counts (height fogs) are left to the corners' spread (header comment).
BRUME_FUNC bool surfaceTileMayMeetVolume(SurfaceTile t, LightData l, VolumeData v) {
    if (v.kind.x != VOLUME_BOX) return false;
    vec3 sigmaT = vec3(v.sigmaS_g) + vec3(v.sigmaA);
    if (!(max(sigmaT.x, max(sigmaT.y, sigmaT.z)) > 0.0f)) return false;
    return surfaceTileMayMeetBox(t, l, vec3(v.worldMin), vec3(v.worldMax));
}

BRUME_NAMESPACE_END

#endif
