// The GPU's loop over volumes around the shared closed forms of shared/shadows.h (core:
// lightFogTransmittance): the fog's transmittance from p toward light l. Volumes through
// resources.glsl volumeAt (a texel view where the shader defines BRUME_VOLUME_TEXELS).
// Specialized pipelines (shared/specialization.h) compile out the point/spot and vdb cases a scene lacks.
int localFogShadowsFlag() { return SPEC_LOCAL_FOG_SHADOWS != 0 ? frame.localFogShadows : 0; }

// Volume i's kind in a pipeline specialized with the scene's volume list (SPEC_VOLUME_COUNT >= 0).
int listedVolumeKind(int i) { return BRUME_SPEC_LISTED_KIND(SPEC_VOLUME_LIST, i); }

// The listed volumes' data, fetched once by an invocation that evaluates the transmittance toward
// several lights (or at several points): lavapipe gathers a volume's texels lane by lane on every
// fetch, and fetched inside the light loop they were gathered once per light (docs/performance.md,
// "hoist"). Members of volumes not listed are left unset and never read. Unused without the list
// (SPEC_VOLUME_COUNT < 0: lightFogTransmittance then reads every volume itself).
#define BRUME_FOG_VOLUME_MEMBER(i) VolumeData v##i;
struct FogVolumes {
    BRUME_EACH_LISTED_VOLUME(BRUME_FOG_VOLUME_MEMBER)
};
#undef BRUME_FOG_VOLUME_MEMBER

FogVolumes fogVolumes() {
    FogVolumes f;
#define BRUME_FETCH_FOG_VOLUME(i) if (BRUME_SPEC_VOLUME_LISTED(i)) f.v##i = volumeAt(i);
    BRUME_EACH_LISTED_VOLUME(BRUME_FETCH_FOG_VOLUME)
#undef BRUME_FETCH_FOG_VOLUME
    return f;
}

// exp(-tau) per channel; one exp where the pipeline knows every volume's sigma_t is grey
// (SPEC_GREY_FOG_SHADOWS), so that tau's three channels are the same float: the same values.
vec3 transmittanceOfDepth(vec3 tau) { return SPEC_GREY_FOG_SHADOWS != 0 ? vec3(exp(-tau.x)) : exp(-tau); }

// vs: fogVolumes(), fetched by the caller once for all its lights.
vec3 lightFogTransmittance(FogVolumes vs, LightData l, vec3 p, vec3 toLight, float distance) {
    if (!fogShadowsLight(l, localFogShadowsFlag())) return vec3(1.0f);
    vec3 tau = vec3(0.0f);
    if (SPEC_VOLUME_COUNT >= 0) {
        // Unrolled by hand with each volume's kind a constant: only that kind's closed form is
        // built for it (a loop would run every kind's code for every volume on lavapipe).
#define BRUME_LISTED_VOLUME(i) \
    if (BRUME_SPEC_VOLUME_LISTED(i))   \
        tau += shadowOpticalDepthListed(listedVolumeKind(i), BRUME_SPEC_LISTED_SHAPE(i), vs.v##i, p, toLight, distance);
        BRUME_EACH_LISTED_VOLUME(BRUME_LISTED_VOLUME)
#undef BRUME_LISTED_VOLUME
    } else {
        for (int i = 0; i < frame.counts.z; ++i) tau += shadowOpticalDepth(volumeAt(i), p, toLight, distance);
    }
    return transmittanceOfDepth(tau);
}

// The same for a caller that evaluates one transmittance (the volumes fetched here).
vec3 lightFogTransmittance(LightData l, vec3 p, vec3 toLight, float distance) {
    return lightFogTransmittance(fogVolumes(), l, p, toLight, distance);
}

// Entry i of the fog transmittance volume, read through its texel view (shared/frame_table.h
// shadowTexels): lavapipe gathers a texel buffer's texels as vectors, where it loads a storage
// buffer's lane by lane (docs/performance.md, "blend").
vec3 shadowEntry(int i) { return texelFetch(shadowTexels, i).rgb; }

vec3 shadowCell(int light, ShadowLookup k, int x, int y, int z) {
    ivec3 c = ivec3(x != 0 ? k.upper.x : k.cell.x, y != 0 ? k.upper.y : k.cell.y, z != 0 ? k.upper.z : k.cell.z);
    return shadowEntry(shadowVolumeIndex(k.cells, light, c));
}

// The 8 cells around lookup k (core: blendShadowCells).
ShadowBlend blendShadowCells(int light, ShadowLookup k) {
    return shadowBlend(shadowCell(light, k, 0, 0, 0), shadowCell(light, k, 1, 0, 0), shadowCell(light, k, 0, 1, 0),
                       shadowCell(light, k, 1, 1, 0), shadowCell(light, k, 0, 0, 1), shadowCell(light, k, 1, 0, 1),
                       shadowCell(light, k, 0, 1, 1), shadowCell(light, k, 1, 1, 1), k.weights);
}

// The 8 cells of lookup k as offsets inside one light's layer, and the layer's size: computed once
// per froxel, so each light's blend costs one multiply-add per cell instead of shadowVolumeIndex's
// chain (the same entries: shadowVolumeIndex(cells, light, c) = light * layer + offset(c)).
struct ShadowCorners {
    int layer;
    ivec4 lower;  // c000, c001, c010, c011 (c<z><y><x>, shadow_volume.h shadowBlend)
    ivec4 upper;  // c100, c101, c110, c111
};

ShadowCorners shadowCorners(ShadowLookup k) {
    ShadowCorners c;
    c.layer = k.cells.z * k.cells.y * k.cells.x;
    ivec2 y = ivec2(k.cell.y, k.upper.y) * k.cells.x;
    ivec2 z = ivec2(k.cell.z, k.upper.z) * (k.cells.y * k.cells.x);
    c.lower = ivec4(z.x + y.x + k.cell.x, z.x + y.x + k.upper.x, z.x + y.y + k.cell.x, z.x + y.y + k.upper.x);
    c.upper = ivec4(z.y + y.x + k.cell.x, z.y + y.x + k.upper.x, z.y + y.y + k.cell.x, z.y + y.y + k.upper.x);
    return c;
}

// blendShadowCells with the corners of shadowCorners(k): the same cells, the same blend.
ShadowBlend blendShadowCorners(int light, ShadowCorners c, vec3 weights) {
    int base = light * c.layer;
    return shadowBlend(shadowEntry(base + c.lower.x), shadowEntry(base + c.lower.y), shadowEntry(base + c.lower.z),
                       shadowEntry(base + c.lower.w), shadowEntry(base + c.upper.x), shadowEntry(base + c.upper.y),
                       shadowEntry(base + c.upper.z), shadowEntry(base + c.upper.w), weights);
}

// Light `light`'s vdb layer blended at k (core: vdbLayerBlend; shared/vdb_shadow.h): 1 without vdb
// shadows. No exact fallback: only the shadow volume pass marches grids.
vec3 vdbShadowBlend(int light, ShadowLookup k) {
    if (SPEC_VDB_SHADOWS == 0 || frame.vdbShadowSamples <= 0) return vec3(1.0f);
    return vdbShadowTransmittance(blendShadowCells(vdbShadowLayer(light, frame.counts.w), k).transmittance);
}

// The light pass's transmittance (core: froxelFogTransmittance): the shadow volume's trilinear
// blend where its 8 cells agree, the exact closed form where a shadow edge crosses them.
// k: shadowLookup of the froxel, computed once for all lights.
vec3 froxelFogTransmittance(int light, ShadowLookup k, vec3 p, vec3 toLight, float distance) {
    if (!fogShadowsLight(lightAt(light), localFogShadowsFlag())) return vec3(1.0f);
    vec3 vdb = vdbShadowBlend(light, k);
    ShadowBlend b = blendShadowCells(light, k);
    if (b.trusted) return b.transmittance * vdb;
    return lightFogTransmittance(lightAt(light), p, toLight, distance) * vdb;
}

// Surfaces (core: surfaceFogTransmittance): the exact closed form everywhere, times the vdb layer's
// blend. Not the volume's blend with the exact fallback: lavapipe runs both sides of that branch, so
// the blend only added its 8 loads to the exact form's cost (docs/performance.md, "perfgeo").
// s: shadowLookupAt of p, computed once for all lights (the vdb layer's lookup).
// vs: fogVolumes(), fetched once per fragment. l: lightAt(light), or the same light's surface slot
// (geometry.frag), whose kind may be a constant.
vec3 surfaceFogTransmittance(FogVolumes vs, LightData l, int light, SurfaceShadowLookup s, vec3 p, vec3 toLight,
                             float distance) {
    if (!fogShadowsLight(l, localFogShadowsFlag())) return vec3(1.0f);
    vec3 vdb = vdbShadowBlend(light, s.k);  // at the clamped lookup even outside (core: the same)
    return lightFogTransmittance(vs, l, p, toLight, distance) * vdb;
}
