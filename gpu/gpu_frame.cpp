// GpuRenderer's per-frame work: resources that follow the frame's sizes (dirty tracking), the
// command buffer of one frame and its submission.
#include <chrono>

#include "renderer_state.h"
#include "shaders/shared/bindings.h"
#include "shaders/shared/brume.h"
#include "vk_check.h"

namespace brume::gpu {
namespace {

VkExtent3D extentOf(glm::ivec3 d) {
    return {static_cast<uint32_t>(d.x), static_cast<uint32_t>(d.y), static_cast<uint32_t>(d.z)};
}

int clusterCount(glm::ivec3 froxelDims) {
    const glm::ivec3 c = shd::clusterDims(froxelDims);
    return c.x * c.y * c.z;
}

std::array<const GpuImage*, 6> froxelImages(const FrameResources& r) {
    return {&r.mediaScatteringG, &r.mediaExtinction, &r.mediaEmission, &r.source, &r.integratedScattering,
            &r.integratedTransmittance};
}

void transition(VkCommandBuffer cmd, const std::vector<VkImage>& images, VkImageLayout from, VkImageLayout to,
                VkPipelineStageFlags srcStage, VkAccessFlags srcAccess, VkPipelineStageFlags dstStage,
                VkAccessFlags dstAccess) {
    std::vector<VkImageMemoryBarrier> barriers;
    for (VkImage img : images) {
        VkImageMemoryBarrier b = vkStruct<VkImageMemoryBarrier>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER);
        b.srcAccessMask = srcAccess;
        b.dstAccessMask = dstAccess;
        b.oldLayout = from;
        b.newLayout = to;
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = img;
        b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        barriers.push_back(b);
    }
    vkCmdPipelineBarrier(cmd, srcStage, dstStage, 0, 0, nullptr, 0, nullptr, static_cast<uint32_t>(barriers.size()),
                         barriers.data());
}

void copyImageToBuffer(VkCommandBuffer cmd, const GpuImage& img, const Buffer& buf) {
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = img.extent;
    vkCmdCopyImageToBuffer(cmd, img.image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buf.buffer.get(), 1, &region);
}

}  // namespace

Result<void> GpuRenderer::State::ensureBuffer(Buffer& b, VkDeviceSize size, VkBufferUsageFlags usage, Memory memory,
                                              const char* name, bool& dirty) {
    if (b.buffer && b.size >= size) return {};
    // Grow geometrically so that scenes gaining objects one by one (the editor) rarely reallocate.
    const VkDeviceSize capacity = std::max(size, b.size * 2);
    b = Buffer{};
    Result<Buffer> nb = createBuffer(*device, capacity, usage, memory, name);
    if (!nb) return nb.error();
    b = std::move(nb.value());
    dirty = true;
    return {};
}

Result<void> GpuRenderer::State::ensureFroxelImages(glm::ivec3 dims, bool& dirty) {
    if (res.froxelDims == dims) return {};
    static constexpr std::array<const char*, 6> names{"mediaScatteringG", "mediaExtinction", "mediaEmission",
                                                      "source", "integratedScattering", "integratedTransmittance"};
    std::array<GpuImage*, 6> images{&res.mediaScatteringG, &res.mediaExtinction, &res.mediaEmission, &res.source,
                                 &res.integratedScattering, &res.integratedTransmittance};
    res.froxelDims = glm::ivec3(0);
    for (size_t i = 0; i < images.size(); ++i) {
        *images[i] = GpuImage{};  // release before allocating: peak memory stays one set of volumes
        Result<GpuImage> img = createImage(*device, extentOf(dims), true, kVolumeFormat, kVolumeUsage, names[i]);
        if (!img) return img.error();
        *images[i] = std::move(img.value());
    }
    static constexpr std::array<std::array<const char*, 2>, 2> historyNames{
        {{"history source 0", "history extinction 0"}, {"history source 1", "history extinction 1"}}};
    for (size_t i = 0; i < res.history.size(); ++i) {
        for (int k = 0; k < 2; ++k) {
            GpuImage& slot = k == 0 ? res.history[i].source : res.history[i].extinction;
            slot = GpuImage{};
            Result<GpuImage> img =
                createImage(*device, extentOf(dims), true, kVolumeFormat, kVolumeUsage, historyNames[i][static_cast<size_t>(k)]);
            if (!img) return img.error();
            slot = std::move(img.value());
        }
    }
    res.historyUndefined = true;
    res.froxelDims = dims;
    dirty = true;
    return {};
}

Result<void> GpuRenderer::State::ensureScreenImages(glm::ivec2 size, bool& dirty) {
    if (res.size == size) return {};
    const VkExtent3D e{static_cast<uint32_t>(size.x), static_cast<uint32_t>(size.y), 1};
    const VkImageUsageFlags target = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT;
    res.size = glm::ivec2(0);
    for (GpuImage* img : {&res.sceneColor, &res.sceneDepth, &res.depthBuffer, &res.output}) *img = GpuImage{};
    struct Spec { GpuImage* img; VkFormat format; VkImageUsageFlags usage; const char* name; };
    for (const Spec& s : {Spec{&res.sceneColor, kVolumeFormat, target, "sceneColor"},
                          Spec{&res.sceneDepth, VK_FORMAT_R32_SFLOAT, target, "sceneDepth"},
                          Spec{&res.depthBuffer, VK_FORMAT_D32_SFLOAT, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                               "depthBuffer"},
                          Spec{&res.output, kVolumeFormat, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                               "output"}}) {
        Result<GpuImage> img = createImage(*device, e, false, s.format, s.usage, s.name);
        if (!img) return img.error();
        *s.img = std::move(img.value());
    }
    res.outputReadback = Buffer{};
    Result<Buffer> rb = createBuffer(*device, static_cast<VkDeviceSize>(size.x) * static_cast<VkDeviceSize>(size.y) * 16,
                                     VK_BUFFER_USAGE_TRANSFER_DST_BIT, Memory::Readback, "output readback");
    if (!rb) return rb.error();
    res.outputReadback = std::move(rb.value());
    res.size = size;
    BRUME_TRY(geometry.attach(*device, res));
    dirty = true;
    return {};
}

Result<void> GpuRenderer::State::ensureVolumeReadback(glm::ivec3 dims) {
    const VkDeviceSize bytes = static_cast<VkDeviceSize>(dims.x) * static_cast<VkDeviceSize>(dims.y) *
                               static_cast<VkDeviceSize>(dims.z) * sizeof(glm::vec4);
    for (Buffer& b : volumeReadback) {
        bool unused = false;
        BRUME_TRY(ensureBuffer(b, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, Memory::Readback, "volume readback", unused));
    }
    return {};
}

Result<void> GpuRenderer::State::prepare(glm::ivec2 size, glm::ivec3 dims, const CompiledScene& cs,
                                         size_t vertexBytes, int shadowReduction, size_t sunShadowBytes,
                                         size_t localShadowBytes) {
    bool dirty = false;
    const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    BRUME_TRY(ensureBuffer(res.frame, sizeof(shd::FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, Memory::Upload,
                           "frame uniforms", dirty));
    BRUME_TRY(ensureBuffer(res.counters, sizeof(shd::FroxelCounters),
                           storage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, Memory::Readback, "froxel counters", dirty));
    // Storage buffers cannot be empty: keep room for at least one record.
    BRUME_TRY(ensureBuffer(res.volumes, std::max<size_t>(cs.volumes.size(), 1) * sizeof(shd::VolumeData), storage,
                           Memory::Upload, "volumes", dirty));
    BRUME_TRY(ensureBuffer(res.lights, std::max<size_t>(cs.lights.size(), 1) * sizeof(shd::LightData), storage,
                           Memory::Upload, "lights", dirty));
    BRUME_TRY(ensureBuffer(res.previousFrame, sizeof(shd::FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                           Memory::Upload, "previous frame uniforms", dirty));
    bool vertexDirty = false;
    BRUME_TRY(ensureBuffer(res.vertices, std::max<size_t>(vertexBytes, 64), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
                           Memory::Upload, "geometry vertices", vertexDirty));
    BRUME_TRY(ensureFroxelImages(dims, dirty));
    BRUME_TRY(ensureScreenImages(size, dirty));
    const glm::ivec3 cells = shd::shadowVolumeDims(dims, shadowReduction);
    res.shadowExtent = {cells.x, cells.y, cells.z * static_cast<int>(cs.lights.size())};
    // Scenes with vdb grids keep room for each light's vdb layer (shared/vdb_shadow.h) after the
    // analytic ones, whether or not this frame's request fills it.
    bool anyGrid = false;
    for (const DensityGridPtr& g : cs.grids) anyGrid = anyGrid || g != nullptr;
    const size_t entries = static_cast<size_t>(cells.x) * static_cast<size_t>(cells.y) * static_cast<size_t>(cells.z) *
                           std::max<size_t>(cs.lights.size(), 1) * (anyGrid ? 2 : 1);
    BRUME_TRY(ensureBuffer(res.shadowTransmittance, entries * sizeof(glm::vec4), storage, Memory::DeviceLocal,
                           "shadow transmittance", dirty));
    BRUME_TRY(ensureVdbGrids(cs, dirty));
    BRUME_TRY(chooseVoxelizeVariant(cs));
    // The light reach record follows the clusters (shared/clusters.h lightReachOffset).
    const size_t clusterInts = static_cast<size_t>(shd::CLUSTER_STRIDE) * static_cast<size_t>(clusterCount(dims)) + 2 +
                               2 * cs.lights.size();
    BRUME_TRY(ensureBuffer(res.lightClusters, clusterInts * sizeof(int), storage, Memory::Upload, "light clusters",
                           dirty));
    BRUME_TRY(ensureBuffer(res.sunShadowMap, sizeof(shd::SunShadowFit) + std::max<size_t>(sunShadowBytes, 4), storage,
                           Memory::Upload, "sun shadow map", dirty));
    BRUME_TRY(ensureBuffer(res.localShadowMaps, std::max<size_t>(localShadowBytes, 4), storage, Memory::Upload,
                           "local shadow maps", dirty));
    if (dirty) writeDescriptorBindings(*device, bindings.set, res);
    return {};
}

void GpuRenderer::State::recordFrame(uint32_t vertexCount, glm::vec3 ambient, float cameraFar, bool readBackVolumes,
                                     int historyWriteIndex) {
    timer.reset(cmd);
    vkCmdFillBuffer(cmd, res.counters.buffer.get(), 0, VK_WHOLE_SIZE, 0);
    std::vector<VkImage> storageImages{res.output.image.get()};
    for (const GpuImage* img : froxelImages(res)) storageImages.push_back(img->image.get());
    // Contents are rewritten every frame, so the old layout and contents are discarded; the
    // previous frame finished before its fence was signalled, so nothing earlier needs waiting for.
    transition(cmd, storageImages, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
               VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
               VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    // Last frame's temporal pass wrote the history this frame reads (and overwrites the other half).
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                  VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    // The history outlives frames: only freshly created images start from UNDEFINED (a frame
    // without history does not read them, see temporal.comp).
    if (res.historyUndefined) {
        std::vector<VkImage> history;
        for (const HistoryImages& h : res.history) history.insert(history.end(), {h.source.image.get(), h.extinction.image.get()});
        transition(cmd, history, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0,
                   VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
        res.historyUndefined = false;
    }
    // The light pass counts into the cleared counters with atomics.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                  VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);

    // First: the light pass and the surfaces of the geometry pass read it.
    timer.begin(cmd, "shadow volume");
    recordShadowVolume(cmd, shadowVolumeVariant(), bindings, res.shadowExtent);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    timer.end(cmd);

    timer.begin(cmd, "geometry");
    geometry.record(cmd, bindings, res, vertexCount, ambient, cameraFar);
    timer.end(cmd);

    timer.begin(cmd, "voxelize");
    recordVoxelize(cmd, voxelizeVariant(), bindings, res.froxelDims);
    timer.end(cmd);
    timer.begin(cmd, "light");
    computeToComputeBarrier(cmd);
    recordLight(cmd, light, bindings, res.froxelDims);
    timer.end(cmd);
    timer.begin(cmd, "temporal");
    computeToComputeBarrier(cmd);
    recordTemporal(cmd, temporal, bindings, res, historyWriteIndex);
    timer.end(cmd);
    timer.begin(cmd, "integrate");
    computeToComputeBarrier(cmd);
    recordIntegrate(cmd, integrate, bindings, res.froxelDims);
    timer.end(cmd);
    timer.begin(cmd, "composite");
    // Geometry -> composite is ordered by the render pass's outgoing dependency.
    computeToComputeBarrier(cmd);
    recordComposite(cmd, composite, bindings, res.size);
    timer.end(cmd);
    if (debugParams.view.x != shd::DEBUG_VIEW_FINAL) {
        timer.begin(cmd, "debug view");
        computeToComputeBarrier(cmd);
        recordDebugView(cmd, debugView, bindings, res.size, debugParams);
        timer.end(cmd);
    }
    recordReadback(readBackVolumes);
}

void GpuRenderer::State::recordReadback(bool readBackVolumes) {
    timer.begin(cmd, "readback");
    std::vector<VkImage> sources;
    if (readBackImage) sources.push_back(res.output.image.get());
    const auto volumes = froxelImages(res);
    if (readBackVolumes)
        for (const GpuImage* img : volumes) sources.push_back(img->image.get());
    if (!sources.empty())
        transition(cmd, sources, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                   VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                   VK_ACCESS_TRANSFER_READ_BIT);
    if (readBackImage) copyImageToBuffer(cmd, res.output, res.outputReadback);
    if (readBackVolumes)
        for (size_t i = 0; i < volumes.size(); ++i) copyImageToBuffer(cmd, *volumes[i], volumeReadback[i]);
    // Counters (light pass) and copies, to the host.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                  VK_ACCESS_HOST_READ_BIT);
    timer.end(cmd);
}

Result<double> GpuRenderer::State::submitAndWait() {
    VkSubmitInfo submit = vkStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    const VkFence f = fence.get();
    BRUME_VK(vkResetFences(device->vk(), 1, &f), "reset a fence");
    const auto start = std::chrono::steady_clock::now();
    BRUME_VK(vkQueueSubmit(device->queue(), 1, &submit, f), "submit the frame");
    BRUME_VK(vkWaitForFences(device->vk(), 1, &f, VK_TRUE, UINT64_MAX), "wait for the frame to finish");
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace brume::gpu
