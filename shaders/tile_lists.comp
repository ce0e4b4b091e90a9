// The composite's tile lists (composite_body.glsl): the 8x8 pixel tiles whose pixels all lie within
// the froxel far (their deepest depth, depth_tiles.comp, is not past it) go to nearTiles, the others to
// farTiles, each with its indirect dispatch (one workgroup per tile). The composite runs over the near
// tiles without the distant fog table's lookup (lavapipe would run it under a mask for every pixel),
// the composite far over the others with it: each pixel computes what the single composite computed.
// One invocation walks the tiles in order: no atomics, the same lists every time, and a few tens of
// thousands of trips cost well under a millisecond. Only with distant fog (SPEC_DISTANT_FOG); else
// the lists stay as the frame reset them (empty) and the composite dispatches over its pixel region.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "resources.glsl"
#include "distant_table.h"

layout(local_size_x = 1, local_size_y = 1, local_size_z = 1) in;

void main() {
    if (SPEC_DISTANT_FOG == 0) return;
    ivec2 tiles = depthTileCount(frame.counts.xy);
    int count = tiles.x * tiles.y;
    float froxelFar = frame.froxelRange.y;
    uint near = 0u;
    uint far = 0u;
    for (int i = 0; i < count; ++i) {
        // As the composite's test: a pixel reads the distant fog where its depth is past the froxel far.
        bool isFar = depthTileMax[i] > froxelFar;
        if (isFar) farTileIndex[far] = uint(i);
        else nearTileIndex[near] = uint(i);
        far += isFar ? 1u : 0u;
        near += isFar ? 0u : 1u;
    }
    nearTileList = ExactListHeader(near, 1u, 1u, near);
    farTileList = ExactListHeader(far, 1u, 1u, far);
}
