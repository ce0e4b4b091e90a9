// Fog past the froxel range, in closed form. Beyond the last slice the composite continues each
// pixel's ray to its surface (or the camera's far plane) through the height and depth volumes
// analytically, so there is no seam where the froxel grid ends and the sky gets fog too.
//
// Along a ray s -> origin + s * dir the density length D = integral of density ds has a closed form
// for every height and depth profile. With a source K that is constant along the ray (directional
// lights and ambient at a fixed view direction; emission), the scattered radiance of one medium is
// exactly K * D * phi(sigma_t * D) and its transmittance exp(-sigma_t * D). Several volumes are
// combined as one mixture over the segment (exact when one volume dominates; documented in
// docs/gpu.md). Box and VDB volumes and point/spot lights end at the froxel range.
#ifndef BRUME_SHARED_DISTANT_H
#define BRUME_SHARED_DISTANT_H

#include "integrate.h"
#include "lighting.h"
#include "media.h"
#include "specialization.h"

BRUME_NAMESPACE_BEGIN

// Ray distance in [0, len] where y(s) = y0 + dy * s crosses `level` (0 when it never does). Splitting
// in ray-distance space keeps precision on near-horizontal rays, where differences of heights don't.
BRUME_FUNC float heightCrossing(float y0, float dy, float len, float level) {
    if (dy == 0.0f) return 0.0f;
    return clamp((level - y0) / dy, 0.0f, len);
}

// Integral of exp(-f * max(y(s) - base, 0)) over s in [0, len], y(s) = y0 + dy * s. The ray crosses
// base at most once (at c): of [0, c] and [c, len] one lies below base (density 1: its length) and
// the other above it. Telling them apart by the start's side and the slope, instead of integrating
// both pieces, needs one exp and one slabPhi (lavapipe evaluates both branches of every piece).
BRUME_FUNC float heightExponentialLength(float y0, float dy, float len, float base, float f) {
    float c = heightCrossing(y0, dy, len, base);
    bool startAbove = y0 > base;
    // [a, b]: the piece above base (empty, a = b = c = 0, for a ray that starts below and never rises).
    float a = startAbove ? 0.0f : c;
    float b = startAbove ? (dy < 0.0f ? c : len) : (dy > 0.0f ? len : c);
    float below = startAbove ? len - b : (dy > 0.0f ? c : len);
    float above = b - a;
    // Integrate upward from the piece's lowest point: the exponent of phi is then non-negative.
    float yLow = max(min(y0 + dy * a, y0 + dy * b), base);
    return below + exp(-f * (yLow - base)) * above * slabPhi(f * abs(dy) * above);
}

// One piece [a, b] of heightLinearLength, on which the density is linear: its length x its middle's.
BRUME_FUNC float heightLinearPiece(float y0, float dy, float base, float h, float a, float b) {
    float mid = 0.5f * (a + b);
    float density = clamp(1.0f - max(y0 + dy * mid - base, 0.0f) / h, 0.0f, 1.0f);
    return (b - a) * density;
}

// Integral of clamp(1 - max(y(s) - base, 0) / h, 0, 1) over s in [0, len]: the density is linear in s
// between the crossings of base and base + h, so the midpoint rule on those pieces is exact. (The
// three pieces written out rather than a loop over an array of edges, which lavapipe ran lane by
// lane: docs/performance.md, "pixel, round seven".)
BRUME_FUNC float heightLinearLength(float y0, float dy, float len, float base, float h) {
    float c0 = heightCrossing(y0, dy, len, base);
    float c1 = heightCrossing(y0, dy, len, base + h);
    float sA = min(c0, c1);
    float sB = max(c0, c1);
    float total = 0.0f;
    total += heightLinearPiece(y0, dy, base, h, 0.0f, sA);
    total += heightLinearPiece(y0, dy, base, h, sA, sB);
    total += heightLinearPiece(y0, dy, base, h, sB, len);
    return total;
}

// Integral of the depth fog's density over ray distances [s0, s1] from the camera (the ray starts
// at the camera, so the distance to the camera is s).
BRUME_FUNC float depthFogLength(float s0, float s1, float start, float visibility) {
    float a = max(s0, start);
    if (s1 <= a) return 0.0f;
    float k = 3.0f / visibility;
    // (s1 - a) - (e^{-k(a-start)} - e^{-k(s1-start)}) / k, with the difference written through phi
    // so it neither cancels nor divides by a tiny k.
    float len = s1 - a;
    float ea = exp(-k * (a - start));
    return len - ea * len * slabPhi(k * len);
}

// Density length of one volume along camera ray [s0, s1] (origin = camera position, dir unit).
BRUME_FUNC float distantDensityLength(VolumeData v, vec3 origin, vec3 dir, float s0, float s1) {
    if (s1 <= s0) return 0.0f;
    int k = v.kind.x;
    float y0 = origin.y + dir.y * s0;
    if (BRUME_VOLUME_KIND_USED(VOLUME_HEIGHT_EXPONENTIAL) && k == VOLUME_HEIGHT_EXPONENTIAL)
        return heightExponentialLength(y0, dir.y, s1 - s0, v.params.x, v.params.y);
    if (BRUME_VOLUME_KIND_USED(VOLUME_HEIGHT_LINEAR) && k == VOLUME_HEIGHT_LINEAR)
        return heightLinearLength(y0, dir.y, s1 - s0, v.params.x, v.params.y);
    if (BRUME_VOLUME_KIND_USED(VOLUME_DEPTH) && k == VOLUME_DEPTH) return depthFogLength(s0, s1, v.params.y, v.params.x);
    return 0.0f;
}

// In-scattering per unit sigma_s from a light that is the same everywhere along the ray
// (directional lights); 0 for point and spot lights.
BRUME_FUNC vec3 distantLightPerSigmaS(LightData l, vec3 dir, float g) {
    if (l.kind.x != LIGHT_DIRECTIONAL) return vec3(0.0f);
    return inScatterPerSigmaS(l, evalLight(l, vec3(0.0f)), dir, g);
}

// Running sums over the volumes of one distant segment.
struct DistantSegment {
    vec3 opticalDepth;   // sum of sigma_t * D
    vec3 sourceLength;   // sum of K * D, K = sigma_s * (lights + ambient) + emission
};

BRUME_FUNC DistantSegment emptyDistantSegment() {
    DistantSegment d;
    d.opticalDepth = vec3(0.0f);
    d.sourceLength = vec3(0.0f);
    return d;
}

// Adds one volume; lightPerSigmaS = sum over lights of distantLightPerSigmaS(l, dir, g of this
// volume) + ambient.
BRUME_FUNC DistantSegment addDistantVolume(DistantSegment d, VolumeData v, float densityLength, vec3 lightPerSigmaS) {
    if (densityLength <= 0.0f) return d;
    vec3 sigmaS = vec3(v.sigmaS_g);
    d.opticalDepth += (sigmaS + vec3(v.sigmaA)) * densityLength;
    d.sourceLength += (sigmaS * lightPerSigmaS + vec3(v.emission)) * densityLength;
    return d;
}

// Adds one directional light's in-scattering by one volume: lightPerSigmaS = distantLightPerSigmaS
// (g of this volume) x the fog's transmittance toward the light. With addDistantVolume called with
// the ambient alone, this gives the same segment as addDistantVolume with the sum over lights, but
// lets the caller evaluate each light's transmittance once per piece instead of once per volume.
BRUME_FUNC DistantSegment addDistantLight(DistantSegment d, VolumeData v, float densityLength, vec3 lightPerSigmaS) {
    if (densityLength <= 0.0f) return d;
    d.sourceLength += vec3(v.sigmaS_g) * lightPerSigmaS * densityLength;
    return d;
}

BRUME_FUNC Accumulated accumulateDistant(Accumulated a, DistantSegment d) {
    vec3 phi = vec3(slabPhi(d.opticalDepth.x), slabPhi(d.opticalDepth.y), slabPhi(d.opticalDepth.z));
    a.scattering += a.transmittance * d.sourceLength * phi;
    a.transmittance *= exp(-d.opticalDepth);
    return a;
}

BRUME_NAMESPACE_END

#endif
