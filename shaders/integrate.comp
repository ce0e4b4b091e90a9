// Pass 3: front to back along each froxel column; entry s holds camera -> far boundary of slice s
// (core: integrateColumn). Slab lengths are measured along the column-centre ray.
// Built with BRUME_TEMPORAL_REST (integrate_rest.comp) for frames whose view rests or that have no
// history: the temporal pass then dispatches nothing, and this pass resolves each froxel with its own
// history first (shared/temporal.h resolveTemporalAtRest, as the temporal pass in motion would not:
// it reads neighbours), writes the result to the history's *_OUT side, and integrates it. One pass over
// the froxels instead of two (docs/performance.md, "voxel"). The later readers of the resolved S and
// sigma_t (glow, debug view, readback) read the *_OUT side, which holds them in motion too, so the
// result is not stored over sourceImage and sourceExtinction as well (docs/performance.md, "media").
// Dispatched over the columns of the temporal region only (region.lo.xy + invocation; core/
// media_region.h temporalFroxelRegion): S and sigma_t are 0 outside it, so the frame clears the
// integrated volumes to scattering 0 and transmittance 1 first (in front of the region and in the
// columns outside it), and behind the region each column keeps its value at the region's far end.
#version 450
#extension GL_GOOGLE_include_directive : require
#define BRUME_FROXEL_IMAGES
#include "resources.glsl"
#include "distant_table.h"

layout(local_size_x = INTEGRATE_GROUP_X, local_size_y = INTEGRATE_GROUP_Y, local_size_z = 1) in;
// lo.w .. hi.w (inclusive): entries stored in every column: the glow's, or all of them when the
// volumes are read back or a debug view shows a slice (frame_executor.cpp recordIntegrate).
layout(push_constant) uniform RegionBlock { FroxelRegionParams region; };

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

// Whether entry s of a column whose lookups read `read` is stored.
bool storedEntry(int s, ivec2 read) { return (s >= read.x && s <= read.y) || (s >= region.lo.w && s <= region.hi.w); }

void main() {
    ivec2 column = region.lo.xy + ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(column, region.hi.xy))) return;
    vec2 pixel = (vec2(column) + vec2(0.5f)) * float(frame.froxelDims.w);
    Accumulated acc = emptyAccumulated();
    // sliceRayLength(s, pixel, frame) with each slice boundary's depth evaluated once (a pow on
    // lavapipe): slice s's far boundary is slice s + 1's near one.
    float rayScale = length(viewRayFromPixel(pixel, frame));
    float zNear = sliceBoundaryDepth(region.lo.z, frame);
    ivec2 read = columnEntryRange(column);
    for (int s = region.lo.z; s < region.hi.z; ++s) {
        ivec3 id = ivec3(column, s);
        float zFar = sliceBoundaryDepth(s + 1, frame);
        float d = (zFar - zNear) * rayScale;
        zNear = zFar;
#ifdef BRUME_TEMPORAL_REST
        vec4 a = imageLoad(historySourceIn, id);
        vec4 b = imageLoad(historyExtinctionIn, id);
        vec4 c = imageLoad(sourceImage, id);
        vec4 source = resolveTemporalAtRest(historySourceOf(c), historySourceOf(a), frame.temporal.x);
        vec4 extinction = resolveTemporalAtRest(historyExtinctionOf(c, imageLoad(sourceExtinction, id)),
                                                historyExtinctionOf(a, b), frame.temporal.x);
        imageStore(historySourceOut, id, historyTexelA(source, extinction));
        imageStore(historyExtinctionOut, id, historyTexelB(extinction));
        acc = accumulateSlab(acc, source.rgb, extinction.rgb, d);
#else
        // In motion the temporal pass wrote the resolved S and sigma_t to the history's *_OUT side.
        vec4 a = imageLoad(historySourceOut, id);
        acc = accumulateSlab(acc, a.rgb, historyExtinctionOf(a, imageLoad(historyExtinctionOut, id)).rgb, d);
#endif
        if (storedEntry(s, read)) {
            imageStore(integratedScattering, id, vec4(acc.scattering, 0.0f));
            imageStore(integratedTransmittance, id, vec4(acc.transmittance, 0.0f));
        }
    }
    for (int s = region.hi.z; s < frame.froxelDims.z; ++s) {
        ivec3 id = ivec3(column, s);
        if (storedEntry(s, read)) {
            imageStore(integratedScattering, id, vec4(acc.scattering, 0.0f));
            imageStore(integratedTransmittance, id, vec4(acc.transmittance, 0.0f));
        }
    }
}
