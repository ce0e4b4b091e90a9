// The composite's tile lists (composite_body.glsl): the 8x8 pixel tiles whose pixels all lie within
// the froxel far (their deepest depth, depth_tiles.comp, is not past it) go to nearTiles, those whose
// pixels all lie past it (their shallowest depth, by DISTANT_ALL_FAR_MARGIN) to allFarTiles, the others
// to farTiles, each with its indirect dispatch (one workgroup per tile); but the tiles whose pixels are
// all sky (their shallowest depth is the camera far: distant_table.h isSkyDepth) go to skyTiles. The
// composite runs over the near tiles without the distant fog table's lookup (lavapipe would run it
// under a mask for every pixel), the composite all far with it and one entry of the integrated volume
// (its last: 8 loads, not 16), the composite far with it and both entries, the composite sky with the
// two last entries alone: each pixel computes what a single composite would.
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
    // A pixel past the froxel far by the margin reads the integrated volume's last entry alone, if
    // sliceTFromViewDepth's pow(1, 1 / exponent) is 1 here: asked of the same lookup at twice the far
    // (clamped to 1 the same way), or no tile is all far.
    IntegratedLookup past = integratedLookup(vec2(0.5f), 2.0f * froxelFar, frame);
    bool lastEntryAlone = past.entries.x == frame.froxelDims.z - 1 && past.entries.y == past.entries.x;
    float allFarFrom = froxelFar * (1.0f + DISTANT_ALL_FAR_MARGIN);
    uint near = 0u;
    uint far = 0u;
    uint allFar = 0u;
    uint sky = 0u;
    // A sky pixel reads the table's last entry: where the froxels end before the camera far.
    bool skyEntries = distantTableEntries(frame) > 0;
    for (int i = 0; i < count; ++i) {
        // As the composite's test: a pixel reads the distant fog where its depth is past the froxel far.
        vec2 range = depthTileRange[i];
        bool isFar = range.x > froxelFar;
        bool isSky = skyEntries && isSkyDepth(range.y, frame);
        bool isAllFar = !isSky && lastEntryAlone && range.y > allFarFrom;
        if (isSky) skyTileIndex[sky] = uint(i);
        else if (isAllFar) allFarTileIndex[allFar] = uint(i);
        else if (isFar) farTileIndex[far] = uint(i);
        else nearTileIndex[near] = uint(i);
        sky += isSky ? 1u : 0u;
        allFar += isAllFar ? 1u : 0u;
        far += isFar && !isAllFar && !isSky ? 1u : 0u;
        near += isFar ? 0u : 1u;
    }
    nearTileList = ExactListHeader(near, 1u, 1u, near);
    farTileList = ExactListHeader(far, 1u, 1u, far);
    allFarTileList = ExactListHeader(allFar, 1u, 1u, allFar);
    skyTileList = ExactListHeader(sky, 1u, 1u, sky);
}
