// The map through its texel view sunShadowTexels (shared/frame_table.h): lavapipe loads a storage
// buffer lane by lane, a texel view's texels as vector gathers (docs/performance.md, "sunview").
SunShadowFit sunShadowFitTexels() {
    return SunShadowFit(texelFetch(sunShadowTexels, 0), texelFetch(sunShadowTexels, 1), texelFetch(sunShadowTexels, 2),
                        texelFetch(sunShadowTexels, 3));
}
float sunShadowDepthAt(int i) { return texelFetch(sunShadowTexels, SUN_SHADOW_FIT_TEXELS + (i >> 2))[i & 3]; }

// Texel t of the map's layer for surfaces (sunShadowIndex) or for froxels (sunShadowFroxelIndex).
int sunShadowLayerIndex(SunShadowFit fit, ivec2 t, bool froxels) {
    return froxels ? sunShadowFroxelIndex(fit, t) : sunShadowIndex(fit, t);
}

// Visibility of light i at p through one layer of the sun shadow map: 1 for lights the map does not
// serve and outside the map. `froxels`, a constant at each caller, picks the layer.
float sunShadowLayerVisibility(int i, vec3 p, bool froxels) {
    if (SPEC_SUN_SHADOW_MAP == 0 || !sunShadowMapped(frame, i)) return 1.0f;
    SunShadowFit fit = sunShadowFitTexels();
    SunShadowLookup k = sunShadowLookup(fit, p);
    if (!k.inside) return 1.0f;
    return sunShadowPcf(k, sunShadowDepthAt(sunShadowLayerIndex(fit, k.texel, froxels)),
                        sunShadowDepthAt(sunShadowLayerIndex(fit, k.texel + ivec2(1, 0), froxels)),
                        sunShadowDepthAt(sunShadowLayerIndex(fit, k.texel + ivec2(0, 1), froxels)),
                        sunShadowDepthAt(sunShadowLayerIndex(fit, k.texel + ivec2(1, 1), froxels)));
}

// At a surface point (core: sunShadowVisibility).
float sunShadowVisibility(int i, vec3 p) { return sunShadowLayerVisibility(i, p, false); }

// At a froxel's sample point (core: sunShadowFroxelVisibility): the map's froxel layer, which shadows
// the fog inside solids (shared/sun_shadow.h).
float sunShadowFroxelVisibility(int i, vec3 p) { return sunShadowLayerVisibility(i, p, true); }
