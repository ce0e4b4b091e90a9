// Pass 1 (body of voxelize.comp, voxelize_vdb.comp and their _texture variants): media of every
// volume at each froxel's sample point (core: voxelizeRow). Variants because the inlined PNanoVDB walk
// makes the whole shader ~9x slower on lavapipe (1031 vs 115 ms at 1280x720 high) even when no volume
// takes that branch: scenes without vdb volumes (density textures) run a variant without that branch.
// Dispatched over the froxels that can hold media only (core/media_region.h: frame.mediaOrigin*); the
// frame clears the rest of the grid.
#include "influence.glsl"

layout(local_size_x = FROXEL_GROUP_X, local_size_y = FROXEL_GROUP_Y, local_size_z = FROXEL_GROUP_Z) in;

MediaSample mediaAt(vec3 p) {
    MediaSample m = emptyMedia();
    for (int i = 0; i < frame.counts.z; ++i) {
        if (!insideBounds(volumes[i], p)) continue;
#ifdef BRUME_VOXELIZE_VDB
        float density = volumes[i].kind.x == VOLUME_VDB ? vdbDensity(volumes[i], p)
                                                        : analyticDensity(volumes[i], p, frame.cameraPosition.xyz);
#else
        float density = analyticDensity(volumes[i], p, frame.cameraPosition.xyz);
#endif
#ifdef BRUME_VOXELIZE_TEXTURE
        if (density > 0.0f) density *= densityTextureFactor(volumes[i], p);
#endif
        m = addMedium(m, volumes[i], density);
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
    imageStore(mediaEmission, id, vec4(m.emission, 0.0f));
}
