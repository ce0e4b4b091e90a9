// Visibility of light i at p through its point/spot shadow map (core: localShadowVisibility): 1 for
// unmapped lights and outside a spot's face.
// l: the light's data (lightAt(i), or its surface slot in geometry.frag).
float localShadowVisibility(LightData l, vec3 p) {
    int n = frame.localShadowTexels;
    if (SPEC_LOCAL_SHADOW_MAPS == 0 || !localShadowMapped(l, n)) return 1.0f;
    LocalShadowLookup k = localShadowLookup(l, n, p);
    if (!k.inside) return 1.0f;
    // Through the texel view localShadowTexels: lavapipe loads a storage buffer lane by lane.
    return localShadowPcf(k, texelFetch(localShadowTexels, localShadowIndex(k, n, ivec2(0, 0))).x,
                          texelFetch(localShadowTexels, localShadowIndex(k, n, ivec2(1, 0))).x,
                          texelFetch(localShadowTexels, localShadowIndex(k, n, ivec2(0, 1))).x,
                          texelFetch(localShadowTexels, localShadowIndex(k, n, ivec2(1, 1))).x);
}

float localShadowVisibility(int i, vec3 p) { return localShadowVisibility(lightAt(i), p); }
