// The voxelize pass's workgroup (voxelize_body.glsl; Dispatch::MediaFroxels in gpu/frame_executor.cpp).
// Lavapipe runs a workgroup as 8-wide batches along x only (ceil(local_size_x / 8) batches per row,
// the rest of a batch masked): at x = 4 every batch computed 8 lanes for 4 froxels. 8 x 2 x 4 fills
// every batch (docs/performance.md, "froxel, round 7").
#ifndef BRUME_SHARED_VOXELIZE_H
#define BRUME_SHARED_VOXELIZE_H

#include "common.h"

BRUME_NAMESPACE_BEGIN

BRUME_CONST int VOXELIZE_GROUP_X = 8;
BRUME_CONST int VOXELIZE_GROUP_Y = 2;
BRUME_CONST int VOXELIZE_GROUP_Z = 4;

BRUME_NAMESPACE_END

#endif
