// Trilinear sampling of a sparse voxel grid in index space, written once for the CPU (NanoVDB) and
// the GPU (PNanoVDB): each side fetches the 8 voxel values of vdbCell(...) its own way and mixes them
// with vdbTrilinear. Voxel (i, j, k) holds the value at index point (i, j, k) (OpenVDB's convention).
#ifndef BRUME_SHARED_VDB_H
#define BRUME_SHARED_VDB_H

#include "types.h"

BRUME_NAMESPACE_BEGIN

struct VdbCell {
    ivec3 base;  // the lower corner voxel
    vec3 frac;   // position inside the cell, in [0, 1)
};

// Index-space position of a world position (VolumeData.localFromWorld is gridIndexFromWorld for vdb).
BRUME_FUNC vec3 vdbIndexPos(VolumeData v, vec3 worldPos) { return vec3(v.localFromWorld * vec4(worldPos, 1.0f)); }

BRUME_FUNC VdbCell vdbCell(vec3 indexPos) {
    VdbCell c;
    vec3 f = floor(indexPos);
    c.base = ivec3(f);
    c.frac = indexPos - f;
    return c;
}

// lo: values at z = base.z, (x, y) corners 00, 10, 01, 11; hi: the same at z = base.z + 1.
BRUME_FUNC float vdbTrilinear(vec4 lo, vec4 hi, vec3 frac) {
    vec4 z = mix(lo, hi, frac.z);
    float y0 = mix(z.x, z.y, frac.x);
    float y1 = mix(z.z, z.w, frac.x);
    return mix(y0, y1, frac.y);
}

// Occupancy culling (docs/vdb.md): at import each grid gets a coarse grid of cells of 8^3 voxels (one
// NanoVDB leaf), appended to its NanoVDB buffer at byte offset VolumeData.kind.w (0 = none): a header
// of VDB_OCCUPANCY_HEADER_WORDS ints (origin cell xyz, pad, dims xyz, pad), then one uint per cell,
// x fastest, non-zero where any voxel of [8c, 8c + 8]^3 is non-zero. Cell c holds the trilinear
// lower corners 8c..8c+7, whose 8 taps reach 8c+8: where its word is 0 every tap is 0, so skipping
// the tree walk there changes nothing.
BRUME_CONST int VDB_OCCUPANCY_SHIFT = 3;
BRUME_CONST int VDB_OCCUPANCY_HEADER_WORDS = 8;

// Index (after the header) of the cell holding trilinear lower corner `base`; -1 outside the cells.
BRUME_FUNC int vdbOccupancyWord(ivec3 base, ivec3 originCell, ivec3 dims) {
    ivec3 c = (base >> VDB_OCCUPANCY_SHIFT) - originCell;  // arithmetic shift: floor division by 8
    if (any(lessThan(c, ivec3(0))) || any(greaterThanEqual(c, dims))) return -1;
    return (c.z * dims.y + c.y) * dims.x + c.x;
}

BRUME_NAMESPACE_END

#endif
