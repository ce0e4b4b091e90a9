// The deepest and the shallowest view depth of each 8x8 pixel tile of the scene depth (shared/
// distant_table.h depthTileIndex): the integrate pass stores only the entries of each column that the
// depths of its pixels can read (integrate.comp; docs/performance.md, "keep"); with distant fog, the
// distant fog pass takes each table corner's deepest pixel from its (at most 4) tiles instead of
// reading its 16x16 pixels itself (every pixel read once instead of 4 times), and the tile lists pass
// sorts the tiles for the composite by both (docs/performance.md, "pixel" and "allfar").
#version 450
#extension GL_GOOGLE_include_directive : require
#define BRUME_FROXEL_IMAGES
#include "resources.glsl"
#include "distant_table.h"

layout(local_size_x = SCREEN_GROUP_X, local_size_y = SCREEN_GROUP_Y, local_size_z = 1) in;

void main() {
    ivec2 tiles = depthTileCount(frame.counts.xy);
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(t, tiles))) return;
    ivec2 first = t * DISTANT_TILE_PX;
    ivec2 last = frame.counts.xy - 1;
    // Fixed trip counts (unrolled), the coordinates held at the image's last row and column: a tile cut
    // by the edge reads its edge pixels again, which leaves the maximum and the minimum as they are.
    float deepest = 0.0f;
    float shallowest = BRUME_HUGE;
    for (int y = 0; y < DISTANT_TILE_PX; ++y)
        for (int x = 0; x < DISTANT_TILE_PX; ++x) {
            float depth = imageLoad(sceneDepth, min(first + ivec2(x, y), last)).r;
            deepest = max(deepest, depth);
            shallowest = min(shallowest, depth);
        }
    depthTileRange[depthTileIndex(tiles, t)] = vec2(deepest, shallowest);
}
