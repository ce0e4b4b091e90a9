// Temporal pass, between light and integrate (core: temporalPassCpu): each froxel's source S and
// extinction sigma_t are blended with last frame's resolved values by the rule written in
// shared/temporal.h. Dispatched over the temporal region only (region.lo + invocation; core/
// media_region.h temporalFroxelRegion): outside it S and sigma_t are 0 and the history was cleared.
// In motion the history is reprojected, clamped to the current neighbourhood and checked for NaN/Inf;
// the result goes to the history pair's *_OUT images, where integrate, glow, debug view and readback
// read it (this pass reads sourceImage's and sourceExtinction's neighbours, so it cannot write them).
// Frames whose view rests or that have no history dispatch nothing here: integrate_rest.comp resolves
// each froxel with its own history as it integrates (integrate.comp).
#version 450
#extension GL_GOOGLE_include_directive : require
#define BRUME_FROXEL_IMAGES
#include "resources.glsl"
#include "column_entries.glsl"

layout(local_size_x = TEMPORAL_GROUP_X, local_size_y = TEMPORAL_GROUP_Y, local_size_z = 1) in;
layout(push_constant) uniform RegionBlock { FroxelRegionParams region; };
#include "balanced_groups.glsl"

const ivec3 kNeighbours[7] = ivec3[7](ivec3(0, 0, 0), ivec3(-1, 0, 0), ivec3(1, 0, 0), ivec3(0, -1, 0),
                                      ivec3(0, 1, 0), ivec3(0, 0, -1), ivec3(0, 0, 1));

bool inGrid(ivec3 c, ivec3 dims) { return all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, dims)); }

// The froxel's S and sigma_t, each (rgb, 0), from the light pass's two texels (resources.glsl).
void currentAt(ivec3 c, out vec4 source, out vec4 extinction) {
    vec4 a = imageLoad(sourceImage, c);
    source = historySourceOf(a);
    extinction = historyExtinctionOf(a, imageLoad(sourceExtinction, c));
}

// The froxel and its six face neighbours inside the grid that this frame lit: the bounds of S and of
// sigma_t. ends: the walk ends of the froxel's column (x) and of the columns at x - 1, x + 1, y - 1,
// y + 1 (yzw and the fifth): a neighbour past its column's end was not lit this frame, and holds an
// older frame's value (column_entries.glsl).
void neighbourhood(ivec3 c, int own, ivec4 sides, out Bounds source, out Bounds extinction) {
    source = emptyBounds();
    extinction = emptyBounds();
    ivec3 dims = frame.froxelDims.xyz;
    for (int i = 0; i < 7; ++i) {
        ivec3 n = c + kNeighbours[i];
        if (!inGrid(n, dims)) continue;
        int end = i >= 1 && i <= 4 ? sides[i - 1] : own;
        if (n.z >= end) continue;
        vec4 s, e;
        currentAt(n, s, e);
        source = growBounds(source, s);
        extinction = growBounds(extinction, e);
    }
}

// The history read for S and for sigma_t; each corner's two texels (resources.glsl: the layout) are
// loaded once for both. A corner past its column's walk end last frame (previousColumnEnd) was not
// written then and holds an older frame's value: it counts as non-finite, so the taps that were
// written share its weight (addHistoryTap), as at a NaN.
void readHistory(HistoryTaps k, inout HistorySample source, inout HistorySample extinction) {
    ivec4 ends = ivec4(previousColumnEnd(k.lo.xy), previousColumnEnd(ivec2(k.hi.x, k.lo.y)),
                       previousColumnEnd(ivec2(k.lo.x, k.hi.y)), previousColumnEnd(k.hi.xy));
    for (int corner = 0; corner < 8; ++corner) {
        ivec3 c = ivec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
        ivec3 at = ivec3(c.x == 1 ? k.hi.x : k.lo.x, c.y == 1 ? k.hi.y : k.lo.y, c.z == 1 ? k.hi.z : k.lo.z);
        if (at.z >= ends[c.x + 2 * c.y]) continue;
        vec4 a = imageLoad(historySourceIn, at);
        vec4 b = imageLoad(historyExtinctionIn, at);
        source = addHistoryTap(source, historySourceOf(a), c, k.fractions);
        extinction = addHistoryTap(extinction, historyExtinctionOf(a, b), c, k.fractions);
    }
}

void resolveFroxel(ivec3 id, int own, ivec4 sides) {
    HistoryTaps k = historyTaps(id, frame, previousFrame, frame.temporal.x);
    HistorySample histS = emptyHistorySample();
    HistorySample histE = emptyHistorySample();
    if (k.weight > 0.0f) readHistory(k, histS, histE);
    vec4 s, e;
    currentAt(id, s, e);
    Bounds boundsS, boundsE;
    neighbourhood(id, own, sides, boundsS, boundsE);
    vec4 source = resolveTemporal(s, histS, boundsS, k.weight, true);
    vec4 extinction = resolveTemporal(e, histE, boundsE, k.weight, true);
    imageStore(historySourceOut, id, historyTexelA(source, extinction));
    imageStore(historyExtinctionOut, id, historyTexelB(extinction));
}

void main() {
    // Workgroups interleaved between lavapipe's threads (balanced_groups.glsl): the deep runs of the
    // ground's columns are skipped, the sky's are not.
    uvec3 run = balancedGlobalID();
    ivec3 first = region.lo.xyz + ivec3(run.xy, int(run.z) * TEMPORAL_RUN);
    if (any(greaterThanEqual(first, region.hi.xyz))) return;
    // Behind the column's walk end no lookup reads a froxel (column_entries.glsl): not resolved, its
    // history side not written (the next frame's readHistory knows).
    int own = currentColumnEnd(first.xy);
    ivec2 last = frame.froxelDims.xy - ivec2(1);
    ivec4 sides = ivec4(currentColumnEnd(max(first.xy - ivec2(1, 0), ivec2(0))),
                        currentColumnEnd(min(first.xy + ivec2(1, 0), last)),
                        currentColumnEnd(max(first.xy - ivec2(0, 1), ivec2(0))),
                        currentColumnEnd(min(first.xy + ivec2(0, 1), last)));
    int end = min(min(first.z + TEMPORAL_RUN, region.hi.z), own);
    for (int z = first.z; z < end; ++z) resolveFroxel(ivec3(first.xy, z), own, sides);
}
