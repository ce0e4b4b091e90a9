// The fog transmittance volume: each shadowing light's transmittance (shadows.h) evaluated exactly
// on a grid that keeps every r-th froxel in each axis (r = FrameUniforms.shadowReduction, per preset), then
// read back by the light pass with trilinear weights. Where the 8 cells around a froxel disagree by
// more than SHADOW_VOLUME_SPREAD (a shadow edge crosses them) and the froxel is not on a cell, the
// interpolation is not trusted and the froxel evaluates its transmittance exactly: smooth regions
// cost 1/r^3 of the closed forms, edges stay exact, and no light leaks through a dense block's
// shadow (docs/shadows.md, "Cost").
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

// a / b (integer quotient) for 0 <= a < SMALL_QUOTIENT_LIMIT and b >= 1, through a float division:
// lavapipe runs an integer division lane by lane (8 scalar divisions per batch), a float one as one
// vector instruction (docs/performance.md, "media"). Exact: (a + 0.5) / b lies at least 0.5 / b from
// an integer, and the division's error (GLSL allows 2.5 ulp: under 1.5e-7 of the quotient a / b) stays
// below that while a < 3.3e6; tests/test_shadows.cpp checks it against the integer division.
BRUME_CONST int SMALL_QUOTIENT_LIMIT = 1 << 20;
BRUME_FUNC int smallQuotient(int a, int b) { return int((float(a) + 0.5f) / float(b)); }

// Cells per axis: enough that the last froxel has a cell at or past it, (dims - 1 + r - 1) / r + 1
// (dims are far below SMALL_QUOTIENT_LIMIT).
BRUME_FUNC ivec3 shadowVolumeDims(ivec3 froxelDims, int r) {
    ivec3 n = froxelDims + ivec3(r - 2);
    return ivec3(smallQuotient(n.x, r), smallQuotient(n.y, r), smallQuotient(n.z, r)) + ivec3(1);
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
// One level along z of a lookup's 8 cells (c<y><x>): their bilinear blend and their min and max.
// The light pass reads each level once for a block of froxels that share it (light_body.glsl).
struct ShadowLevel {
    vec3 blend;
    vec3 lo;
    vec3 hi;
};

BRUME_FUNC ShadowLevel shadowLevel(vec3 c00, vec3 c01, vec3 c10, vec3 c11, vec2 w) {
    ShadowLevel l;
    l.blend = mix(mix(c00, c01, w.x), mix(c10, c11, w.x), w.y);
    l.lo = min(min(c00, c01), min(c10, c11));
    l.hi = max(max(c00, c01), max(c10, c11));
    return l;
}


// Whether a lookup's froxel sits on its lower cell (weight 0 along all three axes: every r-th froxel
// per axis, 1/8 of them at r = 2). Its blend is then that cell's value, and the cell holds the
// exact transmittance at this froxel's own sample point (shadowCellFroxel: the shadow volume pass
// evaluates the same closed form at the same point), so the blend is trusted whatever the other
// cells hold: the exact fallback would compute the same value again. 12.5% of the default scene's
// exact froxels at high were such (docs/performance.md, "light, sixth round").
BRUME_FUNC bool shadowOnCell(vec3 w) { return w.x == 0.0f && w.y == 0.0f && w.z == 0.0f; }

// The blend between a lookup's lower and upper levels (weights w: the levels' own bilinear ones and
// w.z between them), trusted where the 8 cells agree or the froxel is on a cell.
BRUME_FUNC ShadowBlend shadowBlendLevels(ShadowLevel lower, ShadowLevel upper, vec3 w) {
    vec3 spread = max(lower.hi, upper.hi) - min(lower.lo, upper.lo);
    ShadowBlend b;
    b.trusted = max(spread.x, max(spread.y, spread.z)) <= SHADOW_VOLUME_SPREAD || shadowOnCell(w);
    b.transmittance = mix(lower.blend, upper.blend, w.z);
    return b;
}

// The blend of the 8 cells with weights w, trusted where they agree or the froxel is on a cell.
BRUME_FUNC ShadowBlend shadowBlend(vec3 c000, vec3 c001, vec3 c010, vec3 c011, vec3 c100, vec3 c101, vec3 c110,
                                   vec3 c111, vec3 w) {
    return shadowBlendLevels(shadowLevel(c000, c001, c010, c011, vec2(w)), shadowLevel(c100, c101, c110, c111, vec2(w)),
                             w);
}

BRUME_NAMESPACE_END

#endif
