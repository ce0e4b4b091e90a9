// The deepest view depth of each 8x8 pixel tile of the scene depth (shared/distant_table.h
// depthTileIndex), for the distant fog pass: each table corner takes the deepest of its (at most 4)
// tiles instead of reading its 16x16 pixels itself, so every pixel is read once instead of 4 times
// (docs/performance.md, "pixel"). Written only when the distant fog pass reads it (more than
// DISTANT_TABLE_SCAN_FROM entries); otherwise the loops run no trip.
#version 450
#extension GL_GOOGLE_include_directive : require
#define BRUME_FROXEL_IMAGES
#include "resources.glsl"
#include "distant_table.h"

layout(local_size_x = SCREEN_GROUP_X, local_size_y = SCREEN_GROUP_Y, local_size_z = 1) in;

void main() {
    // SPEC_DISTANT_FOG 0: no distant fog pass reads the tiles.
    if (SPEC_DISTANT_FOG == 0) return;
    ivec2 tiles = depthTileCount(frame.counts.xy);
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(t, tiles))) return;
    ivec2 first = t * DISTANT_TILE_PX;
    // Rows and columns to read: none when the table has too few entries to be scanned.
    ivec2 extent = distantTableEntries(frame) > DISTANT_TABLE_SCAN_FROM
                       ? min(first + DISTANT_TILE_PX, frame.counts.xy) - first
                       : ivec2(0);
    float deepest = 0.0f;
    for (int y = 0; y < extent.y; ++y)
        for (int x = 0; x < extent.x; ++x) deepest = max(deepest, imageLoad(sceneDepth, first + ivec2(x, y)).r);
    depthTileMax[depthTileIndex(tiles, t)] = deepest;
}
