// Density of every analytic volume type and the accumulation of overlapping media.
// Scattering, absorption and emission add; the phase g is the mean of the volumes' g weighted by
// their scattering at the point (density x mean sigma_s), which is exact for the first moment of a
// mixture of Henyey-Greenstein lobes.
#ifndef BRUME_SHARED_MEDIA_H
#define BRUME_SHARED_MEDIA_H

#include "types.h"

BRUME_NAMESPACE_BEGIN

// The box kind's shapes as one distance u of q = 2 x local position: u < 1 inside, u = 1 on the
// surface, and the edge fade is a function of u alone. Box: max |q_a|; ellipsoid: |q|; cylinder:
// max(|q.xz|, |q.y|). All three are computed and one selected: no branch.
BRUME_FUNC float shapeDistance(int shape, vec3 q) {
    vec3 a = abs(q);
    float box = max(a.x, max(a.y, a.z));
    float ellipsoid = length(q);
    float cylinder = max(length(vec2(q.x, q.z)), a.y);
    return shape == SHAPE_ELLIPSOID ? ellipsoid : (shape == SHAPE_CYLINDER ? cylinder : box);
}

// The edge fade at shape distance u (< 1): 1 inside 1 - fade, smoothstep down to 0 at u = 1.
BRUME_FUNC float edgeFade(float u, float fade) { return fade > 0.0f ? 1.0f - smoothstep(1.0f - fade, 1.0f, u) : 1.0f; }

// height_falloff: exp(-falloff (y - bottom)), bottom the volume's lowest world point (box kind and vdb:
// params.z, params.w). Exactly 1 when the falloff is 0 (the default).
BRUME_FUNC float localHeightFactor(VolumeData v, float worldY) {
    return exp(-v.params.z * max(worldY - v.params.w, 0.0f));
}

// Density of a box, ellipsoid or cylinder volume (VOLUME_BOX with kind.y the shape).
BRUME_FUNC float boxDensity(VolumeData v, vec3 worldPos) {
    vec3 q = vec3(v.localFromWorld * vec4(worldPos, 1.0f));
    float d = shapeDistance(boxShape(v), q * 2.0f);
    if (d >= 1.0f) return 0.0f;
    return edgeFade(d, v.params.x) * localHeightFactor(v, worldPos.y);
}

BRUME_FUNC float heightExponentialDensity(VolumeData v, vec3 worldPos) {
    return exp(-v.params.y * max(worldPos.y - v.params.x, 0.0f));
}

BRUME_FUNC float heightLinearDensity(VolumeData v, vec3 worldPos) {
    return clamp(1.0f - max(worldPos.y - v.params.x, 0.0f) / v.params.y, 0.0f, 1.0f);
}

BRUME_FUNC float depthDensity(VolumeData v, vec3 worldPos, vec3 cameraPos) {
    float r = length(worldPos - cameraPos);
    if (r < v.params.y) return 0.0f;
    return 1.0f - exp(-3.0f * (r - v.params.y) / v.params.x);
}

BRUME_FUNC bool insideBounds(VolumeData v, vec3 p) {
    return p.x >= v.worldMin.x && p.y >= v.worldMin.y && p.z >= v.worldMin.z &&
           p.x <= v.worldMax.x && p.y <= v.worldMax.y && p.z <= v.worldMax.z;
}

// Density of an analytic volume of kind k (v's, a constant where the caller knows it: voxelize_body.glsl)
// at a world position (VDB volumes are sampled by their own code and report 0 here).
// BRUME_VOLUME_KIND_USED: a kind the scene lacks is compiled out of specialized pipelines.
BRUME_FUNC float analyticDensityOfKind(int k, VolumeData v, vec3 worldPos, vec3 cameraPos) {
    if (BRUME_VOLUME_KIND_USED(VOLUME_BOX) && k == VOLUME_BOX) return boxDensity(v, worldPos);
    if (BRUME_VOLUME_KIND_USED(VOLUME_HEIGHT_EXPONENTIAL) && k == VOLUME_HEIGHT_EXPONENTIAL)
        return heightExponentialDensity(v, worldPos);
    if (BRUME_VOLUME_KIND_USED(VOLUME_HEIGHT_LINEAR) && k == VOLUME_HEIGHT_LINEAR) return heightLinearDensity(v, worldPos);
    if (BRUME_VOLUME_KIND_USED(VOLUME_DEPTH) && k == VOLUME_DEPTH) return depthDensity(v, worldPos, cameraPos);
    return 0.0f;
}

BRUME_FUNC float analyticDensity(VolumeData v, vec3 worldPos, vec3 cameraPos) {
    return analyticDensityOfKind(v.kind.x, v, worldPos, cameraPos);
}

struct MediaSample {
    vec3 sigmaS;        // [1/m]
    vec3 sigmaT;        // [1/m], sigma_s + sigma_a
    vec3 emission;      // radiance per meter
    float gWeighted;    // sum of weight * g
    float gWeight;      // sum of weight (density x mean sigma_s)
};

BRUME_FUNC MediaSample emptyMedia() {
    MediaSample m;
    m.sigmaS = vec3(0.0f);
    m.sigmaT = vec3(0.0f);
    m.emission = vec3(0.0f);
    m.gWeighted = 0.0f;
    m.gWeight = 0.0f;
    return m;
}

BRUME_FUNC MediaSample addMedium(MediaSample m, VolumeData v, float density) {
    if (density <= 0.0f) return m;
    vec3 s = vec3(v.sigmaS_g) * density;
    m.sigmaS += s;
    m.sigmaT += s + vec3(v.sigmaA) * density;
    m.emission += vec3(v.emission) * density;
    float w = (s.x + s.y + s.z) * (1.0f / 3.0f);
    m.gWeighted += w * v.sigmaS_g.w;
    m.gWeight += w;
    return m;
}

BRUME_FUNC float mediaPhaseG(MediaSample m) { return m.gWeight > 0.0f ? m.gWeighted / m.gWeight : 0.0f; }

BRUME_NAMESPACE_END

#endif
