// Visibility of light i at p through the sun shadow map (core: sunShadowVisibility): 1 for lights
// the map does not serve and outside the map.
float sunShadowVisibility(int i, vec3 p) {
    if (SPEC_SUN_SHADOW_MAP == 0 || !sunShadowMapped(frame, i)) return 1.0f;
    SunShadowLookup k = sunShadowLookup(sunShadowFit, p);
    if (!k.inside) return 1.0f;
    return sunShadowPcf(k, sunShadowDepth[sunShadowIndex(sunShadowFit, k.texel)],
                        sunShadowDepth[sunShadowIndex(sunShadowFit, k.texel + ivec2(1, 0))],
                        sunShadowDepth[sunShadowIndex(sunShadowFit, k.texel + ivec2(0, 1))],
                        sunShadowDepth[sunShadowIndex(sunShadowFit, k.texel + ivec2(1, 1))]);
}

// The same for a froxel's sample point (core: sunShadowFroxelVisibility): the map's froxel layer,
// which shadows the fog inside solids (shared/sun_shadow.h).
float sunShadowFroxelVisibility(int i, vec3 p) {
    if (SPEC_SUN_SHADOW_MAP == 0 || !sunShadowMapped(frame, i)) return 1.0f;
    SunShadowLookup k = sunShadowLookup(sunShadowFit, p);
    if (!k.inside) return 1.0f;
    return sunShadowPcf(k, sunShadowDepth[sunShadowFroxelIndex(sunShadowFit, k.texel)],
                        sunShadowDepth[sunShadowFroxelIndex(sunShadowFit, k.texel + ivec2(1, 0))],
                        sunShadowDepth[sunShadowFroxelIndex(sunShadowFit, k.texel + ivec2(0, 1))],
                        sunShadowDepth[sunShadowFroxelIndex(sunShadowFit, k.texel + ivec2(1, 1))]);
}
