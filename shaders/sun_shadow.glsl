// Visibility of light i at p through the sun shadow map (core: sunShadowVisibility): 1 for lights
// the map does not serve and outside the map. The fit and the depths through resources.glsl
// sunShadowFitAt and sunShadowDepthAt (texel views where the shader defines BRUME_SHADOW_MAP_TEXELS).
float sunShadowVisibility(int i, vec3 p) {
    if (SPEC_SUN_SHADOW_MAP == 0 || !sunShadowMapped(frame, i)) return 1.0f;
    SunShadowFit s = sunShadowFitAt();
    SunShadowLookup k = sunShadowLookup(s, p);
    if (!k.inside) return 1.0f;
    return sunShadowPcf(k, sunShadowDepthAt(sunShadowIndex(s, k.texel)),
                        sunShadowDepthAt(sunShadowIndex(s, k.texel + ivec2(1, 0))),
                        sunShadowDepthAt(sunShadowIndex(s, k.texel + ivec2(0, 1))),
                        sunShadowDepthAt(sunShadowIndex(s, k.texel + ivec2(1, 1))));
}

// The same for a froxel's sample point (core: sunShadowFroxelVisibility): the map's froxel layer,
// which shadows the fog inside solids (shared/sun_shadow.h).
float sunShadowFroxelVisibility(int i, vec3 p) {
    if (SPEC_SUN_SHADOW_MAP == 0 || !sunShadowMapped(frame, i)) return 1.0f;
    SunShadowFit s = sunShadowFitAt();
    SunShadowLookup k = sunShadowLookup(s, p);
    if (!k.inside) return 1.0f;
    return sunShadowPcf(k, sunShadowDepthAt(sunShadowFroxelIndex(s, k.texel)),
                        sunShadowDepthAt(sunShadowFroxelIndex(s, k.texel + ivec2(1, 0))),
                        sunShadowDepthAt(sunShadowFroxelIndex(s, k.texel + ivec2(0, 1))),
                        sunShadowDepthAt(sunShadowFroxelIndex(s, k.texel + ivec2(1, 1))));
}
