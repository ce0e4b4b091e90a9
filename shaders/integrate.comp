// Pass 3: front to back along each froxel column; entry s holds camera -> far boundary of slice s
// (core: integrateColumn). Slab lengths are measured along the column-centre ray.
// Built with BRUME_TEMPORAL_REST (integrate_rest.comp) for frames whose view rests or that have no
// history: the temporal pass then dispatches nothing, and this pass resolves each froxel with its own
// history first (shared/temporal.h resolveTemporalAtRest, as the temporal pass in motion would not:
// it reads neighbours), writes the result to the history's *_OUT side, and integrates it. One pass over
// the froxels instead of two (docs/performance.md, "voxel"). The later readers of the resolved S and
// sigma_t (glow, debug view, readback) read the *_OUT side, which holds them in motion too, so the
// result is not stored over sourceImage and sourceExtinction as well (docs/performance.md, "media").
// Dispatched over the columns that a reader looks up this frame (gpu/pass_temporal.cpp
// integrateColumns); only those of the temporal region (core/media_region.h temporalFroxelRegion)
// integrate. S and sigma_t are 0 outside it, so a stored entry in front of the
// region, or in a column outside it, holds scattering 0 and transmittance 1, and behind the region each
// column keeps its value at the region's far end. The frame used to clear both volumes over the whole
// grid for that (about 4.4 ms at `high` for 1.4 M froxels, a sixth of a small volume's frame); a column
// outside the region now stores its few read entries itself (docs/performance.md, "integclear").
#version 450
#extension GL_GOOGLE_include_directive : require
#define BRUME_FROXEL_IMAGES
#include "resources.glsl"
#include "distant_table.h"

layout(local_size_x = INTEGRATE_GROUP_X, local_size_y = INTEGRATE_GROUP_Y, local_size_z = 1) in;
// lo.w .. hi.w (inclusive): entries stored in every column: the glow's, or all of them when the
// volumes are read back or a debug view shows a slice (frame_executor.cpp recordIntegrate).
layout(push_constant) uniform IntegrateBlock {
    FroxelRegionParams region;
    ivec4 columns;  // the columns dispatched, [xy, zw)
};

#include "column_entries.glsl"
#include "balanced_groups.glsl"

// Whether entry s of a column whose lookups read `read` is stored.
bool storedEntry(int s, ivec2 read) { return (s >= read.x && s <= read.y) || (s >= region.lo.w && s <= region.hi.w); }

void main() {
    // Workgroups interleaved between lavapipe's threads (balanced_groups.glsl): where the frame skips
    // hidden froxels, the sky's columns walk every slice and the ground's few.
    ivec2 column = columns.xy + ivec2(balancedGlobalID().xy);
    if (any(greaterThanEqual(column, columns.zw))) return;
    bool inRegion = all(greaterThanEqual(column, region.lo.xy)) && all(lessThan(column, region.hi.xy));
    vec2 pixel = (vec2(column) + vec2(0.5f)) * float(frame.froxelDims.w);
    Accumulated acc = emptyAccumulated();
    // sliceRayLength(s, pixel, frame) with each slice boundary's depth evaluated once (a pow on
    // lavapipe): slice s's far boundary is slice s + 1's near one.
    float rayScale = length(viewRayFromPixel(pixel, frame));
    float zNear = sliceBoundaryDepth(region.lo.z, frame);
    // The entries the column's lookups read, and its walk end, as the column ends pass stored them
    // (column_entries.glsl): the froxels behind every stored entry are neither resolved nor integrated;
    // the light pass did not light them.
    ivec2 read = currentColumnEntries(column);
    int end = currentColumnEnd(column);
#ifdef BRUME_TEMPORAL_REST
    // The history the previous frame wrote in this column: a froxel past its walk end holds an older
    // frame's value, from another view, and is not blended (weight 0: this frame's sample alone).
    int written = previousColumnEnd(column);
#endif
    // The stored entries that hold no fog: in front of the region in its columns, every one outside
    // it. Two short loops over the column's read entries and the entries stored everywhere (they may
    // overlap: the same value twice).
    int empty = inRegion ? region.lo.z : frame.froxelDims.z;
    for (int s = read.x; s <= min(read.y, empty - 1); ++s) {
        imageStore(integratedScattering, ivec3(column, s), vec4(0.0f));
        imageStore(integratedTransmittance, ivec3(column, s), vec4(1.0f, 1.0f, 1.0f, 0.0f));
    }
    for (int s = max(region.lo.w, 0); s <= min(region.hi.w, empty - 1); ++s) {
        imageStore(integratedScattering, ivec3(column, s), vec4(0.0f));
        imageStore(integratedTransmittance, ivec3(column, s), vec4(1.0f, 1.0f, 1.0f, 0.0f));
    }
    if (!inRegion) end = region.lo.z;  // no trip of the loops below
    for (int s = region.lo.z; s < min(region.hi.z, end); ++s) {
        ivec3 id = ivec3(column, s);
        float zFar = sliceBoundaryDepth(s + 1, frame);
        float d = (zFar - zNear) * rayScale;
        zNear = zFar;
#ifdef BRUME_TEMPORAL_REST
        vec4 a = imageLoad(historySourceIn, id);
        vec4 b = imageLoad(historyExtinctionIn, id);
        vec4 c = imageLoad(sourceImage, id);
        float weight = s < written ? frame.temporal.x : 0.0f;
        vec4 source = resolveTemporalAtRest(historySourceOf(c), historySourceOf(a), weight);
        vec4 extinction = resolveTemporalAtRest(historyExtinctionOf(c, imageLoad(sourceExtinction, id)),
                                                historyExtinctionOf(a, b), weight);
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
    for (int s = region.hi.z; s < end; ++s) {
        ivec3 id = ivec3(column, s);
        if (storedEntry(s, read)) {
            imageStore(integratedScattering, id, vec4(acc.scattering, 0.0f));
            imageStore(integratedTransmittance, id, vec4(acc.transmittance, 0.0f));
        }
    }
}
