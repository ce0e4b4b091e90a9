// What the GPU froxel renderer's descriptor set holds beyond the shared structs of types.h. The
// bindings themselves are declared once, as data, in frame_table.h. Not used by the CPU.
#ifndef BRUME_SHARED_BINDINGS_H
#define BRUME_SHARED_BINDINGS_H

#include "common.h"

BRUME_NAMESPACE_BEGIN

// Written by the light pass with atomics; 16 bytes in std430.
struct FroxelCounters {
    uint litFroxels;      // froxels with sigma_t > 0
    uint skippedFroxels;  // froxels with sigma_t = 0 (lighting skipped)
    uint pad0;
    uint pad1;
};

BRUME_NAMESPACE_END

#endif
