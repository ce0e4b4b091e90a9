// The fog transmittance volume: each shadowing light's transmittance (shadows.h) evaluated exactly
// on a grid that keeps every r-th froxel in each axis (r = FrameUniforms.shadowReduction, per preset), then
// read back by the light pass with trilinear weights. Where the 8 cells around a froxel disagree by
// more than SHADOW_VOLUME_SPREAD (a shadow edge crosses them), the interpolation is not trusted and
// the froxel evaluates its transmittance exactly: smooth regions cost 1/r^3 of the closed forms,
// edges stay exact, and no light leaks through a dense block's shadow (docs/shadows.md, "Cost").
//
// Cell c of axis a samples froxel min(c * r, dims - 1) at the frame's jitter, so every cell sits on
// a froxel's own sample point: at r = 1 the volume is the exact transmittance, and so is every
// froxel whose coordinates are multiples of r.
#ifndef BRUME_SHARED_SHADOW_VOLUME_H
#define BRUME_SHARED_SHADOW_VOLUME_H

#include "froxel.h"
#include "shadows.h"

BRUME_NAMESPACE_BEGIN

// Largest difference (any channel) between the 8 cells' transmittances that is interpolated.
BRUME_CONST float SHADOW_VOLUME_SPREAD = 0.05f;

// Cells per axis: enough that the last froxel has a cell at or past it.
BRUME_FUNC ivec3 shadowVolumeDims(ivec3 froxelDims, int r) {
    return (froxelDims - ivec3(1) + ivec3(r - 1)) / r + ivec3(1);
}

// The froxel whose sample point cell c holds.
BRUME_FUNC ivec3 shadowCellFroxel(ivec3 cell, ivec3 froxelDims, int r) {
    return min(cell * r, froxelDims - ivec3(1));
}

// Entry of cell c of light `light`: the lights' grids follow one another, each z-major like the
// froxel volumes (the CPU's vector and the GPU's storage buffer alike).
BRUME_FUNC int shadowVolumeIndex(ivec3 cells, int light, ivec3 c) {
    return ((light * cells.z + c.z) * cells.y + c.y) * cells.x + c.x;
}

// Where a point reads the volume; the same for every light, so computed once per froxel or surface
// point (integer division is scalar on a CPU's SIMD lanes: lavapipe pays for each one).
struct ShadowLookup {
    ivec3 cells;   // shadowVolumeDims
    ivec3 cell;    // lower corner
    ivec3 upper;   // upper corner: cell + 1, clamped to the volume (its weight is then 0)
    vec3 weights;  // trilinear weights toward the upper corner, in [0, 1]
};

BRUME_FUNC ShadowLookup shadowLookup(ivec3 froxel, ivec3 froxelDims, int r) {
    ShadowLookup k;
    k.cells = shadowVolumeDims(froxelDims, r);
    k.cell = froxel / r;
    k.upper = min(k.cell + ivec3(1), k.cells - ivec3(1));
    ivec3 lo = k.cell * r;
    ivec3 hi = min(lo + ivec3(r), froxelDims - ivec3(1));
    vec3 span = vec3(max(hi - lo, ivec3(1)));
    k.weights = vec3(froxel - lo) / span;
    return k;
}

struct SurfaceShadowLookup {
    ShadowLookup k;
    bool inside;  // false: outside the grid's sample points (past the froxel far, at the borders):
                  // the caller evaluates exactly
};

// The lookup of a point at continuous froxel coordinates `coord` (froxel.h froxelCoordFromWorld(...).xyz).
BRUME_FUNC SurfaceShadowLookup shadowLookupAt(vec3 coord, FrameUniforms f, int r) {
    ivec3 dims = ivec3(f.froxelDims);
    vec3 u = coord - vec3(f.jitter);  // in froxel indices: froxel i's sample point is at u = i
    SurfaceShadowLookup s;
    s.inside = all(greaterThanEqual(u, vec3(0.0f))) && all(lessThanEqual(u, vec3(dims - ivec3(1))));
    ivec3 base = min(ivec3(max(u, vec3(0.0f))), dims - ivec3(1));
    s.k.cells = shadowVolumeDims(dims, r);
    s.k.cell = base / r;
    s.k.upper = min(s.k.cell + ivec3(1), s.k.cells - ivec3(1));
    ivec3 lo = s.k.cell * r;
    ivec3 hi = min(lo + ivec3(r), dims - ivec3(1));
    s.k.weights = clamp((u - vec3(lo)) / vec3(max(hi - lo, ivec3(1))), vec3(0.0f), vec3(1.0f));
    return s;
}

struct ShadowBlend {
    vec3 transmittance;  // trilinear blend of the 8 cells
    bool trusted;        // false: the cells disagree, evaluate exactly
};

// c<z><y><x>: c000 is the lower corner, c001 one step along x, c111 the upper corner.
BRUME_FUNC ShadowBlend shadowBlend(vec3 c000, vec3 c001, vec3 c010, vec3 c011, vec3 c100, vec3 c101, vec3 c110,
                                   vec3 c111, vec3 w) {
    vec3 lo = min(min(min(c000, c001), min(c010, c011)), min(min(c100, c101), min(c110, c111)));
    vec3 hi = max(max(max(c000, c001), max(c010, c011)), max(max(c100, c101), max(c110, c111)));
    vec3 spread = hi - lo;
    ShadowBlend b;
    b.trusted = max(spread.x, max(spread.y, spread.z)) <= SHADOW_VOLUME_SPREAD;
    vec3 y0 = mix(mix(c000, c001, w.x), mix(c010, c011, w.x), w.y);
    vec3 y1 = mix(mix(c100, c101, w.x), mix(c110, c111, w.x), w.y);
    b.transmittance = mix(y0, y1, w.z);
    return b;
}

BRUME_NAMESPACE_END

#endif
