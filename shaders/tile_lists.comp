// The composite's tile lists (composite_body.glsl): the 8x8 pixel tiles whose pixels all lie within
// the froxel far (their deepest depth, depth_tiles.comp, is not past it) go to nearTiles, those whose
// pixels all lie past it (their shallowest depth, by DISTANT_ALL_FAR_MARGIN) to allFarTiles, the others
// to farTiles, each with its indirect dispatch (one workgroup per tile); but the tiles whose pixels are
// all sky (their shallowest depth is the camera far: distant_table.h isSkyDepth) go to skyTiles. The
// composite runs over the near tiles without the distant fog table's lookup (lavapipe would run it
// under a mask for every pixel), the composite all far with it and one entry of the integrated volume
// (its last: 8 loads, not 16), the composite far with it and both entries, the composite sky with the
// two last entries alone: each pixel computes what a single composite would.
// One invocation per row of tiles: it counts its row's tiles of each list, reserves their slots with
// one atomicAdd per list, then writes them in order. The lists' order across rows depends on which
// row reserves first; the composites do not depend on it (each workgroup is one tile). Only with
// distant fog (SPEC_DISTANT_FOG); else the lists stay as the frame reset them (empty) and the
// composite dispatches over its pixel region. It was one invocation walking every tile: ~0.8 ms at
// 1280x720, one lane of one core (docs/performance.md, "tilerows"). The depth tiles through their texel
// view: lavapipe loads a storage buffer lane by lane (shared/frame_table.h).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "resources.glsl"
#include "distant_table.h"

layout(local_size_x = TILE_LIST_GROUP, local_size_y = 1, local_size_z = 1) in;

// The list of a tile whose depths span `range` (deepest, shallowest): 0 near, 1 far, 2 all far, 3 sky.
struct TileClassifier {
    float froxelFar;
    float allFarFrom;
    bool lastEntryAlone;
    bool skyEntries;
};

int tileList(vec2 range, TileClassifier c) {
    // As the composite's test: a pixel reads the distant fog where its depth is past the froxel far.
    bool isFar = range.x > c.froxelFar;
    bool isSky = c.skyEntries && isSkyDepth(range.y, frame);
    bool isAllFar = !isSky && c.lastEntryAlone && range.y > c.allFarFrom;
    return isSky ? 3 : isAllFar ? 2 : isFar ? 1 : 0;
}

// Reserves n slots of list l (its header: the tile count and one workgroup per tile); the first's index.
uint reserve(int l, uint n) {
    if (l == 0) { atomicAdd(nearTileList.groupsX, n); return atomicAdd(nearTileList.count, n); }
    if (l == 1) { atomicAdd(farTileList.groupsX, n); return atomicAdd(farTileList.count, n); }
    if (l == 2) { atomicAdd(allFarTileList.groupsX, n); return atomicAdd(allFarTileList.count, n); }
    atomicAdd(skyTileList.groupsX, n);
    return atomicAdd(skyTileList.count, n);
}

void main() {
    if (SPEC_DISTANT_FOG == 0) return;
    ivec2 tiles = depthTileCount(frame.counts.xy);
    int row = int(gl_GlobalInvocationID.x);
    if (row >= tiles.y) return;
    TileClassifier c;
    c.froxelFar = frame.froxelRange.y;
    // A pixel past the froxel far by the margin reads the integrated volume's last entry alone, if
    // sliceTFromViewDepth's pow(1, 1 / exponent) is 1 here: asked of the same lookup at twice the far
    // (clamped to 1 the same way), or no tile is all far.
    IntegratedLookup past = integratedLookup(vec2(0.5f), 2.0f * c.froxelFar, frame);
    c.lastEntryAlone = past.entries.x == frame.froxelDims.z - 1 && past.entries.y == past.entries.x;
    c.allFarFrom = c.froxelFar * (1.0f + DISTANT_ALL_FAR_MARGIN);
    // A sky pixel reads the table's last entry: where the froxels end before the camera far.
    c.skyEntries = distantTableEntries(frame) > 0;
    int first = row * tiles.x;
    uvec4 counts = uvec4(0u);
    for (int i = first; i < first + tiles.x; ++i) {
        int l = tileList(texelFetch(depthTileTexels, i).xy, c);
        counts += uvec4(l == 0 ? 1u : 0u, l == 1 ? 1u : 0u, l == 2 ? 1u : 0u, l == 3 ? 1u : 0u);
    }
    uvec4 next = uvec4(reserve(0, counts.x), reserve(1, counts.y), reserve(2, counts.z), reserve(3, counts.w));
    for (int i = first; i < first + tiles.x; ++i) {
        int l = tileList(texelFetch(depthTileTexels, i).xy, c);
        if (l == 3) skyTileIndex[next.w++] = uint(i);
        else if (l == 2) allFarTileIndex[next.z++] = uint(i);
        else if (l == 1) farTileIndex[next.y++] = uint(i);
        else nearTileIndex[next.x++] = uint(i);
    }
}
