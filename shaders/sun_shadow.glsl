// The map through its texel view sunShadowTexels (shared/frame_table.h): lavapipe loads a storage
// buffer lane by lane, a texel view's texels as vector gathers (docs/performance.md, "sunview").
SunShadowFit sunShadowFitTexels() {
    return SunShadowFit(texelFetch(sunShadowTexels, 0), texelFetch(sunShadowTexels, 1), texelFetch(sunShadowTexels, 2),
                        texelFetch(sunShadowTexels, 3));
}
float sunShadowDepthAt(int i) { return texelFetch(sunShadowTexels, SUN_SHADOW_FIT_TEXELS + (i >> 2))[i & 3]; }

// Visibility of light i at p through the sun shadow map (core: sunShadowVisibility): 1 for lights
// the map does not serve and outside the map.
float sunShadowVisibility(int i, vec3 p) {
    if (SPEC_SUN_SHADOW_MAP == 0 || !sunShadowMapped(frame, i)) return 1.0f;
    SunShadowFit fit = sunShadowFitTexels();
    SunShadowLookup k = sunShadowLookup(fit, p);
    if (!k.inside) return 1.0f;
    return sunShadowPcf(k, sunShadowDepthAt(sunShadowIndex(fit, k.texel)),
                        sunShadowDepthAt(sunShadowIndex(fit, k.texel + ivec2(1, 0))),
                        sunShadowDepthAt(sunShadowIndex(fit, k.texel + ivec2(0, 1))),
                        sunShadowDepthAt(sunShadowIndex(fit, k.texel + ivec2(1, 1))));
}

// The same for a froxel's sample point (core: sunShadowFroxelVisibility): the map's froxel layer,
// which shadows the fog inside solids (shared/sun_shadow.h).
float sunShadowFroxelVisibility(int i, vec3 p) {
    if (SPEC_SUN_SHADOW_MAP == 0 || !sunShadowMapped(frame, i)) return 1.0f;
    SunShadowFit fit = sunShadowFitTexels();
    SunShadowLookup k = sunShadowLookup(fit, p);
    if (!k.inside) return 1.0f;
    return sunShadowPcf(k, sunShadowDepthAt(sunShadowFroxelIndex(fit, k.texel)),
                        sunShadowDepthAt(sunShadowFroxelIndex(fit, k.texel + ivec2(1, 0))),
                        sunShadowDepthAt(sunShadowFroxelIndex(fit, k.texel + ivec2(0, 1))),
                        sunShadowDepthAt(sunShadowFroxelIndex(fit, k.texel + ivec2(1, 1))));
}
