// Pass 1 (body of voxelize.comp, voxelize_vdb.comp and their _texture variants): media of every
// volume at each froxel's sample point (core: voxelizeRow). Variants because the inlined PNanoVDB walk
// makes the whole shader ~9x slower on lavapipe (1031 vs 115 ms at 1280x720 high) even when no volume
// takes that branch: scenes without vdb volumes (density textures) run a variant without that branch.
// Dispatched over the froxels that can hold media only (core/media_region.h: frame.mediaOrigin*); the
// frame clears the rest of the grid, and all of mediaEmission when no volume emits (SPEC_EMISSION),
// where a later pass reads them. Without vdb volumes only for the read-back volumes: the light passes
// and the glow compute the media themselves (media_at.glsl; gpu/frame_table.h VariantKey::inlineMedia).
#include "media_at.glsl"

layout(local_size_x = FROXEL_GROUP_X, local_size_y = FROXEL_GROUP_Y, local_size_z = FROXEL_GROUP_Z) in;

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID) + ivec3(frame.mediaOriginX, frame.mediaOriginY, frame.mediaOriginZ);
    if (any(greaterThanEqual(id, frame.froxelDims.xyz))) return;
    vec3 p = worldFromFroxelCoord(vec3(id) + frame.jitter.xyz, frame);
    MediaSample m = froxelMediaAt(p);
    imageStore(mediaScatteringG, id, vec4(m.sigmaS, mediaPhaseG(m)));
    imageStore(mediaExtinction, id, vec4(m.sigmaT, 0.0f));
    // No volume emits (SPEC_EMISSION 0): no pass reads mediaEmission; the frame clears it for the
    // read-back volumes (frame_executor.cpp recordClearMedia), a memset where this store runs lane by
    // lane (docs/performance.md, "media").
    if (SPEC_EMISSION != 0) imageStore(mediaEmission, id, vec4(m.emission, 0.0f));
}
