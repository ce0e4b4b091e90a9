// Point and spot light shadow maps: geometry occlusion (planes, boxes, spheres) toward every point
// or spot light with shadows = true, for the froxels and the surfaces of both froxel renderers
// (docs/shadows.md, "Point and spot shadow maps").
//
// Every mapped light owns one slot of LOCAL_SHADOW_FACES faces of N x N texels in one float array
// (LightData.kind.z = slot + 1, 0 = unmapped; N = FrameUniforms.localShadowTexels, 0 = no maps). A point
// light uses the six faces of a cube map; a spot light whose outer angle is below
// LOCAL_SHADOW_SPOT_MAX_COS's angle uses face 0 only, a perspective map along its direction that
// just covers the cone (wider spots use the cube, as point lights). Each texel holds the distance
// from the light to the SECOND surface met by the ray from the light through the texel centre
// (BRUME_HUGE: none), as the sun's map does (sun_shadow.h): a lit surface lies in front of it by the
// solid's thickness, so it never shadows itself, while everything behind the solid is shadowed.
// Sampled with bilinear PCF over the 2x2 texels around a point, clamped to the point's face.
#ifndef BRUME_SHARED_LOCAL_SHADOW_H
#define BRUME_SHARED_LOCAL_SHADOW_H

#include "types.h"

BRUME_NAMESPACE_BEGIN

BRUME_CONST int LOCAL_SHADOW_FACES = 6;
// Spots with cos(outer angle) above this (outer angle < 60 deg) get one perspective face; wider
// cones would stretch it (tan -> infinity at 90 deg) and use the cube.
BRUME_CONST float LOCAL_SHADOW_SPOT_MAX_COS = 0.5f;
// Depth bias in texels of world size at the point's distance: a froxel touching a solid's back face
// stays lit across the PCF's neighbouring texels. Second distances need no bias against acne.
BRUME_CONST float LOCAL_SHADOW_BIAS_TEXELS = 1.0f;

// One face's frame: rays leave the light along normalize(forward + (right u + up v) tanHalf),
// u, v in [-1, 1].
struct LocalShadowFace {
    vec3 right;
    vec3 up;
    vec3 forward;
    float tanHalf;
};

// Whether light l has a map (a point or spot light with shadows and a slot) at map resolution n.
BRUME_FUNC bool localShadowMapped(LightData l, int n) {
    return n > 0 && l.kind.x != LIGHT_DIRECTIONAL && lightCastsShadows(l) && lightShadowSlot(l) >= 0;
}

// 1: a spot's single perspective face; 6: a cube.
BRUME_FUNC int localShadowFaceCount(LightData l) {
    return l.kind.x == LIGHT_SPOT && l.spot.x > LOCAL_SHADOW_SPOT_MAX_COS ? 1 : LOCAL_SHADOW_FACES;
}

// Face f of light l: the spot's face looks along its direction with the cone's half-angle; cube
// faces are +x, -x, +y, -y, +z, -z.
BRUME_FUNC LocalShadowFace localShadowFace(LightData l, int f) {
    LocalShadowFace face;
    if (localShadowFaceCount(l) == 1) {
        vec3 d = normalize(vec3(l.direction));
        vec3 helper = abs(d.y) < 0.99f ? vec3(0.0f, 1.0f, 0.0f) : vec3(1.0f, 0.0f, 0.0f);
        face.forward = d;
        face.right = normalize(cross(helper, d));
        face.up = cross(d, face.right);
        // At least ~0.006 degrees: an outer angle of 0 must not divide by 0 in the lookup.
        float c = l.spot.x;
        face.tanHalf = max(sqrt(max(1.0f - c * c, 0.0f)) / c, 1.0e-4f);
        return face;
    }
    int axis = f / 2;
    float sgn = f % 2 == 0 ? 1.0f : -1.0f;
    vec3 forward = vec3(0.0f);
    forward[axis] = sgn;
    vec3 up = axis == 1 ? vec3(0.0f, 0.0f, 1.0f) : vec3(0.0f, 1.0f, 0.0f);
    face.forward = forward;
    face.right = cross(up, forward);
    face.up = up;
    face.tanHalf = 1.0f;
    return face;
}

// Unit direction from the light through texel (i, j)'s centre of face `face` at resolution n.
BRUME_FUNC vec3 localShadowTexelDir(LocalShadowFace face, int i, int j, int n) {
    vec2 uv = (vec2(float(i), float(j)) + vec2(0.5f)) / float(n) * 2.0f - vec2(1.0f);
    return normalize(face.forward + (face.right * uv.x + face.up * uv.y) * face.tanHalf);
}

// The face of light l that sees offset d (point - light position).
BRUME_FUNC int localShadowFaceOf(LightData l, vec3 d) {
    if (localShadowFaceCount(l) == 1) return 0;
    vec3 a = abs(d);
    int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    return 2 * axis + (d[axis] >= 0.0f ? 0 : 1);
}

struct LocalShadowLookup {
    int base;       // index of texel (0, 0) of the point's face in the map array
    ivec2 texel;    // lower corner of the 2x2 PCF footprint (clamped to the face by the caller)
    vec2 weights;   // bilinear weights toward texel + 1
    float depth;    // the point's distance to the light, biased toward the light
    bool inside;    // false: outside the spot's face (where its cone is 0): unshadowed
};

BRUME_FUNC LocalShadowLookup localShadowLookup(LightData l, int n, vec3 p) {
    vec3 d = p - vec3(l.positionRange);
    int f = localShadowFaceOf(l, d);
    LocalShadowFace face = localShadowFace(l, f);
    float z = dot(d, face.forward);
    float dist = length(d);
    LocalShadowLookup k;
    // In front of the face by more than rounding (a point at the light is unshadowed), so that uv
    // below stays finite.
    k.inside = z > 1.0e-6f * dist;
    vec2 uv = k.inside ? vec2(dot(d, face.right), dot(d, face.up)) / (z * face.tanHalf) : vec2(0.0f);
    k.inside = k.inside && all(lessThanEqual(abs(uv), vec2(1.0f)));
    // Texel-centre coordinates; uv is clamped first so that a point far outside the face (unused,
    // inside = false) cannot overflow the int conversion.
    vec2 t = (clamp(uv, vec2(-2.0f), vec2(2.0f)) * 0.5f + vec2(0.5f)) * float(n) - vec2(0.5f);
    vec2 lower = floor(t);
    k.texel = ivec2(lower);
    k.weights = t - lower;
    k.base = ((lightShadowSlot(l)) * LOCAL_SHADOW_FACES + f) * n * n;
    k.depth = dist - LOCAL_SHADOW_BIAS_TEXELS * 2.0f * face.tanHalf * z / float(n);
    return k;
}

// Index into the map array of texel k.texel + offset, clamped to the point's face.
BRUME_FUNC int localShadowIndex(LocalShadowLookup k, int n, ivec2 offset) {
    ivec2 c = clamp(k.texel + offset, ivec2(0), ivec2(n - 1));
    return k.base + c.y * n + c.x;
}

// Bilinear PCF: the fraction of the 2x2 footprint that sees the light (1 lit, 0 shadowed).
BRUME_FUNC float localShadowPcf(LocalShadowLookup k, float d00, float d10, float d01, float d11) {
    float v00 = k.depth <= d00 ? 1.0f : 0.0f;
    float v10 = k.depth <= d10 ? 1.0f : 0.0f;
    float v01 = k.depth <= d01 ? 1.0f : 0.0f;
    float v11 = k.depth <= d11 ? 1.0f : 0.0f;
    return mix(mix(v00, v10, k.weights.x), mix(v01, v11, k.weights.x), k.weights.y);
}

BRUME_NAMESPACE_END

#endif
