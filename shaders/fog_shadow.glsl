// The GPU's loop over volumes around the shared closed forms of shared/shadows.h (core:
// lightFogTransmittance): the fog's transmittance from p toward light l.
vec3 lightFogTransmittance(LightData l, vec3 p, vec3 toLight, float distance) {
    if (!fogShadowsLight(l, frame.shadows.x)) return vec3(1.0f);
    vec3 tau = vec3(0.0f);
    for (int i = 0; i < frame.counts.z; ++i) tau += shadowOpticalDepth(volumes[i], p, toLight, distance);
    return exp(-tau);
}
