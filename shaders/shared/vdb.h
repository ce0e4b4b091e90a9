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

BRUME_NAMESPACE_END

#endif
