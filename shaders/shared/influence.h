// Influencers (docs/scene-format.md, "Influencers"): spheres and upright capsules moving along a path
// that thin every volume's fog, and the wake they leave, which recovers with a half-life. The host
// (core/influence.h) turns each influencer into samples at the scene time: its shape now at full
// strength, plus its shape at past times tau on a fixed grid of times (multiples of a step that does
// not depend on the frame times), each at strength s 2^(-(t - tau) / h). A point's density is then
//     density x (1 - max over samples of (sample strength x falloff(distance to the sample's axis / radius)))
// with falloff(u) = 1 - smoothstep(0, 1, u): 1 on the axis, 0 at the radius and beyond, C1 at both.
// The CPU froxel renderer, the reference and the GPU's voxelize pass all evaluate influenceFactor.
// Fog shadows do not see influencers (like density textures, shadows use the plain density).
#ifndef BRUME_SHARED_INFLUENCE_H
#define BRUME_SHARED_INFLUENCE_H

#include "common.h"
#include "media.h"

BRUME_NAMESPACE_BEGIN

// One sphere or capsule: the influencer now or at one past time. 32 bytes in std430.
struct InfluenceSample {
    vec4 a;  // xyz: one end of the axis segment (a sphere: its centre) [m]; w: radius [m]
    vec4 b;  // xyz: the other end (a sphere: = a) [m]; w: strength in [0, 1]
};

// Ahead of the samples in the GPU's influence buffer; the CPU keeps the same record. 48 bytes: the
// buffer's texel view (influenceTexels, rgba32f) holds it in its first INFLUENCE_HEADER_TEXELS texels,
// then each InfluenceSample in 2.
BRUME_CONST int INFLUENCE_HEADER_TEXELS = 3;
struct InfluenceHeader {
    ivec4 count;     // x: samples; yzw unused
    vec4 boundsMin;  // xyz: the samples' world box (each one's axis grown by its radius); w unused
    vec4 boundsMax;  // xyz; w unused
};

// Below this strength a wake sample is dropped (it would change the density by less than 0.1%).
BRUME_CONST float INFLUENCE_MIN_STRENGTH = 1.0e-3f;

BRUME_FUNC float influenceFalloff(float u) {
    const float x = clamp(u, 0.0f, 1.0f);
    return 1.0f - x * x * (3.0f - 2.0f * x);
}

// Distance from p to the segment a..b.
BRUME_FUNC float influenceAxisDistance(vec3 p, vec3 a, vec3 b) {
    const vec3 ab = b - a;
    const float len2 = dot(ab, ab);
    const float u = len2 > 0.0f ? clamp(dot(p - a, ab) / len2, 0.0f, 1.0f) : 0.0f;
    return length(p - (a + ab * u));
}

// The density reduction of one sample at p, in [0, strength].
BRUME_FUNC float influenceSampleReduction(InfluenceSample s, vec3 p) {
    const float d = influenceAxisDistance(p, vec3(s.a), vec3(s.b));
    return s.b.w * influenceFalloff(d / max(s.a.w, 1.0e-6f));
}

BRUME_FUNC bool insideInfluenceBounds(InfluenceHeader h, vec3 p) {
    return h.count.x > 0 && all(greaterThanEqual(p, vec3(h.boundsMin))) && all(lessThanEqual(p, vec3(h.boundsMax)));
}

// Media scaled by an influence factor: sigma_s, sigma_t and emission alike, the phase g unchanged.
BRUME_FUNC MediaSample influenceScaleMedia(MediaSample m, float factor) {
    m.sigmaS *= factor;
    m.sigmaT *= factor;
    m.emission *= factor;
    m.gWeighted *= factor;
    m.gWeight *= factor;
    return m;
}

BRUME_NAMESPACE_END

#endif
