// The buffers and images the passes read and write, recreated only when their sizes change.
//
//   frame (uniform) ---------------------------------------------------------> every pass
//   volumes, lights (storage) -> voxelize -> media* -> light -> source -> integrate -> integrated*
//   previousFrame, history[read] -> temporal (after light) -> history[write] -> source, mediaExtinction
//   geometry (raster) -> sceneColor, sceneDepth ------------------------------> composite -> output
//
// Memory (rgba32f, 16 B per froxel per volume): 6 froxel volumes and 4 history volumes (temporal
// ping-pong pair of S and sigma_t); at 1280x720 High (160x90x96 froxels) that is 10 x 22 MiB =
// 221 MiB, at Ultra (320x180x128) 10 x 113 MiB = 1.1 GiB.
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <memory>
#include <vector>

#include "core/density_grid.h"
#include "resources.h"

namespace brume::gpu {

// One side of the temporal history's ping-pong pair: the resolved S and sigma_t of one frame.
struct HistoryImages {
    GpuImage source;      // rgba32f: resolved rgb S
    GpuImage extinction;  // rgba32f: resolved rgb sigma_t
};

struct FrameResources {
    Buffer frame;     // FrameUniforms
    Buffer volumes;   // VolumeData[], at least one entry
    Buffer lights;    // LightData[], at least one entry
    Buffer counters;  // FroxelCounters, read back by the host
    Buffer vertices;  // GeometryVertex[]
    Buffer previousFrame;  // FrameUniforms of the previous frame (temporal pass)

    glm::ivec3 froxelDims{0};
    GpuImage mediaScatteringG, mediaExtinction, mediaEmission, source, integratedScattering, integratedTransmittance;
    // Kept across frames (unlike the volumes above); recreated with them, then undefined until a
    // first transition (historyUndefined) and unread until a frame has written them.
    std::array<HistoryImages, 2> history;
    bool historyUndefined = true;

    // Fog transmittance volume (shaders/shared/shadow_volume.h): shadowVolumeDims cells per light.
    glm::ivec3 shadowExtent{0};  // cells x, y and z * lights: the shadow volume pass's dispatch
    Buffer shadowTransmittance;  // vec4[], at least one entry
    // Sun shadow map (shaders/shared/sun_shadow.h), ray cast on the host: SunShadowFit + float[N * N].
    Buffer sunShadowMap;
    // Point and spot light shadow maps (shaders/shared/local_shadow.h), ray cast on the host:
    // float[slots * 6 * N * N], 1.5 MiB per mapped light at high (N = 256).
    Buffer localShadowMaps;

    // Every vdb volume's NanoVDB grid back to back (compileScene's order and offsets), sparse as
    // imported: GPU memory is the NanoVDB size plus the occupancy cells. Re-uploaded only when the set of grids changes.
    Buffer vdbGrids;                // uint[], at least 32 bytes
    // The grids it holds, in order; held so that a new grid cannot reuse a freed one's address.
    std::vector<std::shared_ptr<const DensityGrid>> vdbGridsUploaded;
    // Light lists per cluster (shaders/shared/clusters.h), built on the CPU (core/clusters.cpp) and
    // uploaded each frame: 256 B per 8^3 froxels, 720 KiB at 1280x720 High.
    Buffer lightClusters;  // int[]

    glm::ivec2 size{0};
    GpuImage sceneColor;   // rgba32f, colour attachment 0 and storage
    GpuImage sceneDepth;   // r32f view depth, colour attachment 1 and storage
    GpuImage depthBuffer;  // d32, depth test only
    GpuImage output;       // rgba32f storage
    Buffer outputReadback;
};

}  // namespace brume::gpu
