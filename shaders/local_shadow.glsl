// Visibility of light i at p through its point/spot shadow map (core: localShadowVisibility): 1 for
// unmapped lights and outside a spot's face.
float localShadowVisibility(int i, vec3 p) {
    int n = frame.localShadowTexels;
    if (SPEC_LOCAL_SHADOW_MAPS == 0 || !localShadowMapped(lightAt(i), n)) return 1.0f;
    LocalShadowLookup k = localShadowLookup(lightAt(i), n, p);
    if (!k.inside) return 1.0f;
    // Through the texel view localShadowTexels: lavapipe loads a storage buffer lane by lane.
    return localShadowPcf(k, texelFetch(localShadowTexels, localShadowIndex(k, n, ivec2(0, 0))).x,
                          texelFetch(localShadowTexels, localShadowIndex(k, n, ivec2(1, 0))).x,
                          texelFetch(localShadowTexels, localShadowIndex(k, n, ivec2(0, 1))).x,
                          texelFetch(localShadowTexels, localShadowIndex(k, n, ivec2(1, 1))).x);
}
