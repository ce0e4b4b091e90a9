// Closed-form integration of a homogeneous slab of length d with extinction sigma_t and source S
// (radiance per meter): scattered = S * (1 - exp(-sigma_t d)) / sigma_t, transmittance = exp(-sigma_t d).
// Written as S * d * phi(sigma_t d) with phi(x) = (1 - e^-x) / x so nothing divides by sigma_t:
// below x = 0.01 phi uses its Taylor series (truncation error < x^4/120 < 1e-9), above it the direct
// form, whose cancellation error there is below 1e-5 relative in float.
#ifndef BRUME_SHARED_INTEGRATE_H
#define BRUME_SHARED_INTEGRATE_H

#include "common.h"

BRUME_NAMESPACE_BEGIN

BRUME_FUNC float slabPhi(float x) {
    if (x < 0.01f) return 1.0f - x * (0.5f - x * (1.0f / 6.0f - x * (1.0f / 24.0f)));
    return (1.0f - exp(-x)) / x;
}

BRUME_FUNC vec3 slabTransmittance(vec3 sigmaT, float d) { return exp(-sigmaT * d); }

BRUME_FUNC vec3 slabScattering(vec3 source, vec3 sigmaT, float d) {
    vec3 x = sigmaT * d;
    return source * d * vec3(slabPhi(x.x), slabPhi(x.y), slabPhi(x.z));
}

// Front-to-back accumulation state: what reaches the camera from everything in front so far.
struct Accumulated {
    vec3 scattering;     // radiance added along the ray
    vec3 transmittance;  // fraction of light from behind that survives
};

BRUME_FUNC Accumulated emptyAccumulated() {
    Accumulated a;
    a.scattering = vec3(0.0f);
    a.transmittance = vec3(1.0f);
    return a;
}

BRUME_FUNC Accumulated accumulateSlab(Accumulated a, vec3 source, vec3 sigmaT, float d) {
    a.scattering += a.transmittance * slabScattering(source, sigmaT, d);
    a.transmittance *= slabTransmittance(sigmaT, d);
    return a;
}

// Linear interpolation of two accumulation states (the composite's lookup, see integratedLookup).
// Blending (S, T) pairs linearly keeps S + A T fixed when every pair has it, so energy is kept.
BRUME_FUNC Accumulated mixAccumulated(Accumulated a, Accumulated b, float t) {
    Accumulated r;
    r.scattering = mix(a.scattering, b.scattering, t);
    r.transmittance = mix(a.transmittance, b.transmittance, t);
    return r;
}

// Fog over a surface (or the sky): radiance behind * transmittance + scattered.
BRUME_FUNC vec3 compositeFog(vec3 background, Accumulated a) { return background * a.transmittance + a.scattering; }

BRUME_NAMESPACE_END

#endif
