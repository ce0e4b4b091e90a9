// Clustered light culling (shaders/shared/clusters.h has the layout and limits; docs/gpu.md
// "Light clusters"): per cluster of froxels, the lights whose range window and spot cone can reach
// one of its froxels' sample points and some volume's bounds (elsewhere a light's term is 0). Conservative and cheap: a light is listed when its range
// sphere meets the axis-aligned box around the cluster's corners and its cone meets the sphere
// around that box; directional lights are listed everywhere; lights with fog_scale 0 or no
// intensity nowhere. Both froxel renderers' light passes loop over these lists only.
#pragma once

#include <vector>

#include "compile.h"

namespace brume {

struct LightClusters {
    glm::ivec3 dims{0};      // clusters (shd::clusterDims of the froxel grid)
    std::vector<int> records;  // dims.x * dims.y * dims.z records of shd::CLUSTER_STRIDE ints
    size_t overfullClusters = 0;  // clusters reached by more than CLUSTER_MAX_LIGHTS lights
};

// The clusters of `frame`'s froxel grid; independent of the frame's jitter (the cluster bounds hold
// every sample point of its froxels). culling = false marks every cluster CLUSTER_ALL_LIGHTS (the
// unculled loop, for comparisons).
LightClusters buildLightClusters(const CompiledScene& cs, const shd::FrameUniforms& frame, bool culling = true);

// Whether light l can reach a point in the box [lo, hi] (the test buildLightClusters uses).
bool lightMayReachBox(const shd::LightData& l, glm::vec3 lo, glm::vec3 hi);

}  // namespace brume
