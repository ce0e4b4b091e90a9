// The light pass's body, built twice (light.comp, light_exact.comp): source S = sigma_s (lights'
// in-scattering x fog transmittance toward the light, read from the shadow volume pass's output
// (fog_shadow.glsl froxelFogTransmittance), + ambient) + emission (core: lightRow). Froxels with
// sigma_t = 0 skip lighting and hold S = emission: nothing scatters where nothing extinguishes, but a
// purely emissive medium still glows.
//
// Split in two dispatches because lavapipe pays for code whether a branch takes it or not
// (docs/performance.md): the exact closed-form fallback of froxelFogTransmittance, needed where a
// shadow edge crosses the shadow volume's cells, would cost every froxel.
//   light.comp (every froxel): the trusted blend only; a froxel where some light's blend is not
//     trusted is appended to exactList (its S written here is replaced by the second pass).
//   light_exact.comp (indirect, one invocation per listed froxel): the whole sum again, with the
//     exact fallback, in the same order, so S is what one pass computing both would write.
// light.comp runs over the froxels that can hold media only (core/media_region.h), like voxelize, one
// invocation per run of LIGHT_RUN froxels along z (bindings.h): it counts its lit froxels and marks its
// exact ones in registers, then adds them with one atomic each (the count, the exact list), where an
// atomic per froxel cost ~17% of the pass on lavapipe (docs/performance.md, "light, fifth round").
// It walks its run in blocks of LIGHT_BLOCK froxels that share their cluster's light list, each
// light's fetch and the transmittance volume's cells (lightBlock); light_exact.comp computes one
// froxel at a time (lightFroxel). Both compute each froxel's S with the same arithmetic in the same
// order.
// Both are specialized (shared/specialization.h): the vdb layer, the sun shadow map and the point/spot
// shadow maps are compiled out when the frame has none (SPEC_VDB_SHADOWS, SPEC_SUN_SHADOW_MAP,
// SPEC_LOCAL_SHADOW_MAPS), where they would return 1. (They were #define variants before.)
#define BRUME_FROXEL_IMAGES
#define BRUME_LIGHT_TEXELS  // lights and their clusters through texel views (resources.glsl lightAt)
#define BRUME_VOLUME_TEXELS  // and the volumes of the exact closed form (resources.glsl volumeAt)
#include "resources.glsl"
#include "fog_shadow.glsl"
#include "sun_shadow.glsl"
#include "local_shadow.glsl"
#ifdef BRUME_INLINE_MEDIA
#ifdef BRUME_VOXELIZE_TEXTURE
#include "density_texture.glsl"
#endif
#include "media_at.glsl"
#endif

#ifdef BRUME_LIGHT_EXACT
layout(local_size_x = LIGHT_EXACT_GROUP) in;
#else
layout(local_size_x = LIGHT_GROUP_X, local_size_y = LIGHT_GROUP_Y, local_size_z = 1) in;
// The froxels the pass computes, [lo, hi): the temporal region (core/media_region.h temporalFroxelRegion;
// gpu/frame_executor.cpp Dispatch::RegionLightRuns).
layout(push_constant) uniform RegionBlock { FroxelRegionParams lightRegion; };
#include "column_entries.glsl"
#include "balanced_groups.glsl"
#endif

// The sun shadow map's visibility at p for the mapped sun (sun_shadow.glsl), looked up once per
// froxel: only light frame.sunShadowLight - 1 is multiplied by it.
float lightSunVisibility(vec3 p) { return sunShadowFroxelVisibility(frame.sunShadowLight - 1, p); }

// Shadow maps' visibility of light i at p; sun: lightSunVisibility(p).
float lightMapVisibility(int i, vec3 p, float sun) {
    return (i == frame.sunShadowLight - 1 ? sun : 1.0f) * localShadowVisibility(i, p);
}

// The froxel's emission: 0 without a load when no volume emits (SPEC_EMISSION; the frame then clears
// mediaEmission, so the value is the same).
vec3 mediaEmissionAt(ivec3 id) { return SPEC_EMISSION != 0 ? imageLoad(mediaEmission, id).rgb : vec3(0.0f); }

// glow.h evalLightFroxel with the light's glow radius this frame read from l.spot.z, where the GPU
// renderer writes lightGlowRadius(l, frame) once per frame (gpu_renderer.cpp writeLightGlowRadii):
// the radius is the same for every froxel, and its pow, matrix product and square root cost every
// (froxel, listed light) pair on lavapipe. The same steps as evalLightFroxel after the radius.
LightSample lightFroxelSample(LightData l, vec3 p, float nearest) {
    float glow = l.spot.z;
    LightSample s = evalLightNear(l, p, glow > 0.0f ? LIGHT_MIN_DISTANCE : nearest);
    float u2 = (s.distance * s.distance) / (glow * glow);
    if (glow > 0.0f && u2 < 1.0f) s.irradiance *= u2 * (2.0f - u2);  // 1 - h
    return s;
}

// A froxel's media (sigma_s and phase g, sigma_t, emission): loaded from voxelize's images, or with
// BRUME_INLINE_MEDIA (the _media variants, scenes without vdb volumes) computed here at the froxel's
// sample point p as voxelize computes them (media_at.glsl), the same values: voxelize then runs only
// when the media volumes are read back, and its 8 stored words per froxel and these loads are saved
// (docs/performance.md, "fuse"). A member a caller does not use is dead code once inlined.
struct FroxelMedia {
    vec4 scatteringG;
    vec3 sigmaT;
    vec3 emission;
};

FroxelMedia froxelMedia(ivec3 id, vec3 p) {
    FroxelMedia f;
#ifdef BRUME_INLINE_MEDIA
    MediaSample m = froxelMediaAt(p);
    f.scatteringG = vec4(m.sigmaS, mediaPhaseG(m));
    f.sigmaT = m.sigmaT;
    f.emission = SPEC_EMISSION != 0 ? m.emission : vec3(0.0f);
#else
    f.scatteringG = imageLoad(mediaScatteringG, id);
    f.sigmaT = imageLoad(mediaExtinction, id).rgb;
    f.emission = mediaEmissionAt(id);
#endif
    return f;
}

#ifdef BRUME_LIGHT_EXACT
// fog_shadow.glsl froxelFogTransmittance, with the corners of shadowCorners and the volumes vs
// (fogVolumes()) fetched once per froxel, not once per light (docs/performance.md, "hoist").
vec3 exactFogTransmittance(FogVolumes vs, int light, ShadowLookup k, ShadowCorners c, vec3 p, vec3 toLight, float distance) {
    if (!fogShadowsLight(lightAt(light), localFogShadowsFlag())) return vec3(1.0f);
    vec3 vdb = vdbShadowBlend(light, k);
    ShadowBlend b = blendShadowCorners(light, c, k.weights);
    if (b.trusted) return b.transmittance * vdb;
    return lightFogTransmittance(vs, lightAt(light), p, toLight, distance) * vdb;
}

// S at froxel id, which light.comp listed (so sigma_t > 0 there): each light's trusted blend as
// light.comp computed it, the exact closed form where the blend is not trusted.
void lightFroxel(ivec3 id) {
    vec3 p = worldFromFroxelCoord(vec3(id) + frame.jitter.xyz, frame);
    FroxelMedia media = froxelMedia(id, p);
    vec4 scatteringG = media.scatteringG;
    vec3 viewDir = normalize(p - frame.cameraPosition.xyz);
    vec3 perSigmaS = frame.ambient.rgb;
    ShadowLookup shadow = shadowLookup(id, frame.froxelDims.xyz, frame.shadowReduction);
    ShadowCorners corners = shadowCorners(shadow);
    float nearest = FROXEL_LIGHT_CLAMP * froxelRadius(id.z, frame);
    HgPhaseTerms phase = hgPhaseTerms(scatteringG.a);
    float sun = lightSunVisibility(p);
    FogVolumes volumes = fogVolumes();
    // Only the lights of this froxel's cluster (clusters.h), in the CPU's order.
    int record = clusterRecord(id, frame.froxelDims.xyz);
    bool all = clusterInt(record) == CLUSTER_ALL_LIGHTS;
    int count = all ? frame.counts.w : clusterInt(record);
    for (int k = 0; k < count; ++k) {
        int i = all ? k : clusterInt(record + 1 + k);
        LightData l = lightAt(i);
        LightSample ls = lightFroxelSample(l, p, nearest);
        vec3 inScatter = inScatterPerSigmaS(l, ls, viewDir, phase);
        // Outside the range window or the cone, or fog_scale 0: the shadow cannot matter.
        if (inScatter == vec3(0.0f)) continue;
        perSigmaS += inScatter * exactFogTransmittance(volumes, i, shadow, corners, p, ls.toLight, ls.distance) *
                     lightMapVisibility(i, p, sun);
    }
    vec3 source = scatteringG.rgb * perSigmaS + media.emission;
    // sigma_t.r beside S as light.comp stored it (its sigma_t.gb in sourceExtinction stays).
    imageStore(sourceImage, id, historyTexelA(vec4(source, 0.0f), vec4(media.sigmaT, 0.0f)));
}
#else
// Appends the froxels of the run starting at `first` whose bit is set in `run` (bit k: first + k along
// z) to exactList, with one atomic for the run's slots and one for the indirect dispatch's groups
// (which only grows: the largest slot count any run reached, in groups of LIGHT_EXACT_GROUP).
void appendExactRun(ivec3 first, uint run) {
    uint n = uint(bitCount(run));
    uint slot = atomicAdd(exactList.count, n);
    atomicMax(exactList.groupsX, (slot + n + uint(LIGHT_EXACT_GROUP) - 1u) / uint(LIGHT_EXACT_GROUP));
    uint plane = uint(frame.froxelDims.x * frame.froxelDims.y);
    uint linear = uint(first.x + frame.froxelDims.x * first.y) + uint(first.z) * plane;
    for (; run != 0u; run &= run - 1u) exactFroxels[slot++] = linear + uint(findLSB(run)) * plane;
}

// The transmittance volume's reduction r: the pipeline's constant, or the frame's where the pipeline
// is not specialized.
int lightShadowReduction() { return SPEC_SHADOW_REDUCTION > 0 ? SPEC_SHADOW_REDUCTION : frame.shadowReduction; }

// Which of a block's cell levels (lightBlock) slot j's lower corner lies on: (z0 + j) / r - z0 / r, a
// constant where the pipeline is specialized with r = 1, 2 or a multiple of 4.
int blockLevel(int z0, int j, int r) {
    if (SPEC_SHADOW_REDUCTION == 1) return j;
    if (SPEC_SHADOW_REDUCTION > 0 && SPEC_SHADOW_REDUCTION % LIGHT_BLOCK == 0) return 0;
    if (SPEC_SHADOW_REDUCTION == 2) return j / 2;
    return (z0 + j) / r - z0 / r;
}

// One level of a light's 8 cells along z (shadow_volume.h shadowLevel), its 4 cells fetched.
ShadowLevel cellLevel(int base, ivec4 xy, vec2 w) {
    return shadowLevel(shadowEntry(base + xy.x), shadowEntry(base + xy.y), shadowEntry(base + xy.z),
                       shadowEntry(base + xy.w), w);
}

ShadowLevel pickLevel(int n, ShadowLevel l0, ShadowLevel l1, ShadowLevel l2, ShadowLevel l3, ShadowLevel l4) {
    return n == 0 ? l0 : (n == 1 ? l1 : (n == 2 ? l2 : (n == 3 ? l3 : l4)));
}

// Froxels z0 .. z0 + LIGHT_BLOCK - 1 of column xy (z0 a multiple of LIGHT_BLOCK = 4, so inside one
// cluster): S of those in [zLo, zHi] (the run), each froxel's as lightFroxel computes it where every
// light's blend is trusted (the same arithmetic in the same order), with the cluster's light list,
// each light's fetch and the transmittance volume's cells read once for the block: its froxels share
// their cells' xy corners and, r at a time, their levels along z (at r = 2: 3 levels of 4 cells, 12
// fetches per light where 4 froxels read 32; shadow_volume.h shadowBlend's min, max and bilinear blend
// split by level, the same operations on the same values).
// lit: the run's froxels with sigma_t > 0 counted; returns the exact ones as bits (bit j: z0 + j).
uint lightBlock(ivec2 xy, int z0, int zLo, int zHi, inout uint lit) {
    int r = lightShadowReduction();
    ivec3 dims = frame.froxelDims.xyz;
    bool valid[LIGHT_BLOCK];
    bool media[LIGHT_BLOCK];
    vec4 scatteringG[LIGHT_BLOCK];
    vec3 emission[LIGHT_BLOCK];
    vec3 sigmaT[LIGHT_BLOCK];
    vec3 p[LIGHT_BLOCK];
    vec3 viewDir[LIGHT_BLOCK];
    vec3 perSigmaS[LIGHT_BLOCK];
    float nearest[LIGHT_BLOCK];
    HgPhaseTerms phase[LIGHT_BLOCK];
    float sun[LIGHT_BLOCK];
    ShadowLookup shadow[LIGHT_BLOCK];
    int level[LIGHT_BLOCK];
    bool exact[LIGHT_BLOCK];
    [[unroll]] for (int j = 0; j < LIGHT_BLOCK; ++j) {
        ivec3 id = ivec3(xy, min(z0 + j, dims.z - 1));
        valid[j] = z0 + j >= zLo && z0 + j <= zHi;
        p[j] = worldFromFroxelCoord(vec3(id) + frame.jitter.xyz, frame);
        FroxelMedia f = froxelMedia(id, p[j]);
        sigmaT[j] = f.sigmaT;
        media[j] = f.sigmaT != vec3(0.0f);
        scatteringG[j] = f.scatteringG;
        emission[j] = f.emission;
        viewDir[j] = normalize(p[j] - frame.cameraPosition.xyz);
        perSigmaS[j] = frame.ambient.rgb;
        nearest[j] = FROXEL_LIGHT_CLAMP * froxelRadius(id.z, frame);
        phase[j] = hgPhaseTerms(scatteringG[j].a);
        sun[j] = lightSunVisibility(p[j]);
        shadow[j] = shadowLookup(id, dims, r);
        level[j] = blockLevel(z0, j, r);
        exact[j] = false;
    }
    // The cells' offsets inside a light's layer: the xy corners, and the block's levels along z.
    // (The same entries as shadowCorners: c<z><y><x> = light * layer + level(z) + xyCorners(y, x).)
    ShadowLookup s0 = shadow[0];
    int plane = s0.cells.y * s0.cells.x;
    ivec2 rows = ivec2(s0.cell.y, s0.upper.y) * s0.cells.x;
    ivec4 xyCorners = ivec4(rows.x + s0.cell.x, rows.x + s0.upper.x, rows.y + s0.cell.x, rows.y + s0.upper.x);
    // Level n is cell z = min(slot 0's + n, the last): slot j's lower corner is on level blockLevel(j),
    // its upper one on the next (shadowLookup's upper, clamped the same way). 5 levels: at r = 1 each
    // of the 4 froxels has its own, and the last one's upper; at r >= 2 fewer are read (the others
    // are dead code once r is a constant).
    ivec4 lowerLevels = min(ivec4(s0.cell.z) + ivec4(0, 1, 2, 3), ivec4(s0.cells.z - 1)) * plane;
    int topLevel = min(s0.cell.z + 4, s0.cells.z - 1) * plane;
    int layer = s0.cells.z * plane;
    vec2 wxy = s0.weights.xy;
    int record = clusterRecord(ivec3(xy, z0), dims);
    bool all = clusterInt(record) == CLUSTER_ALL_LIGHTS;
    int count = all ? frame.counts.w : clusterInt(record);
    for (int k = 0; k < count; ++k) {
        int i = all ? k : clusterInt(record + 1 + k);
        LightData l = lightAt(i);
        bool shadows = fogShadowsLight(l, localFogShadowsFlag());
        int base = i * layer;
        ShadowLevel l0 = cellLevel(base + lowerLevels.x, xyCorners, wxy);
        ShadowLevel l1 = cellLevel(base + lowerLevels.y, xyCorners, wxy);
        ShadowLevel l2 = cellLevel(base + lowerLevels.z, xyCorners, wxy);
        ShadowLevel l3 = cellLevel(base + lowerLevels.w, xyCorners, wxy);
        ShadowLevel l4 = cellLevel(base + topLevel, xyCorners, wxy);
        [[unroll]] for (int j = 0; j < LIGHT_BLOCK; ++j) {
            LightSample ls = lightFroxelSample(l, p[j], nearest[j]);
            vec3 inScatter = inScatterPerSigmaS(l, ls, viewDir[j], phase[j]);
            // Outside the range window or the cone, or fog_scale 0: the shadow cannot matter.
            // (An if block, not a `continue`: spirv-opt unrolls an [[unroll]] loop only without one,
            // and the per-slot arrays then become registers; docs/performance.md, "groups".)
            if (inScatter != vec3(0.0f)) {
                ShadowLevel lower = pickLevel(level[j], l0, l1, l2, l3, l4);
                ShadowLevel upper = pickLevel(level[j] + 1, l0, l1, l2, l3, l4);
                ShadowBlend b = shadowBlendLevels(lower, upper, shadow[j].weights);
                bool trusted = !shadows || b.trusted;
                vec3 transmittance = shadows ? b.transmittance * vdbShadowBlend(i, shadow[j]) : vec3(1.0f);
                perSigmaS[j] += inScatter * transmittance * lightMapVisibility(i, p[j], sun[j]);
                exact[j] = exact[j] || !trusted;
            }
        }
    }
    uint bits = 0u;
    [[unroll]] for (int j = 0; j < LIGHT_BLOCK; ++j) {
        if (valid[j]) {
            ivec3 id = ivec3(xy, z0 + j);
            vec3 source = media[j] ? scatteringG[j].rgb * perSigmaS[j] + emission[j] : emission[j];
            // S and sigma_t in the history's layout (resources.glsl): the temporal and integrate passes
            // read them there.
            vec4 extinction = vec4(sigmaT[j], 0.0f);
            imageStore(sourceImage, id, historyTexelA(vec4(source, 0.0f), extinction));
            imageStore(sourceExtinction, id, historyTexelB(extinction));
            if (media[j]) ++lit;
            if (media[j] && exact[j]) bits |= 1u << uint(j);
        }
    }
    return bits;
}
#endif


void main() {
#ifdef BRUME_LIGHT_EXACT
    uint slot = gl_GlobalInvocationID.x;
    if (slot >= exactList.count) return;
    uint linear = exactFroxels[slot];
    uint plane = uint(frame.froxelDims.x * frame.froxelDims.y);
    ivec3 id = ivec3(int(linear % uint(frame.froxelDims.x)), int((linear % plane) / uint(frame.froxelDims.x)),
                     int(linear / plane));
    lightFroxel(id);
#else
    // The run's first froxel.
    // Workgroups interleaved between lavapipe's threads (balanced_groups.glsl): the deep runs cost
    // little where the frame skips hidden froxels.
    // Over the temporal region (the push constants: the media region and its one-froxel shell): the
    // shell's froxels have no media and get S = sigma_t = 0, which the temporal and integrate passes
    // read there (the frame does not clear these images to 0 first; frame_executor.cpp recordClearMedia).
    // Their light terms are never used (lightBlock stores the emission alone where sigma_t = 0), so the
    // lights and transmittance cells they read need not have been computed for them (gpu_renderer.cpp).
    uvec3 runID = balancedGlobalID();
    ivec3 first = ivec3(runID.xy, int(runID.z) * LIGHT_RUN) + lightRegion.lo.xyz;
    // The run is cut at the column's walk end (column_entries.glsl): the froxels behind are hidden
    // from every lookup, and the temporal pass's neighbourhood leaves them out.
    int end = currentColumnEnd(first.xy);
    if (any(greaterThanEqual(first, ivec3(frame.froxelDims.xy, end)))) return;
    int last = min(first.z + LIGHT_RUN, end) - 1;
    uint lit = 0u;   // froxels of the run with sigma_t > 0
    uint run = 0u;   // bit k: froxel first + k along z needs light exact
    for (int z0 = first.z - first.z % LIGHT_BLOCK; z0 <= last; z0 += LIGHT_BLOCK) {
        uint bits = lightBlock(first.xy, z0, first.z, last, lit);
        run |= z0 >= first.z ? bits << uint(z0 - first.z) : bits >> uint(first.z - z0);
    }
    // The froxels with sigma_t = 0 are counted by the host: every other froxel of the grid.
    if (lit != 0u) atomicAdd(counters.litFroxels, lit);
    if (run != 0u) appendExactRun(first, run);
#endif
}
