// Private to gpu/: what GpuRenderer holds, split over gpu_renderer.cpp (creation, render) and
// gpu_frame.cpp (resources that follow the frame size, command recording, submission).
#pragma once

#include <array>

#include "core/compile.h"
#include "core/local_shadow.h"
#include "core/sun_shadow.h"
#include "core/temporal.h"
#include "frame_resources.h"
#include "gpu_renderer.h"
#include "passes.h"
#include "timing.h"

namespace brume::gpu {

inline constexpr VkFormat kVolumeFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
inline constexpr uint32_t kMaxPasses = 9;
// TRANSFER_DST: the temporal pass copies its result over source and mediaExtinction.
inline constexpr VkImageUsageFlags kVolumeUsage =
    VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;

// Declaration order is destruction order reversed: the device outlives everything it owns.
struct GpuRenderer::State {
    std::unique_ptr<Device> device;
    CommandPoolOwner commandPool;
    VkCommandBuffer cmd = VK_NULL_HANDLE;  // freed with the pool
    FenceOwner fence;
    DescriptorBindings bindings;
    GeometryPass geometry;
    ComputePass voxelize, voxelizeVdb, shadowVolume, shadowVolumeVdb, light, integrate, composite;
    ComputePass temporal;
    // Density texture variants of voxelize, created when a scene first needs them (vdb_grids.cpp);
    // index: the scene has vdb volumes (0/1).
    std::array<ComputePass, 2> voxelizeTexture;
    bool frameHasVdbVolumes = false, frameHasTextures = false;  // this frame's voxelize variant
    // The vdb passes compiled for quantized grids (shaders/vdb_sample.glsl), created when a scene
    // first needs them; first index: encoding Fp16 (0) or Fp8 (1); voxelize's second: density textures.
    std::array<std::array<ComputePass, 2>, 2> voxelizeVdbQuantized;
    std::array<ComputePass, 2> shadowVolumeVdbQuantized;
    VdbEncoding frameVdbEncoding = VdbEncoding::Float;  // of every vdb volume this frame
    ComputePass debugView;
    shd::DebugViewParams debugParams{};  // this call's RenderRequest::debugView and debugSlice
    bool readBackImage = true;           // false: the output stays on the device (renderOnDevice)
    SunShadowCache sunShadow;     // the host-built sun shadow map, kept while its inputs do not change
    LocalShadowCache localShadows;  // the host-built point/spot maps, each kept while its inputs do not change
    TemporalState temporalState;  // history bookkeeping, shared with the CPU (core/temporal.h)
    PassTimer timer;
    FrameResources res;
    std::array<Buffer, 6> volumeReadback;

    Result<void> createCommands();
    Result<void> createPasses();
    Result<void> ensureBuffer(Buffer& b, VkDeviceSize size, VkBufferUsageFlags usage, Memory memory,
                              const char* name, bool& dirty);
    Result<void> ensureFroxelImages(glm::ivec3 dims, bool& dirty);
    Result<void> ensureScreenImages(glm::ivec2 size, bool& dirty);
    Result<void> ensureVolumeReadback(glm::ivec3 dims);
    Result<void> ensureVdbGrids(const CompiledScene& cs, bool& dirty);
    Result<void> chooseVoxelizeVariant(const CompiledScene& cs);
    Result<void> chooseVdbEncoding(const CompiledScene& cs);
    const ComputePass& voxelizeVariant() const;
    const ComputePass& shadowVolumeVariant() const;
    Result<void> prepare(glm::ivec2 size, glm::ivec3 dims, const CompiledScene& cs, size_t vertexBytes,
                         int shadowReduction, size_t sunShadowBytes, size_t localShadowBytes);
    void recordFrame(uint32_t vertexCount, glm::vec3 ambient, float cameraFar, bool readBackVolumes,
                     int historyWriteIndex);
    void recordReadback(bool readBackVolumes);
    Result<double> submitAndWait();
};


}  // namespace brume::gpu
