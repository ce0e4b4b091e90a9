// Which entries of a froxel column some lookup reads, and how deep a frame walks the column for them:
// integrate.comp stores only those entries, and the light, temporal and integrate passes compute no
// froxel deeper (docs/temporal.md, "Hidden froxels"). columnEntryRange and columnWalkEnd read the
// depth tiles (depth_tiles.comp) and the push constants' lo.w .. hi.w (the entries stored in every
// column: the glow's, or all of them; pass_temporal.cpp storedEverywhere): the column ends pass calls
// them once per column, and the other passes read its result (columnEnd).

// The entries of `column` that the composite's lookups can read (shd::integratedLookup): a pixel reads
// the columns around its centre, so column c serves the pixels within a column of its own, those of
// [(c - 0.5) T, (c + 1.5) T) for T pixels a column, and the last column the image's edge beyond; with
// a column of margin, [(c - 1) T, (c + 2) T). Their depths are within the depth tiles' (depth_tiles.comp)
// shallowest and deepest, whose entries integratedEntryRange gives. The entries no lookup reads are not
// stored: at 1280x720 `high` most of a column lies in front of its surfaces or behind them, and a store
// costs lavapipe a loop per word and lane (docs/performance.md, "keep").
#include "distant_table.h"

ivec2 columnEntryRange(ivec2 column) {
    ivec2 size = frame.counts.xy;
    int px = frame.froxelDims.w;
    ivec2 lo = max((column - ivec2(1)) * px, ivec2(0));
    ivec2 hi = min((column + ivec2(2)) * px - ivec2(1), size - ivec2(1));
    if (column.x == frame.froxelDims.x - 1) hi.x = size.x - 1;
    if (column.y == frame.froxelDims.y - 1) hi.y = size.y - 1;
    ivec2 tiles = depthTileCount(size);
    ivec2 t0 = lo / DISTANT_TILE_PX;
    ivec2 t1 = hi / DISTANT_TILE_PX;
    float deepest = 0.0f;
    float shallowest = BRUME_HUGE;
    for (int ty = t0.y; ty <= t1.y; ++ty)
        for (int tx = t0.x; tx <= t1.x; ++tx) {
            // Through the texel view: lavapipe loads a storage buffer lane by lane (shared/frame_table.h).
            vec2 range = texelFetch(depthTileTexels, depthTileIndex(tiles, ivec2(tx, ty))).xy;
            deepest = max(deepest, range.x);
            shallowest = min(shallowest, range.y);
        }
    return integratedEntryRange(shallowest, deepest, frame);
}

// The froxels of a column this frame computes, [0, end): where the frame skips hidden froxels
// (temporalSkipsHidden) those up to the deepest stored entry, `read` (columnEntryRange) or the push
// constants' everywhere-entries `everywhereLast` (hi.w), whichever is deeper; else all of them. Entry
// s integrates froxels 0 .. s, so no stored entry needs a froxel past it. The read-back volumes and the
// debug views store every entry, hence compute every froxel.
int columnWalkEnd(ivec2 read, int everywhereLast) {
    int all = frame.froxelDims.z;
    return temporalSkipsHidden(frame.temporal) ? min(max(read.y, everywhereLast) + 1, all) : all;
}

// What the column ends pass stored (xy: columnEntryRange, z: columnWalkEnd): this frame's (half
// frame.temporal.w of columnEnd) and the previous frame's walk end (the other half), which says which
// froxels of the history the previous frame wrote: the others hold older values, from another view,
// and are not read.
int columnEndIndex(ivec2 column, int side) {
    ivec3 d = frame.froxelDims.xyz;
    return (side * d.y + column.y) * d.x + column.x;
}
// Read through the texel view columnEndTexels: lavapipe loads a storage buffer lane by lane, a texel
// view through its vector gather (shared/frame_table.h).
ivec2 currentColumnEntries(ivec2 column) { return texelFetch(columnEndTexels, columnEndIndex(column, int(frame.temporal.w))).xy; }
int currentColumnEnd(ivec2 column) { return texelFetch(columnEndTexels, columnEndIndex(column, int(frame.temporal.w))).z; }
int previousColumnEnd(ivec2 column) { return texelFetch(columnEndTexels, columnEndIndex(column, 1 - int(frame.temporal.w))).z; }

// How many cells along z of the fog transmittance volume's cell column c this frame's froxels read
// (the shadow volume pass computes no deeper one). A froxel reads the cells around it on each axis,
// floor(x / r) and the next (shared/shadow_volume.h shadowLookup), so cell column c serves the froxel
// columns [(c - 1) r, (c + 1) r), and cell z the froxels from (z - 1) r on: with `deepest` the largest
// walk end of those columns, the cells [0, (deepest - 1) / r + 2). When the frame computes every froxel
// (walk end = all slices) that is every cell of the column.
int shadowCellEnd(ivec2 c, int r, int cells) {
    ivec2 lo = max((c - ivec2(1)) * r, ivec2(0));
    ivec2 hi = min((c + ivec2(1)) * r, frame.froxelDims.xy);
    int deepest = 0;
    for (int y = lo.y; y < hi.y; ++y)
        for (int x = lo.x; x < hi.x; ++x) deepest = max(deepest, currentColumnEnd(ivec2(x, y)));
    return deepest > 0 ? min((deepest - 1) / r + 2, cells) : 0;
}
