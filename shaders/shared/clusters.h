// Clustered light culling (docs/gpu.md "Light clusters"): the froxel grid is cut into clusters of
// CLUSTER_FROXELS^3 froxels; each holds the lights whose range window and spot cone can reach it
// (core/clusters.cpp builds the lists on the CPU once per frame; the GPU reads an upload of them).
// Layout, one record of CLUSTER_STRIDE ints per cluster, x fastest, then y, then slices:
//   [0] count n (or CLUSTER_ALL_LIGHTS), [1..n] light indices in increasing order.
#ifndef BRUME_SHARED_CLUSTERS_H
#define BRUME_SHARED_CLUSTERS_H

#include "common.h"

BRUME_NAMESPACE_BEGIN

// 8^3 froxels per cluster: 2880 clusters (720 KiB) at 1280x720 High, and culling is still fine
// enough that a light whose range covers a few metres touches a few clusters only.
BRUME_CONST int CLUSTER_FROXELS = 8;
// Lights listed per cluster at most. A cluster that more lights reach is marked
// CLUSTER_ALL_LIGHTS: its froxels loop over every light (same image, no culling there) and the
// renderers report it (FroxelVolumes::overfullClusters), which brume render prints as a warning.
BRUME_CONST int CLUSTER_MAX_LIGHTS = 63;
BRUME_CONST int CLUSTER_STRIDE = CLUSTER_MAX_LIGHTS + 1;  // 256 bytes per cluster
BRUME_CONST int CLUSTER_ALL_LIGHTS = -1;

BRUME_FUNC ivec3 clusterDims(ivec3 froxelDims) {
    return (froxelDims + ivec3(CLUSTER_FROXELS - 1)) / CLUSTER_FROXELS;
}

// Offset of the record of the cluster holding froxel `froxel`, in ints.
BRUME_FUNC int clusterRecord(ivec3 froxel, ivec3 froxelDims) {
    ivec3 c = froxel / CLUSTER_FROXELS;
    ivec3 d = clusterDims(froxelDims);
    return ((c.z * d.y + c.y) * d.x + c.x) * CLUSTER_STRIDE;
}

// After the cluster records, the frame's surface lights (core/light_reach.h lightReachRecord), 1 +
// lights ints: [0] n, [1..n] their indices, directional ones first, each group ascending (the geometry
// and distant fog passes' loops). The transmittance layers and the glowing lights stay on the host,
// which dispatches the shadow volume pass per layer and the glow pass per light.
BRUME_FUNC int lightReachOffset(ivec3 froxelDims) {
    ivec3 d = clusterDims(froxelDims);
    return d.x * d.y * d.z * CLUSTER_STRIDE;
}

BRUME_NAMESPACE_END

#endif
