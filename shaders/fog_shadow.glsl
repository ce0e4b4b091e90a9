// The GPU's loop over volumes around the shared closed forms of shared/shadows.h (core:
// lightFogTransmittance): the fog's transmittance from p toward light l.
vec3 lightFogTransmittance(LightData l, vec3 p, vec3 toLight, float distance) {
    if (!fogShadowsLight(l, frame.shadows.x)) return vec3(1.0f);
    vec3 tau = vec3(0.0f);
    for (int i = 0; i < frame.counts.z; ++i) tau += shadowOpticalDepth(volumes[i], p, toLight, distance);
    return exp(-tau);
}

vec3 shadowCell(int light, ivec3 cells, ivec3 c) {
    return shadowTransmittance[shadowVolumeIndex(cells, light, c)].rgb;
}

ShadowBlend blendShadowCells(int light, ShadowLookup k) {
    ivec3 cells = shadowVolumeDims(frame.froxelDims.xyz, frame.shadows.y);
    ivec3 lo = k.cell;
    ivec3 hi = min(k.cell + ivec3(1), cells - ivec3(1));
    return shadowBlend(shadowCell(light, cells, lo), shadowCell(light, cells, ivec3(hi.x, lo.y, lo.z)),
                       shadowCell(light, cells, ivec3(lo.x, hi.y, lo.z)), shadowCell(light, cells, ivec3(hi.x, hi.y, lo.z)),
                       shadowCell(light, cells, ivec3(lo.x, lo.y, hi.z)), shadowCell(light, cells, ivec3(hi.x, lo.y, hi.z)),
                       shadowCell(light, cells, ivec3(lo.x, hi.y, hi.z)), shadowCell(light, cells, hi), k.weights);
}

// The light pass's transmittance (core: froxelFogTransmittance): the shadow volume's trilinear
// blend where its 8 cells agree, the exact closed form where a shadow edge crosses them.
vec3 froxelFogTransmittance(int light, ivec3 froxel, vec3 p, vec3 toLight, float distance) {
    if (!fogShadowsLight(lights[light], frame.shadows.x)) return vec3(1.0f);
    ShadowBlend b = blendShadowCells(light, shadowLookup(froxel, frame.froxelDims.xyz, frame.shadows.y));
    if (b.trusted) return b.transmittance;
    return lightFogTransmittance(lights[light], p, toLight, distance);
}

// Surfaces (core: surfaceFogTransmittance): the volume inside the grid, exact outside and at edges.
vec3 surfaceFogTransmittance(int light, vec3 p, vec3 toLight, float distance) {
    if (!fogShadowsLight(lights[light], frame.shadows.x)) return vec3(1.0f);
    SurfaceShadowLookup s = shadowLookupAt(froxelCoordFromWorld(p, frame), frame, frame.shadows.y);
    if (s.inside) {
        ShadowBlend b = blendShadowCells(light, s.k);
        if (b.trusted) return b.transmittance;
    }
    return lightFogTransmittance(lights[light], p, toLight, distance);
}
