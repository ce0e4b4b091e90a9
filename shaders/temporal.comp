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

layout(local_size_x = FROXEL_GROUP_X, local_size_y = FROXEL_GROUP_Y, local_size_z = FROXEL_GROUP_Z) in;
layout(push_constant) uniform RegionBlock { FroxelRegionParams region; };

const ivec3 kNeighbours[7] = ivec3[7](ivec3(0, 0, 0), ivec3(-1, 0, 0), ivec3(1, 0, 0), ivec3(0, -1, 0),
                                      ivec3(0, 1, 0), ivec3(0, 0, -1), ivec3(0, 0, 1));

bool inGrid(ivec3 c, ivec3 dims) { return all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, dims)); }

// The froxel's S and sigma_t, each (rgb, 0), from the light pass's two texels (resources.glsl).
void currentAt(ivec3 c, out vec4 source, out vec4 extinction) {
    vec4 a = imageLoad(sourceImage, c);
    source = historySourceOf(a);
    extinction = historyExtinctionOf(a, imageLoad(sourceExtinction, c));
}

// The froxel and its six face neighbours inside the grid: the bounds of S and of sigma_t.
void neighbourhood(ivec3 c, out Bounds source, out Bounds extinction) {
    source = emptyBounds();
    extinction = emptyBounds();
    ivec3 dims = frame.froxelDims.xyz;
    for (int i = 0; i < 7; ++i) {
        ivec3 n = c + kNeighbours[i];
        if (!inGrid(n, dims)) continue;
        vec4 s, e;
        currentAt(n, s, e);
        source = growBounds(source, s);
        extinction = growBounds(extinction, e);
    }
}

// The history read for S and for sigma_t; each corner's two texels (resources.glsl: the layout) are
// loaded once for both.
void readHistory(HistoryTaps k, inout HistorySample source, inout HistorySample extinction) {
    for (int corner = 0; corner < 8; ++corner) {
        ivec3 c = ivec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
        ivec3 at = ivec3(c.x == 1 ? k.hi.x : k.lo.x, c.y == 1 ? k.hi.y : k.lo.y, c.z == 1 ? k.hi.z : k.lo.z);
        vec4 a = imageLoad(historySourceIn, at);
        vec4 b = imageLoad(historyExtinctionIn, at);
        source = addHistoryTap(source, historySourceOf(a), c, k.fractions);
        extinction = addHistoryTap(extinction, historyExtinctionOf(a, b), c, k.fractions);
    }
}

void main() {
    ivec3 id = region.lo.xyz + ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(id, region.hi.xyz))) return;
    HistoryTaps k = historyTaps(id, frame, previousFrame, frame.temporal.x);
    HistorySample histS = emptyHistorySample();
    HistorySample histE = emptyHistorySample();
    if (k.weight > 0.0f) readHistory(k, histS, histE);
    vec4 s, e;
    currentAt(id, s, e);
    Bounds boundsS, boundsE;
    neighbourhood(id, boundsS, boundsE);
    vec4 source = resolveTemporal(s, histS, boundsS, k.weight, true);
    vec4 extinction = resolveTemporal(e, histE, boundsE, k.weight, true);
    imageStore(historySourceOut, id, historyTexelA(source, extinction));
    imageStore(historyExtinctionOut, id, historyTexelB(extinction));
}
