// The buffers and images the passes read and write, recreated only when their sizes change.
//
//   frame (uniform) ---------------------------------------------------------> every pass
//   volumes, lights (storage) -> voxelize -> media* -> light -> source -> integrate -> integrated*
//   geometry (raster) -> sceneColor, sceneDepth ------------------------------> composite -> output
//
// Memory (rgba32f, 16 B per froxel per volume): 6 froxel volumes; at 1280x720 High
// (160x90x96 froxels) that is 6 x 22 MiB = 133 MiB, at Ultra (320x180x128) 6 x 113 MiB = 675 MiB.
#pragma once

#include <glm/glm.hpp>

#include "resources.h"

namespace brume::gpu {

struct FrameResources {
    Buffer frame;     // FrameUniforms
    Buffer volumes;   // VolumeData[], at least one entry
    Buffer lights;    // LightData[], at least one entry
    Buffer counters;  // FroxelCounters, read back by the host
    Buffer vertices;  // GeometryVertex[]

    glm::ivec3 froxelDims{0};
    GpuImage mediaScatteringG, mediaExtinction, mediaEmission, source, integratedScattering, integratedTransmittance;

    // Fog transmittance volume (shaders/shared/shadow_volume.h): shadowVolumeDims cells per light.
    glm::ivec3 shadowExtent{0};  // cells x, y and z * lights: the shadow volume pass's dispatch
    Buffer shadowTransmittance;  // vec4[], at least one entry

    glm::ivec2 size{0};
    GpuImage sceneColor;   // rgba32f, colour attachment 0 and storage
    GpuImage sceneDepth;   // r32f view depth, colour attachment 1 and storage
    GpuImage depthBuffer;  // d32, depth test only
    GpuImage output;       // rgba32f storage
    Buffer outputReadback;
};

}  // namespace brume::gpu
