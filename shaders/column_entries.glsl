// Which entries of a froxel column some lookup reads, and how deep a frame must walk the column
// for them: integrate.comp stores only those entries, and a frame that skips hidden froxels
// (frame.temporal.z, shared/temporal.h temporalSkipsHidden) lights and resolves nothing deeper.
// Reads the depth tiles (depth_tiles.comp) and the push constants' lo.w .. hi.w (the entries stored
// in every column: the glow's, or all of them; frame_executor.cpp storedEverywhere).

// The entries of `column` that the composite's lookups can read (shd::integratedLookup): a pixel reads
// the columns around its centre, so column c serves the pixels within a column of its own, those of
// [(c - 0.5) T, (c + 1.5) T) for T pixels a column, and the last column the image's edge beyond; with
// a column of margin, [(c - 1) T, (c + 2) T). Their depths are within the depth tiles' (depth_tiles.comp)
// shallowest and deepest, whose entries integratedEntryRange gives. The entries no lookup reads are not
// stored: at 1280x720 `high` most of a column lies in front of its surfaces or behind them, and a store
// costs lavapipe a loop per word and lane (docs/performance.md, "keep").
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
            vec2 range = depthTileRange[depthTileIndex(tiles, ivec2(tx, ty))];
            deepest = max(deepest, range.x);
            shallowest = min(shallowest, range.y);
        }
    return integratedEntryRange(shallowest, deepest, frame);
}

// The froxels of a column this frame computes, [0, end): all of them, or where the frame skips hidden
// froxels (at rest, temporalSkipsHidden) those up to the deepest stored entry, `read` (columnEntryRange)
// or the push constants' everywhere-entries `everywhereLast` (hi.w), whichever is deeper. Entry s
// integrates froxels 0 .. s, so no stored entry needs a froxel past it; the froxels behind are never
// lit or resolved at rest, and keep the values of the two full frames that began the rest
// (docs/temporal.md, "Hidden froxels at rest").
int columnWalkEnd(ivec2 read, int everywhereLast) {
    int all = frame.froxelDims.z;
    return temporalSkipsHidden(frame.temporal) ? min(max(read.y, everywhereLast) + 1, all) : all;
}
