// Henyey-Greenstein phase, light evaluation and Lambert surfaces.
#ifndef BRUME_SHARED_LIGHTING_H
#define BRUME_SHARED_LIGHTING_H

#include "specialization.h"
#include "types.h"

BRUME_NAMESPACE_BEGIN

// |g| is clamped to this so that the lobe's peak, (1+g)/(4 pi (1-g)^2), stays finite in float.
BRUME_CONST float PHASE_G_LIMIT = 0.999f;
// Point and spot lights behave as spheres of this radius for the inverse-square law [m]: no
// infinity at the light's position.
BRUME_CONST float LIGHT_MIN_DISTANCE = 0.01f;

// The parts of hgPhase that depend on g only, computed once per froxel for all its lights.
struct HgPhaseTerms {
    float numerator;  // (1 - g^2) / (4 pi)
    float base;       // (1 - g)^2 for g >= 0, (1 + g)^2 for g < 0
    float slope;      // 2 g for g >= 0, -2 g for g < 0
    float sign;       // -1 for g >= 0 (1 - cos), +1 for g < 0 (1 + cos)
};

BRUME_FUNC HgPhaseTerms hgPhaseTerms(float g) {
    float gc = clamp(g, -PHASE_G_LIMIT, PHASE_G_LIMIT);
    HgPhaseTerms t;
    t.numerator = BRUME_INV_4PI * (1.0f - gc * gc);
    t.base = gc >= 0.0f ? (1.0f - gc) * (1.0f - gc) : (1.0f + gc) * (1.0f + gc);
    t.slope = gc >= 0.0f ? 2.0f * gc : -2.0f * gc;
    t.sign = gc >= 0.0f ? -1.0f : 1.0f;
    return t;
}

// Henyey-Greenstein phase function [1/sr] from hgPhaseTerms(g) (see hgPhase).
BRUME_FUNC float hgPhaseOf(HgPhaseTerms t, float cosTheta) {
    // 1 + g^2 - 2 g cos, written as (1 - g)^2 + 2 g (1 - cos) for g >= 0 and (1 + g)^2 - 2 g (1 + cos)
    // for g < 0: both terms are then non-negative, so there is no cancellation at the peak, where the
    // naive form loses ~25% of its value in float at |g| = 0.999. (sign * cos is exact, so
    // 1 + sign * cos rounds as 1 - cos or 1 + cos.)
    float denom = max(t.base + t.slope * (1.0f + t.sign * cosTheta), 1.0e-12f);
    return t.numerator / (denom * sqrt(denom));
}

// Henyey-Greenstein phase function [1/sr]. cosTheta is the cosine between the direction the light
// travels and the direction it is scattered into; g > 0 scatters forward. Integrates to 1 over the
// sphere.
BRUME_FUNC float hgPhase(float g, float cosTheta) { return hgPhaseOf(hgPhaseTerms(g), cosTheta); }

// Smooth range window: 1 at the light, 0 at `range` and beyond, (1 - (r/range)^4)^2.
BRUME_FUNC float rangeWindow(float dist, float range) {
    if (range <= 0.0f) return 1.0f;
    float x = dist / range;
    float x2 = x * x;
    float w = clamp(1.0f - x2 * x2, 0.0f, 1.0f);
    return w * w;
}

// Spot cone: 1 inside the inner angle, 0 outside the outer, Hermite smoothstep on the cosine between.
BRUME_FUNC float spotCone(float cosAngle, float cosOuter, float cosInner) {
    if (cosInner - cosOuter < 1.0e-6f) return cosAngle >= cosOuter ? 1.0f : 0.0f;
    return smoothstep(cosOuter, cosInner, cosAngle);
}

struct LightSample {
    vec3 irradiance;   // W/m^2 arriving at the point on a surface facing the light (no shadowing)
    vec3 toLight;      // unit direction from the point toward the light
    float distance;    // distance to the light [m] (BRUME_HUGE for directional)
};

// A froxel resolves a point light no better than its own size: the light pass evaluates the
// inverse square no closer than this fraction of the froxel's radius (froxel.h froxelRadius). Without
// it, the jittered sample nearest a light inside the fog swings 1/r^2 by orders of magnitude from
// frame to frame (30% image flicker measured, 2.6% after the temporal blend). Over a ball of radius
// R around the light the clamp keeps (3R - 2m)/R^3 of the true mean 3/R^2 (m = 0.5 R: 2/3 of it) in
// that froxel only.
BRUME_CONST float FROXEL_LIGHT_CLAMP = 0.5f;

// evalLight, with the inverse square evaluated no closer than minDistance [m] to the light.
BRUME_FUNC LightSample evalLightNear(LightData l, vec3 p, float minDistance) {
    LightSample s;
    if (l.kind.x == LIGHT_DIRECTIONAL) {
        s.toLight = -vec3(l.direction);
        s.irradiance = vec3(l.intensity);
        s.distance = BRUME_HUGE;
        return s;
    }
    vec3 d = vec3(l.positionRange) - p;
    float dist = length(d);
    s.toLight = dist > 0.0f ? d / dist : vec3(0.0f, 1.0f, 0.0f);
    s.distance = dist;
    float r = max(dist, max(minDistance, LIGHT_MIN_DISTANCE));
    float atten = rangeWindow(dist, l.positionRange.w) / (r * r);
    // BRUME_SPOT_LIGHTS_USED: compiled out of pipelines whose scene has no spot light, where lavapipe
    // would run the cone for every light under a mask (docs/performance.md, "spot").
    if (BRUME_SPOT_LIGHTS_USED && l.kind.x == LIGHT_SPOT) {
        atten *= spotCone(dot(vec3(l.direction), -s.toLight), l.spot.x, l.spot.y);
    }
    s.irradiance = vec3(l.intensity) * atten;
    return s;
}

BRUME_FUNC LightSample evalLight(LightData l, vec3 p) { return evalLightNear(l, p, LIGHT_MIN_DISTANCE); }

// Radiance scattered toward the viewer at p by one light, per unit sigma_s (multiply by sigma_s and
// the visibility). viewDir is the unit direction from the camera to p.
BRUME_FUNC vec3 inScatterPerSigmaS(LightData l, LightSample s, vec3 viewDir, HgPhaseTerms phase) {
    // The light travels along -toLight; scattered light leaves toward the camera, along -viewDir.
    float cosTheta = dot(-s.toLight, -viewDir);
    return s.irradiance * (hgPhaseOf(phase, cosTheta) * l.fogScale);
}

BRUME_FUNC vec3 inScatterPerSigmaS(LightData l, LightSample s, vec3 viewDir, float g) {
    return inScatterPerSigmaS(l, s, viewDir, hgPhaseTerms(g));
}

// Lambertian surface: radiance = albedo / pi * irradiance * cos.
BRUME_FUNC vec3 lambert(vec3 albedo, vec3 normal, LightSample s) {
    return albedo * (1.0f / BRUME_PI) * s.irradiance * max(dot(normal, s.toLight), 0.0f);
}

BRUME_NAMESPACE_END

#endif
