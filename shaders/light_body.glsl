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

#ifdef BRUME_LIGHT_EXACT
layout(local_size_x = LIGHT_EXACT_GROUP) in;
#else
layout(local_size_x = LIGHT_GROUP_X, local_size_y = LIGHT_GROUP_Y, local_size_z = 1) in;
#endif

// The sun shadow map's visibility at p for the mapped sun (sun_shadow.glsl), looked up once per
// froxel: only light frame.sunShadowLight - 1 is multiplied by it.
float lightSunVisibility(vec3 p) { return sunShadowFroxelVisibility(frame.sunShadowLight - 1, p); }

// Shadow maps' visibility of light i at p; sun: lightSunVisibility(p).
float lightMapVisibility(int i, vec3 p, float sun) {
    return (i == frame.sunShadowLight - 1 ? sun : 1.0f) * localShadowVisibility(i, p);
}

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

#ifdef BRUME_LIGHT_EXACT
// fog_shadow.glsl froxelFogTransmittance, with the corners of shadowCorners.
vec3 exactFogTransmittance(int light, ShadowLookup k, ShadowCorners c, vec3 p, vec3 toLight, float distance) {
    if (!fogShadowsLight(lightAt(light), localFogShadowsFlag())) return vec3(1.0f);
    vec3 vdb = vdbShadowBlend(light, k);
    ShadowBlend b = blendShadowCorners(light, c, k.weights);
    if (b.trusted) return b.transmittance * vdb;
    return lightFogTransmittance(lightAt(light), p, toLight, distance) * vdb;
}
#else
// The trusted blend of light `light`'s fog transmittance at k (fog_shadow.glsl
// froxelFogTransmittance without its exact fallback); trusted = false where that fallback is needed.
vec3 trustedFogTransmittance(int light, ShadowLookup k, ShadowCorners c, out bool trusted) {
    trusted = true;
    if (!fogShadowsLight(lightAt(light), localFogShadowsFlag())) return vec3(1.0f);
    ShadowBlend b = blendShadowCorners(light, c, k.weights);
    trusted = b.trusted;
    return b.transmittance * vdbShadowBlend(light, k);
}

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
#endif

// S at froxel id, which has media (sigma_t > 0). light.comp: returns whether some light's blend was
// not trusted (the froxel then goes to light exact, which writes S again).
bool lightFroxel(ivec3 id) {
    bool exact = false;
    vec4 scatteringG = imageLoad(mediaScatteringG, id);
    vec3 p = worldFromFroxelCoord(vec3(id) + frame.jitter.xyz, frame);
    vec3 viewDir = normalize(p - frame.cameraPosition.xyz);
    vec3 perSigmaS = frame.ambient.rgb;
    ShadowLookup shadow = shadowLookup(id, frame.froxelDims.xyz, frame.shadowReduction);
    ShadowCorners corners = shadowCorners(shadow);
    float nearest = FROXEL_LIGHT_CLAMP * froxelRadius(id.z, frame);
    HgPhaseTerms phase = hgPhaseTerms(scatteringG.a);
    float sun = lightSunVisibility(p);
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
#ifdef BRUME_LIGHT_EXACT
        perSigmaS += inScatter * exactFogTransmittance(i, shadow, corners, p, ls.toLight, ls.distance) *
                     lightMapVisibility(i, p, sun);
#else
        bool trusted;
        perSigmaS += inScatter * trustedFogTransmittance(i, shadow, corners, trusted) * lightMapVisibility(i, p, sun);
        exact = exact || !trusted;
#endif
    }
    vec3 source = scatteringG.rgb * perSigmaS + imageLoad(mediaEmission, id).rgb;
    imageStore(sourceImage, id, vec4(source, 0.0f));
    return exact;
}

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
    // The run's first froxel; the run is cut at the grid's end.
    ivec3 first = ivec3(gl_GlobalInvocationID.xy, int(gl_GlobalInvocationID.z) * LIGHT_RUN) +
                  ivec3(frame.mediaOriginX, frame.mediaOriginY, frame.mediaOriginZ);
    if (any(greaterThanEqual(first, frame.froxelDims.xyz))) return;
    int last = min(first.z + LIGHT_RUN, frame.froxelDims.z) - 1;
    uint lit = 0u;   // froxels of the run with sigma_t > 0
    uint run = 0u;   // bit k: froxel first + k along z needs light exact
    for (int z = first.z; z <= last; ++z) {
        ivec3 id = ivec3(first.xy, z);
        if (imageLoad(mediaExtinction, id).rgb == vec3(0.0f)) {
            imageStore(sourceImage, id, vec4(imageLoad(mediaEmission, id).rgb, 0.0f));
        } else {
            ++lit;
            if (lightFroxel(id)) run |= 1u << uint(z - first.z);
        }
    }
    // The froxels with sigma_t = 0 are counted by the host: every other froxel of the grid.
    if (lit != 0u) atomicAdd(counters.litFroxels, lit);
    if (run != 0u) appendExactRun(first, run);
#endif
}
