// The glow of point and spot lights standing in fog, split between the froxel grid and the pixels.
//
// Seen from the camera, a light inside the fog glows with its in-scattering integrated along each
// pixel's ray: about pi / b for a ray passing at b from the light. The froxel grid samples the
// inverse square once per froxel and the composite interpolates between column centres a tile
// apart, so near the light the grid can neither hold 1/r^2 nor the ~1/b peak on screen
// (docs/quality.md, "Point lights in fog": 2.9% off the reference at high, the error across tiles).
//
// So the inverse square is split at a glow radius R (a few froxels, lightGlowRadius) with the
// window h(u) = (1 - u^2)^2, u = r / R (h = 0 beyond R):
//     1/r^2 = (1 - h) / r^2        the froxel part: (2 - u^2) / R^2 inside R, smooth and finite
//           +      h  / r^2        the pixel part: non-zero only inside the ball of radius R
// The light pass evaluates the first (evalLightFroxel); the composite adds the second per pixel
// along the pixel's own ray (lightGlowPerSigmaS), with the medium of the froxel at the ray's
// closest point to the light taken as uniform over the ball. With t = b tan(phi) along the ray
// (b the closest distance), dt / r^2 = dphi / b, so the pixel part is a smooth integral over phi,
// done with 6-point Gauss-Legendre: exact as b -> 0, where the grid was worst.
//
// The pixel part leaves out what is small over a ball of a few froxels: the fog's shadow toward the
// light is exp(-sigma_t r) in the ball's uniform medium, and the point/spot shadow maps are not read.
#ifndef BRUME_SHARED_GLOW_H
#define BRUME_SHARED_GLOW_H

#include "froxel.h"
#include "lighting.h"

BRUME_NAMESPACE_BEGIN

// Glow radius R in froxel radii at the light's depth. Larger: a smoother froxel part, more pixels
// doing the per-pixel part, the uniform-medium assumption over a larger ball. Measured against the
// reference at 320x180 (docs/quality.md): 2 and 3 gain alike at high (lanterns 0.59% / 0.47%), but
// at low 3 spreads the ball over the default scene's box edge (1.70% -> 3.63%).
BRUME_CONST float LIGHT_GLOW_FROXELS = 2.0f;

// R for light l in frame f [m]; 0 when the light has no glow (directional, fog_scale 0, not between
// the froxel near and far), and then the froxel part keeps the whole inverse square.
// The froxel radius of froxel.h froxelRadius, at the light's own view depth rather than per slice.
BRUME_FUNC float lightGlowRadius(LightData l, FrameUniforms f) {
    if (l.kind.x == LIGHT_DIRECTIONAL || !(l.fogScale > 0.0f)) return 0.0f;
    float z = -(f.viewFromWorld * vec4(vec3(l.positionRange), 1.0f)).z;
    float zNear = f.froxelRange.x;
    float zFar = f.froxelRange.y;
    if (!(z > zNear) || !(z < zFar)) return 0.0f;
    float k = f.froxelRange.z;
    float slices = float(f.froxelDims.z);
    // u > 0 here, but kept off 0 so that pow never sees 0^0 (GLSL leaves it undefined).
    float u = max((z - zNear) / (zFar - zNear), 1e-30f);
    // Slice thickness dz/ds at z: (far - near) k t^(k-1) / slices with t = u^(1/k), written as
    // u^(1 - 1/k): no division by t, which underflows to 0 near the froxel near plane (u^10 at
    // k = 0.1). For k < 1 the derivative grows without bound toward the near plane: no slice is
    // thicker than the whole grid, so it is held there (finite R, never inf or NaN).
    float thickness = (zFar - zNear) * k * min(pow(u, 1.0f - 1.0f / k), slices / k) / slices;
    float tile = float(f.froxelDims.w);
    float w = 2.0f * f.projection.x * z * tile / float(f.counts.x);
    float h = 2.0f * f.projection.y * z * tile / float(f.counts.y);
    return LIGHT_GLOW_FROXELS * 0.5f * sqrt(w * w + h * h + thickness * thickness);
}

// The light pass's sample of light l at p: the froxel part (1 - h) / r^2 of a light with a glow,
// else the inverse square evaluated no closer than `nearest` (lighting.h FROXEL_LIGHT_CLAMP).
BRUME_FUNC LightSample evalLightFroxel(LightData l, vec3 p, float nearest, FrameUniforms f) {
    float glow = lightGlowRadius(l, f);
    // One evalLightNear with the clamp chosen (lavapipe runs both sides of a branch: two calls cost two).
    LightSample s = evalLightNear(l, p, glow > 0.0f ? LIGHT_MIN_DISTANCE : nearest);
    float u2 = (s.distance * s.distance) / (glow * glow);
    if (glow > 0.0f && u2 < 1.0f) s.irradiance *= u2 * (2.0f - u2);  // 1 - h
    return s;
}

// Where a camera ray meets a light's glow ball.
struct LightGlowRay {
    float radius;   // R [m]; 0 = the ray does not meet the ball (nothing to add)
    float closest;  // ray distance of the closest point to the light [m]
    float b;        // distance of the closest point from the light [m]
    float enter;    // ray distance where the ray enters the ball (or starts, inside it) [m]
    vec2 phi;       // the ray's part inside the ball and in front of its end, as angles atan(t / b)
};

// The ray from `origin` along the unit `dir`, ending at ray distance `rayEnd` (a surface or the far).
BRUME_FUNC LightGlowRay lightGlowRay(LightData l, FrameUniforms f, vec3 origin, vec3 dir, float rayEnd) {
    LightGlowRay g;
    g.radius = 0.0f;
    g.closest = 0.0f;
    g.b = 1.0f;
    g.enter = 0.0f;
    g.phi = vec2(0.0f);
    float radius = lightGlowRadius(l, f);
    if (radius <= 0.0f) return g;
    vec3 toLight = vec3(l.positionRange) - origin;
    float tc = dot(toLight, dir);
    float b = max(length(toLight - dir * tc), LIGHT_MIN_DISTANCE);
    if (b >= radius) return g;
    float c = sqrt(radius * radius - b * b);
    float t0 = max(-c, -tc);
    float t1 = min(c, rayEnd - tc);
    if (!(t1 > t0)) return g;
    g.radius = radius;
    g.closest = tc;
    g.b = b;
    g.enter = tc + t0;
    g.phi = vec2(atan(t0 / b), atan(t1 / b));
    return g;
}

// The froxel whose medium stands for the ball's: the one holding the ray's closest point to the
// light, clamped into the grid.
BRUME_FUNC ivec3 lightGlowFroxel(LightGlowRay r, vec3 origin, vec3 dir, FrameUniforms f) {
    vec4 c = froxelCoordFromWorld(origin + dir * r.closest, f);
    ivec3 i = ivec3(floor(vec3(c)));
    return clamp(i, ivec3(0), ivec3(f.froxelDims) - ivec3(1));
}

// One node of lightGlowPerSigmaS's quadrature: x in [-1, 1] on [phi0, phi1], weight its weight.
BRUME_FUNC vec3 lightGlowNode(LightData l, LightGlowRay r, vec3 origin, vec3 dir, vec3 sigmaT, float g, float mid,
                              float halfWidth, float x, float weight) {
    float t = r.b * tan(mid + halfWidth * x);
    LightSample s = evalLightNear(l, origin + dir * (r.closest + t), LIGHT_MIN_DISTANCE);
    float rr = max(s.distance, LIGHT_MIN_DISTANCE);
    float u2 = (s.distance * s.distance) / (r.radius * r.radius);
    float h = max(1.0f - u2, 0.0f);
    // dt / r^2 = dphi / b: the irradiance's 1/r^2 times r^2 / b.
    float w = weight * halfWidth * h * h * rr * rr / r.b;
    float depth = max(r.closest + t - r.enter, 0.0f);  // inside the ball, before this point
    return inScatterPerSigmaS(l, s, dir, g) * w * exp(-sigmaT * (depth + s.distance));
}

// The pixel part along ray r, per unit sigma_s, as seen from where the ray enters the ball (multiply
// by sigma_s and the transmittance from the camera to r.enter). sigmaT and g: the ball's medium.
// Every exponent is <= 0, so an opaque medium gives 0, never an overflow.
// 6-point Gauss-Legendre on [phi0, phi1], in symmetric pairs, written out node by node: as a loop
// over arrays of nodes and weights, lavapipe kept the loop and the arrays (indexed by the trip), and
// the glow pass cost about 1.28x (docs/performance.md, "pixel, round seven"). The same sum in the same order.
BRUME_FUNC vec3 lightGlowPerSigmaS(LightData l, LightGlowRay r, vec3 origin, vec3 dir, vec3 sigmaT, float g) {
    vec3 sum = vec3(0.0f);
    if (r.radius <= 0.0f) return sum;
    float mid = 0.5f * (r.phi.x + r.phi.y);
    float halfWidth = 0.5f * (r.phi.y - r.phi.x);
    sum += lightGlowNode(l, r, origin, dir, sigmaT, g, mid, halfWidth, 0.2386191861f, 0.4679139346f);
    sum += lightGlowNode(l, r, origin, dir, sigmaT, g, mid, halfWidth, -0.2386191861f, 0.4679139346f);
    sum += lightGlowNode(l, r, origin, dir, sigmaT, g, mid, halfWidth, 0.6612093865f, 0.3607615730f);
    sum += lightGlowNode(l, r, origin, dir, sigmaT, g, mid, halfWidth, -0.6612093865f, 0.3607615730f);
    sum += lightGlowNode(l, r, origin, dir, sigmaT, g, mid, halfWidth, 0.9324695142f, 0.1713244924f);
    sum += lightGlowNode(l, r, origin, dir, sigmaT, g, mid, halfWidth, -0.9324695142f, 0.1713244924f);
    return sum;
}

// The glow pass (glow.comp; core: compositeRow) adds each glowing light's pixel part over the pixels
// whose rays can meet its ball only: one dispatch per light over lightGlowScreenRect, its parameters
// as push constants. Lavapipe pays for the quadrature on every pixel it runs on, taken or not
// (docs/performance.md), so in the composite it cost every pixel of the screen.
struct GlowParams {
    ivec4 rect;   // first and last pixel (x0, y0, x1, y1) of the dispatch, inclusive
    ivec4 light;  // x: the light's index; y, z: the integrated entries its pixels can read (inclusive); w unused
};

// Pixels (x0, y0, x1, y1), inclusive, clamped to the image, outside which no pixel centre's ray meets
// light l's glow ball (lightGlowRay's radius is 0 there); x1 < x0 when none can. Conservative: the
// ball's exact extent in x / depth and y / depth (its tangent planes through the camera), one pixel
// of margin; the whole image when the ball reaches behind the camera near.
BRUME_FUNC ivec4 lightGlowScreenRect(LightData l, FrameUniforms f) {
    ivec4 none = ivec4(0, 0, -1, -1);
    ivec4 all = ivec4(0, 0, f.counts.x - 1, f.counts.y - 1);
    float radius = lightGlowRadius(l, f);
    if (radius <= 0.0f) return none;
    vec3 c = vec3(f.viewFromWorld * vec4(vec3(l.positionRange), 1.0f));
    float d = -c.z;
    if (!(d - radius > 0.5f * f.projection.z)) return all;
    // The slopes s = x / depth of the two planes through the camera tangent to the ball, from
    // (x - s depth)^2 = R^2 (1 + s^2) at the ball's centre: s = (x d +- R sqrt(x^2 + d^2 - R^2)) /
    // (d^2 - R^2), d > R here; the same for y. Tighter than the ball's bounding box projected
    // through its corners (its near face's corners stand out by d / (d - R) and more off-centre):
    // at `low` the radius is about a seventh of the depth.
    // As (d - R)(d + R): d * d - R * R cancels to a few digits when R is close to d at large depths
    // (a camera far of 10^7 m puts R = d near 10^5 m, where the squares are 2^11 apart).
    float d2R2 = (d - radius) * (d + radius);
    float rootX = radius * sqrt(c.x * c.x + d2R2);
    float rootY = radius * sqrt(c.y * c.y + d2R2);
    float sxLo = (c.x * d - rootX) / d2R2;
    float sxHi = (c.x * d + rootX) / d2R2;
    float syLo = (c.y * d - rootY) / d2R2;
    float syHi = (c.y * d + rootY) / d2R2;
    // Pixel coordinate of view-space slope s (froxel.h viewRayFromPixel inverted).
    float w = float(f.counts.x);
    float h = float(f.counts.y);
    float px0 = (sxLo / f.projection.x + 1.0f) * 0.5f * w;
    float px1 = (sxHi / f.projection.x + 1.0f) * 0.5f * w;
    float py0 = (1.0f - syHi / f.projection.y) * 0.5f * h;
    float py1 = (1.0f - syLo / f.projection.y) * 0.5f * h;
    // Pixel i's centre is at i + 0.5.
    vec4 r = vec4(floor(px0 - 0.5f) - 1.0f, floor(py0 - 0.5f) - 1.0f, ceil(px1 - 0.5f) + 1.0f, ceil(py1 - 0.5f) + 1.0f);
    r = clamp(r, vec4(-1.0f), vec4(w, h, w, h));
    ivec4 i = ivec4(max(int(r.x), 0), max(int(r.y), 0), min(int(r.z), f.counts.x - 1), min(int(r.w), f.counts.y - 1));
    return i.z < i.x || i.w < i.y ? none : i;
}

BRUME_NAMESPACE_END

#endif
