// The sun shadow map: geometry occlusion (planes, boxes, spheres) toward one directional light with
// shadows = true, for the froxels (light shafts) and the surfaces of both froxel renderers
// (docs/shadows.md, "Sun shadow map").
//
// One orthographic map fitted to the froxel range: its square covers the bounding sphere of the
// froxel frustum (camera to froxel far) seen along the light, so every froxel and every surface in
// the froxel range lies inside it. Each texel holds the depth, along the light, of the SECOND
// surface met by a ray cast from the sun's side through the texel centre (relative to the sphere's
// centre; BRUME_HUGE: none), i.e. where the ray leaves the first solid it enters ("second-depth"
// shadow maps): a lit surface lies in front of that depth by the solid's thickness, so it never
// shadows itself (no acne, whatever the sun's elevation), while everything behind the solid is in
// its shadow. Planes have no back: they shadow nothing (only the space under the ground, which no
// camera ray reaches; a sun below the horizon still lights fog above the ground, see docs).
// Sampled with bilinear PCF: the 2x2 texels around a point, each compared with the point's depth,
// blended with bilinear weights.
// The map holds a second layer of N x N depths for the froxels (sunShadowFroxelIndex): where the
// texel ray enters a solid, the depth of that FIRST surface (else as the first layer). Fog inside a
// solid is never seen, but a froxel straddling a solid's face blends its sample into the pixels that
// look at that face: lit by the second-depth layer, the fog inside the roof of a light-shaft scene
// brightened the pixels looking up at the roof's underside (docs/shadows.md, "Shaft error").
// Surfaces keep the second-depth layer (no acne); planes stay second-depth in both (no back: fog
// under a sunlit ground stays lit, so the froxels straddling the ground do not darken it).
#ifndef BRUME_SHARED_SUN_SHADOW_H
#define BRUME_SHARED_SUN_SHADOW_H

#include "types.h"

BRUME_NAMESPACE_BEGIN

// Where the texel rays start, before the sphere's centre along the light [m]: occluders outside the
// froxel range (a roof above the view) still shadow it.
BRUME_CONST float SUN_SHADOW_RAY_START = 1000.0f;
// Depth bias in texels of world size: a point just behind a solid's back face (a froxel touching
// it) stays lit across the PCF's neighbouring texels. Second depths need no bias against acne.
BRUME_CONST float SUN_SHADOW_BIAS_TEXELS = 1.0f;

// The map's frame, 64 bytes, std430 = C++ layout (the GPU buffer's header).
struct SunShadowFit {
    vec4 centerRadius;  // xyz: centre of the froxel range's bounding sphere; w: its radius R [m]
    vec4 right;         // xyz: unit light-space x; w: map resolution N (texels per side)
    vec4 up;            // xyz: unit light-space y
    vec4 dir;           // xyz: unit direction the light travels (depth axis)
};

// The fit's size in vec4s: the GPU reads the map's buffer (the fit, then the depths) through an
// rgba32f texel view (shared/frame_table.h sunShadowTexels), the depths starting at this texel.
BRUME_CONST int SUN_SHADOW_FIT_TEXELS = 4;

// The fit for light l (directional) and frame f.
BRUME_FUNC SunShadowFit fitSunShadow(FrameUniforms f, LightData l, int resolution) {
    float farD = f.froxelRange.y;
    vec3 forward = normalize(vec3(f.worldFromView * vec4(0.0f, 0.0f, -1.0f, 0.0f)));
    float halfFar = 0.5f * farD;
    float radius = sqrt(halfFar * halfFar + farD * farD * (f.projection.x * f.projection.x + f.projection.y * f.projection.y));
    vec3 d = normalize(vec3(l.direction));
    vec3 helper = abs(d.y) < 0.99f ? vec3(0.0f, 1.0f, 0.0f) : vec3(1.0f, 0.0f, 0.0f);
    vec3 right = normalize(cross(helper, d));
    SunShadowFit s;
    s.centerRadius = vec4(vec3(f.cameraPosition) + forward * halfFar, radius);
    s.right = vec4(right, float(resolution));
    s.up = vec4(cross(d, right), 0.0f);
    s.dir = vec4(d, 0.0f);
    return s;
}

// Start of the ray through texel (i, j)'s centre; it travels along s.dir.
BRUME_FUNC vec3 sunShadowTexelRayOrigin(SunShadowFit s, int i, int j) {
    float n = s.right.w;
    float r = s.centerRadius.w;
    vec2 uv = (vec2(float(i), float(j)) + vec2(0.5f)) / n * 2.0f - vec2(1.0f);
    return vec3(s.centerRadius) + (vec3(s.right) * uv.x + vec3(s.up) * uv.y) * r - vec3(s.dir) * SUN_SHADOW_RAY_START;
}

struct SunShadowLookup {
    ivec2 texel;    // lower corner of the 2x2 PCF footprint (may lie outside the map: clamped by the caller)
    vec2 weights;   // bilinear weights toward texel + 1
    float depth;    // the point's depth, biased toward the light
    bool inside;    // false: outside the map (beyond the froxel range): unshadowed
};

BRUME_FUNC SunShadowLookup sunShadowLookup(SunShadowFit s, vec3 p) {
    float n = s.right.w;
    float r = s.centerRadius.w;
    vec3 q = p - vec3(s.centerRadius);
    vec2 uv = vec2(dot(q, vec3(s.right)), dot(q, vec3(s.up))) / r;
    vec2 t = (uv * 0.5f + vec2(0.5f)) * n - vec2(0.5f);  // texel-centre coordinates
    vec2 base = floor(t);
    SunShadowLookup k;
    k.texel = ivec2(base);
    k.weights = t - base;
    k.depth = dot(q, vec3(s.dir)) - SUN_SHADOW_BIAS_TEXELS * 2.0f * r / n;
    k.inside = all(lessThanEqual(abs(uv), vec2(1.0f)));
    return k;
}

// Clamped texel index into the depth array (row-major, j rows of N).
BRUME_FUNC int sunShadowIndex(SunShadowFit s, ivec2 texel) {
    int n = int(s.right.w);
    ivec2 c = clamp(texel, ivec2(0), ivec2(n - 1));
    return c.y * n + c.x;
}

// Index into the froxels' layer (first surface of a solid; see the top of this file).
BRUME_FUNC int sunShadowFroxelIndex(SunShadowFit s, ivec2 texel) {
    int n = int(s.right.w);
    return n * n + sunShadowIndex(s, texel);
}

// Bilinear PCF: the fraction of the 2x2 footprint that sees the light (1 lit, 0 shadowed).
BRUME_FUNC float sunShadowPcf(SunShadowLookup k, float d00, float d10, float d01, float d11) {
    float v00 = k.depth <= d00 ? 1.0f : 0.0f;
    float v10 = k.depth <= d10 ? 1.0f : 0.0f;
    float v01 = k.depth <= d01 ? 1.0f : 0.0f;
    float v11 = k.depth <= d11 ? 1.0f : 0.0f;
    return mix(mix(v00, v10, k.weights.x), mix(v01, v11, k.weights.x), k.weights.y);
}

// Which light the map serves (FrameUniforms.sunShadowLight = light index + 1, 0 = none).
BRUME_FUNC bool sunShadowMapped(FrameUniforms f, int light) { return f.sunShadowLight == light + 1; }

BRUME_NAMESPACE_END

#endif
