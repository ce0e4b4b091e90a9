// Private to gpu/: what GpuRenderer holds, split over gpu_renderer.cpp (creation, render) and
// frame_executor.cpp (the frame's resources from the tables, command recording, submission).
#pragma once

#include <array>

#include "core/compile.h"
#include "core/local_shadow.h"
#include "core/sun_shadow.h"
#include "core/temporal.h"
#include "frame_resources.h"
#include "geometry_mesh.h"
#include "gpu_renderer.h"
#include "passes.h"
#include "timing.h"

namespace brume::gpu {

// The scene's shader variants (frame_table.h VariantKey); temporalRest is the frame's, left false.
Result<VariantKey> variantOf(const CompiledScene& cs);

// What decides which passes a frame records and which pipelines they use (frame_table.h kPasses).
struct FramePasses {
    VariantKey variant;
    bool debugView = false;        // a debug view replaces the image (When::DebugView)
    bool reuseSurfaces = false;    // the frame keeps the surfaces (When::SurfacesChanged)
    bool readBackVolumes = false;  // voxelize fills the media images for the read-back volumes
    bool spheres = false;          // the geometry has sphere proxies (their own pipelines)
    bool records(const PassDecl& p) const;
    bool dispatches(const PassDecl& p) const;  // recorded, and with a compute pipeline this frame
};

// A call's specialization constants (passes marked specialized), from the scene and the frame alone.
struct FrameKeys {
    SpecKey spec;         // the scene's
    SpecKey froxelSpec;   // spec with the volumes out of the froxels' reach culled (PassDecl::culledVolumes)
    SpecKey surfaceSpec;  // spec with the volumes out of the surfaces' reach culled (the geometry pass)
    // The fallbacks (RenderRequest::pipelineFallbacks): the same image for any volumes in reach and any
    // set of surface lights. The froxel passes take spec (froxelFallback), the geometry pass
    // surfaceFallback: spec reading its surface lights from the light reach list (SPEC_SURFACE_LIGHTS -1).
    SpecKey surfaceFallback;
    bool froxelFallback = false;  // this frame's culled passes take spec
    // The key a pass's pipeline is specialized with (null: none; PassDecl::specialized).
    const SpecKey* of(const PassDecl& p) const {
        return !p.specialized ? nullptr : p.culledVolumes && !froxelFallback ? &froxelSpec : &spec;
    }
    // These keys with both fallbacks taken.
    FrameKeys fallbacks() const {
        FrameKeys k = *this;
        k.froxelFallback = true;
        k.surfaceSpec = surfaceFallback;
        return k;
    }
};

// Declaration order is destruction order reversed: the device outlives everything it owns.
struct GpuRenderer::State {
    std::unique_ptr<Device> device;
    CommandPoolOwner commandPool;
    VkCommandBuffer cmd = VK_NULL_HANDLE;  // freed with the pool
    FenceOwner fence;
    DescriptorBindings bindings;
    GeometryPass geometry;
    PipelineCache pipelines;          // one per shader variant (frame_table.h variantShaderName)
    VariantKey variant;               // this frame's
    FrameKeys keys;                   // this call's specialization keys
    shd::DebugViewParams debugParams{};  // this call's RenderRequest::debugView and debugSlice
    std::vector<shd::GlowParams> glow;   // the glow pass's dispatches, one per glowing light in view
    bool readBackImage = true;           // false: the output stays on the device (renderOnDevice)
    // When::SurfacesChanged passes: this frame keeps their last output (reuseSurfaces), which is
    // valid while surfacesValid (no resource replaced since the frame that wrote it) and was made
    // from surfaceInputs (gpu_renderer.cpp).
    bool reuseSurfaces = false;
    bool surfacesValid = false;
    std::vector<uint8_t> surfaceInputs;
    bool froxelRegions = true;           // GpuOptions::froxelRegions
    bool poisonShadowVolume = false;     // GpuOptions::poisonShadowVolume
    bool poisonIntegrated = false;       // GpuOptions::poisonIntegrated
    bool poisonSource = false;           // GpuOptions::poisonSource
    bool skipHidden = true;              // GpuOptions::skipHiddenFroxels
    // A prepare that failed part-way (out of GPU memory) may have replaced resources without
    // rewriting the descriptors: the next prepare rewrites them all.
    bool descriptorsStale = false;
    SunShadowCache sunShadow;     // the host-built sun shadow map, kept while its inputs do not change
    LocalShadowCache localShadows;  // the host-built point/spot maps, each kept while its inputs do not change
    TemporalState temporalState;  // history bookkeeping, shared with the CPU (core/temporal.h)
    PassTimer timer;
    FrameResources res;
    // The editor interleaves small coarse frames (while the user drags) with full-size ones (at rest):
    // the larger set of sized resources is kept here while a smaller one is in use, so that coming
    // back to rest reuses memory the device has already touched instead of allocating and faulting in
    // hundreds of MiB (parkSizedResources). Only its sized members are used (swapSizedResources).
    FrameResources parked;
    bool allocated = false;  // this render's prepare allocated sized resources (GpuRender::allocated)
    bool compiled = false;   // this render created pipelines (GpuRender::compiled)

    Result<void> createCommands();
    Result<void> createPasses();
    Result<void> ensureBuffer(Buffer& b, VkDeviceSize size, VkBufferUsageFlags usage, Memory memory,
                              const char* name, bool& dirty);
    // what: the buffer's contents in words for the error when a texel view of it could not address them
    // (ensureBuffer checks every buffer that has views; shared/frame_table.h).
    Result<void> ensureBuffer(BufferId id, VkDeviceSize size, bool& dirty, const char* what = nullptr);
    Result<void> parkSizedResources(glm::ivec3 dims, glm::ivec2 size, bool& dirty);
    Result<void> ensureFroxelImages(glm::ivec3 dims, bool media, bool& dirty);
    Result<void> ensureScreenImages(glm::ivec2 size, bool& dirty);
    Result<void> ensureVolumeReadback(glm::ivec3 dims);
    Result<void> ensureTexelViews(bool& dirty);
    Result<void> ensureVdbGrids(const CompiledScene& cs, bool& dirty);
    Result<void> chooseVariant(const CompiledScene& cs);
    Result<void> prepare(glm::ivec2 size, glm::ivec3 dims, const CompiledScene& cs, size_t vertexBytes,
                         int shadowReduction, size_t sunShadowBytes, size_t localShadowBytes, bool readBackVolumes);
    // Adds to `batch` the pipelines such a frame's passes use with these keys and the caches lack.
    void requestPipelines(const FramePasses& passes, const FrameKeys& frameKeys, PipelineBatch& batch);
    // Whether the pipelines such a frame's culled passes (PassDecl::culledVolumes) use with these keys are made.
    bool hasCulledPipelines(const FramePasses& passes, const FrameKeys& frameKeys) const;
    // Whether every pipeline a frame of `passes` records with these keys is made.
    bool hasPipelines(const FramePasses& passes, const FrameKeys& frameKeys) const;
    // RenderRequest::pipelineFallbacks: frameKeys with each fallback taken (FrameKeys::fallbacks: the
    // culled froxel passes', all or none; the geometry pass's) whose own pipelines are missing where
    // the fallback's are made: the same image, no compile. The one rule for the render
    // (takeFallbacks) and for GpuRenderer::hasPipelines.
    FrameKeys withFallbacks(const FramePasses& passes, const FrameKeys& frameKeys) const;
    void takeFallbacks(const FramePasses& passes) { keys = withFallbacks(passes, keys); }
    Result<void> recordFrame(const GeometryMesh& mesh, glm::vec3 ambient, float cameraFar, bool readBackVolumes,
                             int historyWriteIndex);
    // historyWriteIndex: the side holding this frame's resolved S and sigma_t (read back for sourceImage
    // and mediaExtinction).
    void recordReadback(bool readBackVolumes, int historyWriteIndex);
    Result<double> submitAndWait();
};

// The passes' timings plus the readback.
inline constexpr uint32_t kMaxPasses = static_cast<uint32_t>(kPasses.size()) + 1;

}  // namespace brume::gpu
