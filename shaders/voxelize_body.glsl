// Pass 1 (body of voxelize.comp, voxelize_vdb.comp and their _texture variants): media of every
// volume at each froxel's sample point (core: voxelizeRow). Variants because the inlined PNanoVDB walk
// makes the whole shader ~9x slower on lavapipe (1031 vs 115 ms at 1280x720 high) even when no volume
// takes that branch: scenes without vdb volumes (density textures) run a variant without that branch.
// Dispatched over the froxels that can hold media only (core/media_region.h: frame.mediaOrigin*); the
// frame clears the rest of the grid, and all of mediaEmission when no volume emits (SPEC_EMISSION).
#include "influence.glsl"

layout(local_size_x = FROXEL_GROUP_X, local_size_y = FROXEL_GROUP_Y, local_size_z = FROXEL_GROUP_Z) in;

// Volume i (of kind k: a constant in pipelines specialized with the scene's volume list) at p. The
// volumes come through the texel view volumeTexels (resources.glsl volumeAt: a vector gather on
// lavapipe, where volumes[i] loads lane by lane).
void addVolume(inout MediaSample m, int i, int k, vec3 p) {
    VolumeData v = volumeAt(i);
    if (!insideBounds(v, p)) return;
#ifdef BRUME_VOXELIZE_VDB
    float density = BRUME_VOLUME_KIND_USED(VOLUME_VDB) && k == VOLUME_VDB
                        ? vdbDensity(v, p)
                        : analyticDensityOfKind(k, v, p, frame.cameraPosition.xyz);
#else
    float density = analyticDensityOfKind(k, v, p, frame.cameraPosition.xyz);
#endif
#ifdef BRUME_VOXELIZE_TEXTURE
    if (density > 0.0f) density *= densityTextureFactor(v, p);
#endif
    m = addMedium(m, v, density);
}

MediaSample mediaAt(vec3 p) {
    MediaSample m = emptyMedia();
    if (SPEC_VOLUME_COUNT >= 0) {
        // Unrolled by hand with each volume's kind a constant (fog_shadow.glsl does the same): only that
        // kind's density is built for it; a loop would run every kind's code for every volume.
#define BRUME_LISTED_VOLUME(i) \
    if (BRUME_SPEC_VOLUME_LISTED(i)) \
        addVolume(m, i, BRUME_SPEC_LISTED_KIND(SPEC_VOLUME_LIST, i), p);
        BRUME_EACH_LISTED_VOLUME(BRUME_LISTED_VOLUME)
#undef BRUME_LISTED_VOLUME
    } else {
        for (int i = 0; i < frame.counts.z; ++i) addVolume(m, i, volumeAt(i).kind.x, p);
    }
    return m;
}

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID) + ivec3(frame.mediaOriginX, frame.mediaOriginY, frame.mediaOriginZ);
    if (any(greaterThanEqual(id, frame.froxelDims.xyz))) return;
    vec3 p = worldFromFroxelCoord(vec3(id) + frame.jitter.xyz, frame);
    MediaSample m = mediaAt(p);
    if (SPEC_INFLUENCERS != 0) m = influencedMedia(m, p);
    imageStore(mediaScatteringG, id, vec4(m.sigmaS, mediaPhaseG(m)));
    imageStore(mediaExtinction, id, vec4(m.sigmaT, 0.0f));
    // No volume emits (SPEC_EMISSION 0): the frame clears mediaEmission instead (frame_executor.cpp
    // recordClearMedia), a memset where this store runs lane by lane (docs/performance.md, "media").
    if (SPEC_EMISSION != 0) imageStore(mediaEmission, id, vec4(m.emission, 0.0f));
}
