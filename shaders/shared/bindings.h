// What the GPU froxel renderer's descriptor set holds beyond the shared structs of types.h. The
// bindings themselves are declared once, as data, in frame_table.h. Not used by the CPU.
#ifndef BRUME_SHARED_BINDINGS_H
#define BRUME_SHARED_BINDINGS_H

#include "common.h"
#include "types.h"

BRUME_NAMESPACE_BEGIN

// Written by the light pass with atomics (one per run of froxels); 16 bytes in std430. The froxels
// with sigma_t = 0 (lighting skipped) are the grid's others: the host counts them.
struct FroxelCounters {
    uint litFroxels;  // froxels with sigma_t > 0
    uint pad0;
    uint pad1;
    uint pad2;
};

// The light pass's list of froxels that need the exact fog transmittance (light_body.glsl): this
// header, then one uint per froxel (x + X (y + Y z)). groupsX..Z are the indirect dispatch of the
// second light pass (VkDispatchIndirectCommand); the frame starts them at (0, 1, 1) and count at 0.
struct ExactListHeader {
    uint groupsX;
    uint groupsY;
    uint groupsZ;
    uint count;
};
// The r32i texels of an ExactListHeader: a tile list's texel view (frame_table.h nearTileTexels) holds its
// tiles from this texel on.
BRUME_CONST int TILE_LIST_HEADER_TEXELS = 4;
// The tile lists pass: one invocation per row of 8x8 pixel tiles, this many rows per workgroup (one
// 8-wide batch on lavapipe).
BRUME_CONST int TILE_LIST_GROUP = 8;
// Invocations per workgroup of the exact light pass (one per listed froxel).
BRUME_CONST int LIGHT_EXACT_GROUP = 64;
// The light pass: one invocation per run of LIGHT_RUN froxels along z (at most 32: the run's exact
// froxels are the bits of a uint), LIGHT_GROUP_X x LIGHT_GROUP_Y runs per workgroup.
BRUME_CONST int LIGHT_RUN = 32;
// Froxels along z that light_body.glsl lightBlock computes together (one cluster's light list, each
// light's fetch and its transmittance cells shared); its 5 cell levels are written for 4.
BRUME_CONST int LIGHT_BLOCK = 4;
BRUME_CONST int LIGHT_GROUP_X = 8;
BRUME_CONST int LIGHT_GROUP_Y = 8;
// The temporal pass in motion: one invocation per run of TEMPORAL_RUN froxels along z of the temporal
// region, TEMPORAL_GROUP_X x TEMPORAL_GROUP_Y runs per workgroup. Its loop ends at the column's walk
// end (shaders/column_entries.glsl): lavapipe leaves a loop once no lane of its 8 still runs it, where
// an early return costs the whole body under a mask.
BRUME_CONST int TEMPORAL_RUN = 16;
BRUME_CONST int TEMPORAL_GROUP_X = 8;
BRUME_CONST int TEMPORAL_GROUP_Y = 8;
// The shadow volume pass: one invocation per run of SHADOW_RUN cells along z of a layer's region,
// FROXEL_GROUP_X x FROXEL_GROUP_Y x FROXEL_GROUP_Z runs per workgroup. Without vdb grids its loop ends
// at the deepest cell a lit froxel reads (shaders/column_entries.glsl shadowCellEnd). Runs of 8 at
// `low` measured the same (docs/performance.md, "shadowskip").
BRUME_CONST int SHADOW_RUN = 16;

// The geometry pass's surface lights (core/light_reach.h LightReach::surfaceLights, in that order) as a
// uniform buffer (frame_table.h surfaceLights), written once per render call. A pipeline specialized
// with SPEC_SURFACE_LIGHTS (at most SURFACE_LIGHT_SLOTS lights) unrolls its light loop over these slots:
// each slot's loads have a constant offset, which lavapipe makes one scalar load each, where the
// texel view's fetches through the reach list were vector gathers (docs/performance.md, "surfacelights").
BRUME_CONST int SURFACE_LIGHT_SLOTS = 8;
struct SurfaceLights {
    LightData light[SURFACE_LIGHT_SLOTS];  // slot s: lights[index[s].x]
    ivec4 index[SURFACE_LIGHT_SLOTS];      // x: the light's index in lights[]; yzw unused
};

// The temporal and integrate passes' push constants: the froxels they compute, [lo, hi) per axis
// (core/media_region.h temporalFroxelRegion; w unused). The rest of the grid is known without them:
// the frame clears it, or the integrate pass stores it (gpu/pass_temporal.cpp). The shadow volume
// pass's: the cells it computes in one listed light's layer (core/media_region.h shadowCellRegion),
// the light in lo.w; the others are never read.
struct FroxelRegionParams {
    ivec4 lo;
    ivec4 hi;
};

// The integrate pass's: the temporal region (lo.w .. hi.w: the entries stored in every column), and
// the columns it runs over, [columns.xy, columns.zw): those some reader looks up this frame
// (gpu/pass_temporal.cpp integrateColumns).
struct IntegrateParams {
    FroxelRegionParams region;
    ivec4 columns;
};

BRUME_NAMESPACE_END

#endif
