// The GPU's march of the vdb volumes toward a light (shared/vdb_shadow.h; core: vdbFogOpticalDepth),
// sampling with vdb_sample.glsl's vdbDensity. Only the shadow volume pass's vdb variant includes it.
vec3 vdbFogOpticalDepth(LightData l, vec3 p, vec3 toLight, float distance) {
    if (frame.vdbShadowSamples <= 0 || !fogShadowsLight(l, frame.localFogShadows)) return vec3(0.0f);
    vec3 tau = vec3(0.0f);
    for (int i = 0; i < frame.counts.z; ++i) {
        VolumeData v = volumeAt(i);
        VdbShadowMarch m = vdbShadowMarch(v, p, toLight, distance, frame.vdbShadowSamples);
        float sum = 0.0f;
        for (int s = 0; s < m.count; ++s) sum += vdbDensity(v, m.start + m.step * float(s));
        tau += vdbShadowOpticalDepth(v, sum, m.stepLength);
    }
    return tau;
}
