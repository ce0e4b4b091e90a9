// The froxel frame's executor: everything the tables of frame_table.h imply, derived rather than
// written per resource or per pass. Resources that follow the frame's sizes (dirty tracking), the
// pipeline of each pass's variant, barriers from the passes' reads and writes, labels and timestamps,
// the readback, and the submission.
#include <chrono>

#include "renderer_state.h"
#include "shaders/shared/bindings.h"
#include "shaders/shared/brume.h"
#include "shaders/shared/distant_table.h"
#include "vk_check.h"

namespace brume::gpu {
namespace {

VkExtent3D extentOf(glm::ivec3 d) {
    return {static_cast<uint32_t>(d.x), static_cast<uint32_t>(d.y), static_cast<uint32_t>(d.z)};
}

uint32_t groups(int n, int size) { return static_cast<uint32_t>(shd::brumeDivRoundUp(n, size)); }

// Froxel images are also copied (temporal pass) and read back (tests).
constexpr VkImageUsageFlags kVolumeUsage =
    VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;

void transition(VkCommandBuffer cmd, const std::vector<VkImage>& images, VkImageLayout from, VkImageLayout to,
                VkPipelineStageFlags srcStage, VkAccessFlags srcAccess, VkPipelineStageFlags dstStage,
                VkAccessFlags dstAccess) {
    std::vector<LayoutChange> changes;
    for (VkImage img : images) changes.push_back({img, from, to});
    layoutBarrier(cmd, changes, srcStage, srcAccess, dstStage, dstAccess);
}

void copyImageToBuffer(VkCommandBuffer cmd, const GpuImage& img, const Buffer& buf) {
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = img.extent;
    vkCmdCopyImageToBuffer(cmd, img.image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buf.buffer.get(), 1, &region);
}

// The accesses a barrier waits for (writes) or makes visible to (reads and writes) in these stages.
VkAccessFlags writeAccess(VkPipelineStageFlags stages) {
    VkAccessFlags a = 0;
    if (stages & (VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_VERTEX_SHADER_BIT |
                  VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT))
        a |= VK_ACCESS_SHADER_WRITE_BIT;
    if (stages & VK_PIPELINE_STAGE_TRANSFER_BIT) a |= VK_ACCESS_TRANSFER_WRITE_BIT;
    if (stages & VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT) a |= VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    return a;
}
VkAccessFlags readWriteAccess(VkPipelineStageFlags stages) {
    VkAccessFlags a = writeAccess(stages);
    if (a & VK_ACCESS_SHADER_WRITE_BIT) a |= VK_ACCESS_SHADER_READ_BIT;
    if (a & VK_ACCESS_TRANSFER_WRITE_BIT) a |= VK_ACCESS_TRANSFER_READ_BIT;
    if (a & VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT) a |= VK_ACCESS_COLOR_ATTACHMENT_READ_BIT;
    if (stages & VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT) a |= VK_ACCESS_INDIRECT_COMMAND_READ_BIT;
    return a;
}

// Accesses recorded since the last barrier; a pass that reads or writes what an earlier one wrote,
// or writes what an earlier one read, waits for all of them (one global barrier: the chain is
// serial anyway, and lavapipe runs one pass at a time). Accesses are to memory: a texel view's
// reads are its buffer's (memoryOf).
class Hazards {
public:
    void wrote(ResRef r, VkPipelineStageFlags s) { writes_.push_back({memoryOf(r), s}); }
    void read(ResRef r, VkPipelineStageFlags s) { reads_.push_back({memoryOf(r), s}); }
    bool conflicts(const PassDecl& p) const {
        for (const auto& [r, s] : writes_)
            if (touches(p.reads, r) || touches(p.writes, r)) return true;
        for (const auto& [r, s] : reads_)
            if (touches(p.writes, r)) return true;
        return false;
    }
    VkPipelineStageFlags writeStages() const { return stages(writes_); }
    VkPipelineStageFlags allStages() const { return stages(writes_) | stages(reads_); }
    void clear() { writes_.clear(), reads_.clear(); }

private:
    using Access = std::pair<ResRef, VkPipelineStageFlags>;
    static bool touches(const ResList& list, ResRef memory) {
        for (ResRef x : list)
            if (memoryOf(x) == memory) return true;
        return false;
    }
    static VkPipelineStageFlags stages(const std::vector<Access>& v) {
        VkPipelineStageFlags s = 0;
        for (const auto& [r, st] : v) s |= st;
        return s;
    }
    std::vector<Access> writes_, reads_;
};

}  // namespace

const GpuImage& FrameResources::image(ResRef ref, int writeIndex) const {
    switch (ref.kind) {
        case ResRef::Kind::HistoryIn: return history[ref.index][static_cast<size_t>(1 - writeIndex)];
        case ResRef::Kind::HistoryOut: return history[ref.index][static_cast<size_t>(writeIndex)];
        default: return images[ref.index];
    }
}

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

// Usage and memory follow the table's kind.
Result<void> GpuRenderer::State::ensureBuffer(BufferId id, VkDeviceSize size, bool& dirty, const char* what) {
    const BufferDecl& d = decl(id);
    // Its readers go through its texel views (shared/frame_table.h), which address at most the device's
    // maxTexelBufferElements texels (ensureTexelViews): past that they would read nothing, silently.
    const uint32_t maxTexels = device->limits().maxTexelBufferElements;
    for (const TexelViewDecl& v : kTexelViews)
        if (v.buffer == id && (size + texelBytes(v.format) - 1) / texelBytes(v.format) > maxTexels)
            return Error{std::string(what ? what : d.name) + " needs " +
                         std::to_string((size + texelBytes(v.format) - 1) / texelBytes(v.format)) +
                         " texels, more than this Vulkan device's texel buffers hold (" + std::to_string(maxTexels) +
                         "); use a smaller image, fewer lights or a lower quality preset."};
    VkBufferUsageFlags usage = d.kind == BufferKind::UNIFORM ? VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT
                                                             : VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    Memory memory = hostWrites(d.kind) ? Memory::Upload : Memory::DeviceLocal;
    if (d.kind == BufferKind::STORAGE_READBACK) {
        usage |= VK_BUFFER_USAGE_TRANSFER_DST_BIT;  // cleared with vkCmdFillBuffer each frame
        memory = Memory::Readback;
    }
    // Filled with NaN before each frame under GpuOptions::poisonShadowVolume (tests).
    if (id == BufferId::shadowTransmittance) usage |= VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    if (hasTexelView(id)) usage |= VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
    // Reset with vkCmdUpdateBuffer each frame, read as a dispatch's group count.
    if (d.kind == BufferKind::STORAGE_INDIRECT)
        usage |= VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
    // About to be replaced: its texel views go first (ensureTexelViews makes them again over the
    // new buffer).
    if (!res[id].buffer || res[id].size < size)
        for (const TexelViewDecl& v : kTexelViews)
            if (v.buffer == id) res.texelViews[static_cast<size_t>(v.id)].reset();
    return ensureBuffer(res[id], size, usage, memory, d.name, dirty);
}

namespace {

// About the bytes a set of sized resources holds, in units of 16 B: 10 froxel volumes and about 4
// screen images (frame_resources.h).
int64_t sizedWeight(glm::ivec3 dims, glm::ivec2 size) {
    return 10 * int64_t(dims.x) * dims.y * dims.z + 4 * int64_t(size.x) * size.y;
}

// The members of FrameResources whose size follows the froxel grid or the image (with the history's
// bookkeeping, which belongs to its images). The buffers only grow and stay where they are.
void swapSizedResources(FrameResources& a, FrameResources& b) {
    std::swap(a.images, b.images);
    std::swap(a.history, b.history);
    std::swap(a.historyUndefined, b.historyUndefined);
    std::swap(a.historyWritten, b.historyWritten);
    std::swap(a.froxelDims, b.froxelDims);
    std::swap(a.mediaImages, b.mediaImages);
    std::swap(a.size, b.size);
    std::swap(a.outputReadback, b.outputReadback);
}

void releaseSizedResources(FrameResources& r) {
    FrameResources empty;
    swapSizedResources(r, empty);  // empty's destructor frees them
}

}  // namespace

// Called before the ensure* below; the parked set is the largest one seen lately. Back at its sizes:
// swap the sets, no allocation. Going smaller than the current set while it is the largest: park it
// (the one given back is reallocated by ensure*). Going at least as large as the parked set: free
// it first, nothing will come back to it. Peak memory stays the largest set plus the current one.
// A swapped-in set's history is not read across the swap: the dims are part of the temporal scene
// key (core/temporal.h), so the frame after a size change restarts its history.
Result<void> GpuRenderer::State::parkSizedResources(glm::ivec3 dims, glm::ivec2 size, bool& dirty) {
    if (res.froxelDims == dims && res.size == size) return {};
    if (parked.froxelDims == dims && parked.size == size) {
        swapSizedResources(res, parked);
        dirty = true;
        if (Result<void> a = geometry.attach(*device, res); !a) {
            res.size = glm::ivec2(0);  // ensureScreenImages reallocates and attaches again
            return a.error();
        }
        return {};
    }
    const int64_t now = sizedWeight(dims, size), current = sizedWeight(res.froxelDims, res.size),
                  kept = sizedWeight(parked.froxelDims, parked.size);
    if (now < current && current >= kept) swapSizedResources(res, parked);
    else if (now >= kept) releaseSizedResources(parked);
    return {};
}

// Whether voxelize dispatches this frame: with vdb volumes always; without, the light passes and the
// glow compute the media themselves (VariantKey::inlineMedia) and voxelize runs only to fill the media
// images for the read-back volumes.
bool voxelizeDispatches(const VariantKey& variant, bool readBackVolumes) {
    return !variant.inlineMedia() || readBackVolumes;
}

// media: whether the MEDIA images (voxelize's output) get the grid's size; else one texel each. Only
// they are made again when only that changes.
Result<void> GpuRenderer::State::ensureFroxelImages(glm::ivec3 dims, bool media, bool& dirty) {
    const bool resized = res.froxelDims != dims;
    if (!resized && res.mediaImages == media) return {};
    allocated = true;
    dirty = true;
    // Until every image is made: a failure half-way leaves a set the next call rebuilds whole.
    res.froxelDims = glm::ivec3(0);
    for (const ImageDecl& d : kImages) {
        const bool isMedia = (d.flags & image_flags::MEDIA) != 0;
        // At the same size only the MEDIA images change.
        if (d.shape != ImageShape::image3D || (!resized && !isMedia)) continue;
        GpuImage& slot = res[d.id];
        slot = GpuImage{};  // release before allocating: peak memory stays one set of volumes
        const glm::ivec3 extent = isMedia && !media ? glm::ivec3(1) : dims;
        Result<GpuImage> img = createImage(*device, extentOf(extent), true, vkFormat(d.format), kVolumeUsage, d.name);
        if (!img) return img.error();
        slot = std::move(img.value());
    }
    res.mediaImages = media;
    if (!resized) {
        res.froxelDims = dims;
        return {};
    }
    for (const HistoryDecl& d : kHistory) {
        for (size_t k = 0; k < 2; ++k) {
            GpuImage& slot = res.history[static_cast<size_t>(d.id)][k];
            slot = GpuImage{};
            Result<GpuImage> img = createImage(*device, extentOf(dims), true, vkFormat(d.format), kVolumeUsage,
                                               std::string(d.name) + " " + std::to_string(k));
            if (!img) return img.error();
            slot = std::move(img.value());
        }
    }
    res.historyUndefined = true;
    res.historyWritten.fill(FroxelRegion{glm::ivec3(0), dims});  // undefined contents: anything
    res.froxelDims = dims;
    dirty = true;
    return {};
}

Result<void> GpuRenderer::State::ensureScreenImages(glm::ivec2 size, bool& dirty) {
    if (res.size == size) return {};
    allocated = true;
    const VkExtent3D e{static_cast<uint32_t>(size.x), static_cast<uint32_t>(size.y), 1};
    res.size = glm::ivec2(0);
    for (const ImageDecl& d : kImages) {
        if (d.shape != ImageShape::image2D) continue;
        GpuImage& slot = res[d.id];
        slot = GpuImage{};
        VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT;
        // The composite copies the target sceneColor over the output where no fog is.
        if (d.flags & image_flags::TARGET) usage |= VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
        if (d.flags & image_flags::OUTPUT) usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
        Result<GpuImage> img = createImage(*device, e, false, vkFormat(d.format), usage, d.name);
        if (!img) return img.error();
        slot = std::move(img.value());
    }
    res.outputReadback = Buffer{};
    Result<Buffer> rb = createBuffer(*device, static_cast<VkDeviceSize>(size.x) * static_cast<VkDeviceSize>(size.y) * 16,
                                     VK_BUFFER_USAGE_TRANSFER_DST_BIT, Memory::Readback, "output readback");
    if (!rb) return rb.error();
    res.outputReadback = std::move(rb.value());
    res.size = size;
    if (Result<void> a = geometry.attach(*device, res); !a) {
        res.size = glm::ivec2(0);  // attach again next time
        return a.error();
    }
    dirty = true;
    return {};
}

// Each texel view over its buffer's whole range (at most the device's texel count: a buffer grown
// past what prepare() asked for holds nothing read beyond it), made again when the buffer was
// (ensureBuffer drops the old view).
Result<void> GpuRenderer::State::ensureTexelViews(bool& dirty) {
    for (const TexelViewDecl& d : kTexelViews) {
        const Buffer& b = res[d.buffer];
        BufferViewOwner& v = res.texelViews[static_cast<size_t>(d.id)];
        if (v) continue;
        const VkDeviceSize texel = texelBytes(d.format);
        const VkDeviceSize limit = VkDeviceSize(device->limits().maxTexelBufferElements) * texel;
        VkBufferViewCreateInfo info = vkStruct<VkBufferViewCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO);
        info.buffer = b.buffer.get();
        info.format = vkFormat(d.format);
        info.offset = 0;
        info.range = std::min(b.size, limit) / texel * texel;
        VkBufferView view = VK_NULL_HANDLE;
        BRUME_VK(vkCreateBufferView(device->vk(), &info, nullptr, &view), std::string("create the texel view ") + d.name);
        device->name(view, VK_OBJECT_TYPE_BUFFER_VIEW, d.name);
        v = BufferViewOwner(device->vk(), view);
        dirty = true;
    }
    return {};
}

Result<void> GpuRenderer::State::ensureVolumeReadback(glm::ivec3 dims) {
    const VkDeviceSize bytes = static_cast<VkDeviceSize>(dims.x) * static_cast<VkDeviceSize>(dims.y) *
                               static_cast<VkDeviceSize>(dims.z) * sizeof(glm::vec4);
    size_t k = 0;
    for (const ImageDecl& d : kImages) {
        if (!(d.flags & image_flags::READBACK)) continue;
        if (res.volumeReadback.size() <= k) res.volumeReadback.emplace_back();
        if (res.volumeReadbackFormat.size() <= k) res.volumeReadbackFormat.push_back(VK_FORMAT_UNDEFINED);
        bool unused = false;
        BRUME_TRY(ensureBuffer(res.volumeReadback[k++], bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, Memory::Readback,
                               (std::string(d.name) + " readback").c_str(), unused));
    }
    return {};
}

Result<void> GpuRenderer::State::prepare(glm::ivec2 size, glm::ivec3 dims, const CompiledScene& cs,
                                         size_t vertexBytes, int shadowReduction, size_t sunShadowBytes,
                                         size_t localShadowBytes, bool readBackVolumes) {
    bool dirty = descriptorsStale;
    descriptorsStale = true;  // until the descriptors below are written
    allocated = false;
    BRUME_TRY(ensureBuffer(BufferId::frame, sizeof(shd::FrameUniforms), dirty));
    BRUME_TRY(ensureBuffer(BufferId::previousFrame, sizeof(shd::FrameUniforms), dirty));
    BRUME_TRY(ensureBuffer(BufferId::counters, sizeof(shd::FroxelCounters), dirty));
    BRUME_TRY(ensureBuffer(BufferId::surfaceLights, sizeof(shd::SurfaceLights), dirty));
    // Storage buffers cannot be empty: keep room for at least one record.
    BRUME_TRY(ensureBuffer(BufferId::volumes, std::max<size_t>(cs.volumes.size(), 1) * sizeof(shd::VolumeData), dirty));
    BRUME_TRY(ensureBuffer(BufferId::lights, std::max<size_t>(cs.lights.size(), 1) * sizeof(shd::LightData), dirty));
    // Its readers go through the rgba32f texel view influenceTexels (shaders/influence.glsl).
    static_assert(sizeof(shd::InfluenceHeader) == 16 * shd::INFLUENCE_HEADER_TEXELS && sizeof(shd::InfluenceSample) == 32);
    BRUME_TRY(ensureBuffer(BufferId::influence,
                           sizeof(shd::InfluenceHeader) +
                               std::max<size_t>(cs.influence.samples.size(), 1) * sizeof(shd::InfluenceSample),
                           dirty, "The influencers' samples"));
    bool vertexDirty = false;
    BRUME_TRY(ensureBuffer(res.vertices, std::max<size_t>(vertexBytes, 64), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
                           Memory::Upload, "geometry vertices", vertexDirty));
    BRUME_TRY(parkSizedResources(dims, size, dirty));
    BRUME_TRY(chooseVariant(cs));
    // Voxelize's images at the grid's size only for the frames that run it (voxelizeDispatches).
    const bool media = voxelizeDispatches(variant, readBackVolumes);
    if (Result<void> f = ensureFroxelImages(dims, media, dirty); !f) {
        if (parked.froxelDims == glm::ivec3(0)) return f.error();
        releaseSizedResources(parked);  // out of memory with a set parked: give it back, try once more
        BRUME_TRY(ensureFroxelImages(dims, media, dirty));
    }
    // Room for every froxel: the exact light pass's list (bindings.h ExactListHeader).
    BRUME_TRY(ensureBuffer(BufferId::exactList,
                           sizeof(shd::ExactListHeader) + static_cast<size_t>(dims.x) * static_cast<size_t>(dims.y) *
                                                              static_cast<size_t>(dims.z) * sizeof(uint32_t),
                           dirty));
    BRUME_TRY(ensureScreenImages(size, dirty));
    const glm::ivec3 cells = shd::shadowVolumeDims(dims, shadowReduction);
    // Scenes with vdb grids keep room for each light's vdb layer (shared/vdb_shadow.h) after the
    // analytic ones, whether or not this frame's request fills it.
    bool anyGrid = false;
    for (const DensityGridPtr& g : cs.grids) anyGrid = anyGrid || g != nullptr;
    const size_t entries = static_cast<size_t>(cells.x) * static_cast<size_t>(cells.y) * static_cast<size_t>(cells.z) *
                           std::max<size_t>(cs.lights.size(), 1) * (anyGrid ? 2 : 1);
    // Its readers address it through the texel view shadowTexels (ensureBuffer checks the device's limit).
    BRUME_TRY(ensureBuffer(BufferId::shadowTransmittance, entries * sizeof(glm::vec4), dirty, "The fog transmittance volume"));
    BRUME_TRY(ensureVdbGrids(cs, dirty));
    // The light reach record follows the clusters (shared/clusters.h lightReachOffset).
    const glm::ivec3 c = shd::clusterDims(dims);
    const size_t clusterInts =
        static_cast<size_t>(shd::CLUSTER_STRIDE) * static_cast<size_t>(c.x * c.y * c.z) + 1 + cs.lights.size();
    BRUME_TRY(ensureBuffer(BufferId::lightClusters, clusterInts * sizeof(int), dirty));
    // Whole rgba32f texels: its readers go through the texel view sunShadowTexels (shared/frame_table.h).
    static_assert(sizeof(shd::SunShadowFit) == 16 * shd::SUN_SHADOW_FIT_TEXELS);
    BRUME_TRY(ensureBuffer(BufferId::sunShadowMap, sizeof(shd::SunShadowFit) + std::max<size_t>((sunShadowBytes + 15) / 16 * 16, 16),
                           dirty));
    BRUME_TRY(ensureBuffer(BufferId::localShadowMaps, std::max<size_t>(localShadowBytes, 4), dirty,
                           "The point and spot lights' shadow maps"));
    const glm::ivec2 corners = shd::distantTableCorners(size);
    BRUME_TRY(ensureBuffer(BufferId::distantTable,
                           static_cast<size_t>(corners.x * corners.y) * shd::DISTANT_TABLE_DEPTHS * 2 * sizeof(glm::vec4), dirty));
    const glm::ivec2 tiles = shd::depthTileCount(size);
    BRUME_TRY(ensureBuffer(BufferId::depthTiles, static_cast<size_t>(tiles.x * tiles.y) * sizeof(glm::vec2), dirty,
                           "The image's depth tiles"));
    // This frame's and the previous frame's read entries and walk end of each froxel column
    // (column_entries.glsl).
    BRUME_TRY(ensureBuffer(BufferId::columnEnds,
                           2 * static_cast<size_t>(dims.x) * static_cast<size_t>(dims.y) * sizeof(glm::ivec4), dirty,
                           "The froxel grid's column ends"));
    const size_t tileList = sizeof(shd::ExactListHeader) + static_cast<size_t>(tiles.x * tiles.y) * sizeof(uint32_t);
    // The composites read a list's tiles through its r32i texel view, past the header's texels.
    static_assert(sizeof(shd::ExactListHeader) == shd::TILE_LIST_HEADER_TEXELS * sizeof(int32_t));
    for (BufferId list : {BufferId::nearTiles, BufferId::farTiles, BufferId::allFarTiles, BufferId::skyTiles})
        BRUME_TRY(ensureBuffer(list, tileList, dirty, "The composite's tile lists"));
    BRUME_TRY(ensureTexelViews(dirty));
    if (dirty) {
        writeDescriptorBindings(*device, bindings.set, res);
        surfacesValid = false;  // a screen image or the distant table may be new
    }
    descriptorsStale = false;
    return {};
}


// Outside the media region the voxelize and light passes would write 0 (core/media_region.h): when
// the region is not the whole grid, clear what they write that a later pass reads there (S and
// sigma_t, read by the temporal and integrate passes over their larger region; sigma_s and g, read by
// the glow when it loads them), then dispatch over the region. mediaEmission is read outside the region,
// or at all when no volume emits (SPEC_EMISSION 0: voxelize leaves its store out, the light passes
// read 0 without a load), only by the read-back volumes: it is cleared for them alone, a memset of
// the whole grid (~2% of a `high` frame: docs/performance.md, "fuse").
void recordClearMedia(const PassContext& ctx) {
    const FrameResources& r = *ctx.res;
    const bool partial = r.mediaOrigin != glm::ivec3(0) || r.mediaExtent != r.froxelDims;
    const bool dispatches = voxelizeDispatches(*ctx.variant, ctx.readBackVolumes);
    auto cleared = [&](ResRef w) {
        if (w.kind != ResRef::Kind::Image) return false;
        // mediaEmission: the read-back volumes read all of it; with vdb volumes (voxelize stores the media)
        // the light pass loads it over the temporal region too, the media region's shell included.
        if (w == ResRef(ImageId::mediaEmission))
            return (ctx.readBackVolumes && (partial || !r.mediaEmits)) || (partial && dispatches && r.mediaEmits);
        // Inline media: only the read-back volumes read mediaScatteringG (glow computes it), and nothing
        // reads mediaExtinction (the light pass computes sigma_t and stores it in sourceImage and
        // sourceExtinction, which are cleared here for the temporal and integrate passes).
        if (w == ResRef(ImageId::mediaScatteringG) || w == ResRef(ImageId::mediaExtinction)) return partial && dispatches;
        // S and sigma_t: the light pass writes them over the temporal region (0 where there are no
        // media), which is all the temporal and integrate passes read; the read-back volumes read the
        // whole grid. Tests poison them instead (GpuOptions::poisonSource).
        return partial && (ctx.readBackVolumes || ctx.poisonSource);
    };
    bool any = false;
    for (ResRef w : ctx.pass->writes) any = any || cleared(w);
    if (any) {
        const VkPipelineStageFlags compute = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
        const VkPipelineStageFlags transfer = VK_PIPELINE_STAGE_TRANSFER_BIT;
        // After the frame's layout transitions and last frame's readers (compute and copies).
        memoryBarrier(ctx.cmd, compute | transfer, VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT, transfer,
                      VK_ACCESS_TRANSFER_WRITE_BIT);
        const VkClearColorValue zero{};
        // GpuOptions::poisonSource: finite, since the temporal resolve replaces non-finite samples.
        const VkClearColorValue poison{{1.0f, 1.0f, 1.0f, 1.0f}};
        const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        for (ResRef w : ctx.pass->writes) {
            if (!cleared(w)) continue;
            const bool source = w == ResRef(ImageId::sourceImage) || w == ResRef(ImageId::sourceExtinction);
            const VkClearColorValue& value = source && ctx.poisonSource && !ctx.readBackVolumes ? poison : zero;
            vkCmdClearColorImage(ctx.cmd, r.image(w, ctx.historyWriteIndex).image.get(), VK_IMAGE_LAYOUT_GENERAL, &value, 1,
                                 &all);
        }
        memoryBarrier(ctx.cmd, transfer, VK_ACCESS_TRANSFER_WRITE_BIT, compute,
                      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    }
    if (dispatches) dispatchPass(ctx);
}

void pushRegion(const PassContext& ctx, const FroxelRegion& region, int loW, int hiW) {
    const shd::FroxelRegionParams p{glm::ivec4(region.lo, loW), glm::ivec4(region.hi, hiW)};
    vkCmdPushConstants(ctx.cmd, ctx.bindings->pipelineLayout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(p), &p);
}

// One dispatch per computed layer over its cells, the light pushed in lo.w (FrameResources::shadowLayers):
// the layers write disjoint entries, so no barrier between them.
void recordShadowCells(const PassContext& ctx) {
    bindComputePass(ctx.cmd, *ctx.pipeline, *ctx.bindings);
    for (const FrameResources::ShadowLayer& layer : ctx.res->shadowLayers) {
        const glm::ivec3 e = layer.cells.hi - layer.cells.lo;
        pushRegion(ctx, layer.cells, layer.light);
        // One invocation per run of SHADOW_RUN cells along z (shaders/shadow_cells.glsl).
        vkCmdDispatch(ctx.cmd, groups(e.x, shd::FROXEL_GROUP_X), groups(e.y, shd::FROXEL_GROUP_Y),
                      groups(groups(e.z, shd::SHADOW_RUN), shd::FROXEL_GROUP_Z));
    }
}

void recordComposite(const PassContext& ctx) {
    const FrameResources& r = *ctx.res;
    if (r.compositeLo != glm::ivec2(0) || r.compositeHi != r.size) {
        // After the geometry pass's writes (and the executor's barrier), before the dispatch's.
        const VkPipelineStageFlags transfer = VK_PIPELINE_STAGE_TRANSFER_BIT;
        const VkImage color = r[ImageId::sceneColor].image.get(), output = r[ImageId::outputImage].image.get();
        constexpr VkImageLayout G = VK_IMAGE_LAYOUT_GENERAL, SRC = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                DST = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        const std::array<LayoutChange, 2> toCopy{{{color, G, SRC}, {output, G, DST}}};
        layoutBarrier(ctx.cmd, toCopy, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                      VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_SHADER_WRITE_BIT, transfer,
                      VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT);
        VkImageCopy all{};
        all.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        all.dstSubresource = all.srcSubresource;
        all.extent = r[ImageId::outputImage].extent;
        vkCmdCopyImage(ctx.cmd, color, SRC, output, DST, 1, &all);
        const std::array<LayoutChange, 2> back{{{color, SRC, G}, {output, DST, G}}};
        layoutBarrier(ctx.cmd, back, transfer, VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT,
                      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    }
    pushRegion(ctx, FroxelRegion{glm::ivec3(r.compositeLo, 0), glm::ivec3(r.compositeHi, 1)});
    dispatchPass(ctx);
}

void dispatchPass(const PassContext& ctx) {
    bindComputePass(ctx.cmd, *ctx.pipeline, *ctx.bindings);
    const FrameResources& r = *ctx.res;
    switch (ctx.pass->dispatch) {
        case Dispatch::Columns:
            vkCmdDispatch(ctx.cmd, groups(r.froxelDims.x, shd::INTEGRATE_GROUP_X),
                          groups(r.froxelDims.y, shd::INTEGRATE_GROUP_Y), 1);
            break;
        case Dispatch::Screen:
            vkCmdDispatch(ctx.cmd, groups(r.size.x, shd::SCREEN_GROUP_X), groups(r.size.y, shd::SCREEN_GROUP_Y), 1);
            break;
        case Dispatch::CompositePixels: {
            // A tile list's workgroup is one 8x8 pixel tile (composite_body.glsl).
            static_assert(shd::SCREEN_GROUP_X == shd::DISTANT_TILE_PX && shd::SCREEN_GROUP_Y == shd::DISTANT_TILE_PX);
            if (r.distantFog) {
                vkCmdDispatchIndirect(ctx.cmd, r[BufferId::nearTiles].buffer.get(), 0);
                break;
            }
            const glm::ivec2 e = glm::max(r.compositeHi - r.compositeLo, glm::ivec2(0));
            vkCmdDispatch(ctx.cmd, groups(e.x, shd::SCREEN_GROUP_X), groups(e.y, shd::SCREEN_GROUP_Y), 1);
            break;
        }
        case Dispatch::Indirect: vkCmdDispatchIndirect(ctx.cmd, r[*ctx.pass->indirect].buffer.get(), 0); break;
        case Dispatch::TileRows:
            // The tile lists: empty without distant fog.
            if (r.distantFog) vkCmdDispatch(ctx.cmd, groups(shd::depthTileCount(r.size).y, shd::TILE_LIST_GROUP), 1, 1);
            break;
        case Dispatch::ShadowCells: break;  // one dispatch per layer: recordShadowCells
        case Dispatch::MediaFroxels:
            vkCmdDispatch(ctx.cmd, groups(r.mediaExtent.x, shd::FROXEL_GROUP_X),
                          groups(r.mediaExtent.y, shd::FROXEL_GROUP_Y), groups(r.mediaExtent.z, shd::FROXEL_GROUP_Z));
            break;
        case Dispatch::RegionLightRuns: {
            // The temporal region, not only the media region: its shell of media-free froxels gets S and
            // sigma_t = 0 from the pass itself, where the frame used to clear the whole grid first
            // (recordClearMedia; docs/performance.md, "shadowskip").
            const glm::ivec3 e = r.temporalRegion.empty() ? glm::ivec3(0) : r.temporalRegion.hi - r.temporalRegion.lo;
            pushRegion(ctx, r.temporalRegion);
            vkCmdDispatch(ctx.cmd, groups(e.x, shd::LIGHT_GROUP_X), groups(e.y, shd::LIGHT_GROUP_Y), groups(e.z, shd::LIGHT_RUN));
            break;
        }
        case Dispatch::RegionRuns: {
            const glm::ivec3 e = r.temporalRegion.empty() ? glm::ivec3(0) : r.temporalRegion.hi - r.temporalRegion.lo;
            vkCmdDispatch(ctx.cmd, groups(e.x, shd::TEMPORAL_GROUP_X), groups(e.y, shd::TEMPORAL_GROUP_Y),
                          groups(e.z, shd::TEMPORAL_RUN));
            break;
        }
        case Dispatch::IntegrateColumns: {
            // The temporal region, the entries stored in every column, and the columns dispatched.
            const glm::ivec4 c = integrateColumns(ctx);
            const glm::ivec2 everywhere = storedEverywhere(ctx);
            const shd::IntegrateParams p{{glm::ivec4(r.temporalRegion.lo, everywhere.x), glm::ivec4(r.temporalRegion.hi, everywhere.y)}, c};
            vkCmdPushConstants(ctx.cmd, ctx.bindings->pipelineLayout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(p), &p);
            vkCmdDispatch(ctx.cmd, groups(c.z - c.x, shd::INTEGRATE_GROUP_X), groups(c.w - c.y, shd::INTEGRATE_GROUP_Y), 1);
            break;
        }
        case Dispatch::TileCorners: {
            if (!r.distantFog) break;  // no table to fill
            const glm::ivec2 corners = shd::distantTableCorners(r.size);
            vkCmdDispatch(ctx.cmd, groups(corners.x, shd::SCREEN_GROUP_X), groups(corners.y, shd::SCREEN_GROUP_Y), 1);
            break;
        }
        case Dispatch::DepthTiles: {
            const glm::ivec2 tiles = shd::depthTileCount(r.size);
            vkCmdDispatch(ctx.cmd, groups(tiles.x, shd::SCREEN_GROUP_X), groups(tiles.y, shd::SCREEN_GROUP_Y), 1);
            break;
        }
        case Dispatch::Raster:
        case Dispatch::GlowRects: break;  // recordGlow dispatches
    }
}

bool FramePasses::records(const PassDecl& p) const {
    if (p.when == When::DebugView && !debugView) return false;
    if (p.when == When::SurfacesChanged && reuseSurfaces) return false;
    return !((p.when == When::VdbScene && !variant.vdb) || (p.when == When::NoVdbScene && variant.vdb));
}

bool FramePasses::dispatches(const PassDecl& p) const {
    // At rest the temporal pass dispatches nothing (integrate_rest resolves the history): no pipeline.
    // Without vdb volumes voxelize dispatches only for the read-back volumes (voxelizeDispatches).
    return records(p) && p.dispatch != Dispatch::Raster && !(p.record == Record::TemporalCopy && variant.temporalRest) &&
           !(p.record == Record::ClearMedia && !voxelizeDispatches(variant, readBackVolumes));
}

void GpuRenderer::State::requestPipelines(const FramePasses& passes, const FrameKeys& frameKeys, PipelineBatch& batch) {
    const VkPipelineLayout layout = bindings.pipelineLayout.get();
    for (const PassDecl& p : kPasses) {
        if (p.record == Record::Geometry && passes.records(p))
            geometry.request(*device, layout, frameKeys.surfaceSpec, passes.variant.shapes, passes.spheres, batch);
        else if (passes.dispatches(p))
            pipelines.request(*device, layout, variantShaderName(p.shader, p.variant, passes.variant), frameKeys.of(p),
                              batch);
    }
}

bool GpuRenderer::State::hasCulledPipelines(const FramePasses& passes, const FrameKeys& frameKeys) const {
    for (const PassDecl& p : kPasses)
        if (p.culledVolumes && passes.dispatches(p) &&
            !pipelines.has(variantShaderName(p.shader, p.variant, passes.variant), frameKeys.of(p)))
            return false;
    return true;
}

bool GpuRenderer::State::hasPipelines(const FramePasses& passes, const FrameKeys& frameKeys) const {
    for (const PassDecl& p : kPasses) {
        if (p.record == Record::Geometry) {
            if (passes.records(p) && !geometry.has(frameKeys.surfaceSpec, passes.variant.shapes, passes.spheres))
                return false;
        } else if (passes.dispatches(p) &&
                   !pipelines.has(variantShaderName(p.shader, p.variant, passes.variant), frameKeys.of(p))) {
            return false;
        }
    }
    return true;
}

FrameKeys GpuRenderer::State::withFallbacks(const FramePasses& passes, const FrameKeys& frameKeys) const {
    FrameKeys k = frameKeys;
    const FrameKeys fallback = frameKeys.fallbacks();
    if (!hasCulledPipelines(passes, frameKeys) && hasCulledPipelines(passes, fallback)) k.froxelFallback = true;
    if (!geometry.has(frameKeys.surfaceSpec, passes.variant.shapes, passes.spheres) &&
        geometry.has(fallback.surfaceSpec, passes.variant.shapes, passes.spheres))
        k.surfaceSpec = fallback.surfaceSpec;
    return k;
}

Result<void> GpuRenderer::State::recordFrame(const GeometryMesh& mesh, glm::vec3 ambient, float cameraFar,
                                             bool readBackVolumes, int historyWriteIndex) {
    timer.reset(cmd);
    const VkPipelineStageFlags compute = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
    const VkAccessFlags computeRW = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    Hazards hazards;
    vkCmdFillBuffer(cmd, res[BufferId::counters].buffer.get(), 0, VK_WHOLE_SIZE, 0);
    hazards.wrote(BufferId::counters, VK_PIPELINE_STAGE_TRANSFER_BIT);
    // Lists start empty, their indirect dispatch at (0, 1, 1) groups.
    const shd::ExactListHeader emptyList{0, 1, 1, 0};
    for (const BufferDecl& d : kBuffers) {
        if (d.kind != BufferKind::STORAGE_INDIRECT) continue;
        vkCmdUpdateBuffer(cmd, res[d.id].buffer.get(), 0, sizeof(emptyList), &emptyList);
        hazards.wrote(d.id, VK_PIPELINE_STAGE_TRANSFER_BIT);
    }
    if (poisonShadowVolume) {
        constexpr uint32_t kQuietNaN = 0x7fc00000u;
        vkCmdFillBuffer(cmd, res[BufferId::shadowTransmittance].buffer.get(), 0, VK_WHOLE_SIZE, kQuietNaN);
        hazards.wrote(BufferId::shadowTransmittance, VK_PIPELINE_STAGE_TRANSFER_BIT);
    }
    // The images rewritten every frame start from UNDEFINED: their old contents are discarded; the
    // previous frame finished before its fence was signalled, so nothing earlier needs waiting for.
    std::vector<VkImage> frameImages;
    for (const ImageDecl& d : kImages)
        if (d.flags & image_flags::FRAME) frameImages.push_back(res[d.id].image.get());
    transition(cmd, frameImages, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
               0, compute, computeRW);
    // Last frame's temporal pass wrote the history this frame reads (and overwrites the other half).
    memoryBarrier(cmd, compute, VK_ACCESS_SHADER_WRITE_BIT, compute, computeRW);
    // The history outlives frames: only freshly created images start from UNDEFINED (a frame
    // without history does not read them, see temporal.comp).
    if (res.historyUndefined) {
        std::vector<VkImage> history;
        for (const auto& pair : res.history)
            for (const GpuImage& img : pair) history.push_back(img.image.get());
        transition(cmd, history, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
                   0, compute, computeRW);
        res.historyUndefined = false;
    }

    const VkPipelineLayout layout = bindings.pipelineLayout.get();
    const FramePasses passes{variant, debugParams.view.x != shd::DEBUG_VIEW_FINAL, reuseSurfaces, readBackVolumes,
                             mesh.sphereVertices > 0};
    // The pipelines this frame lacks, made together before it records (pipeline.h PipelineBatch).
    PipelineBatch batch;
    requestPipelines(passes, keys, batch);
    compiled = compiled || batch.size() > 0;
    BRUME_TRY(batch.run());
    for (const PassDecl& p : kPasses) {
        if (!passes.records(p)) continue;
        PassContext ctx;
        ctx.cmd = cmd;
        ctx.pass = &p;
        ctx.bindings = &bindings;
        ctx.res = &res;
        ctx.historyWriteIndex = historyWriteIndex;
        ctx.variant = &variant;
        ctx.debugParams = debugParams;
        ctx.glow = &glow;
        ctx.ambient = ambient;
        ctx.cameraFar = cameraFar;
        ctx.triangleVertices = mesh.triangleVertices;
        ctx.sphereVertices = mesh.sphereVertices;
        ctx.readBackVolumes = readBackVolumes;
        ctx.poisonIntegrated = poisonIntegrated;
        ctx.poisonSource = poisonSource;
        if (passes.dispatches(p)) {
            Result<const ComputePass*> pipeline =
                pipelines.get(*device, layout, variantShaderName(p.shader, p.variant, variant), keys.of(p));
            if (!pipeline) return pipeline.error();
            ctx.pipeline = pipeline.value();
        }
        // The start timestamp goes before the barrier (timing.h).
        timer.begin(cmd, p.label);
        const VkPipelineStageFlags stages = passStages(p);
        if (hazards.conflicts(p)) {
            memoryBarrier(cmd, hazards.allStages(), writeAccess(hazards.writeStages()), stages, readWriteAccess(stages));
            hazards.clear();
        }
        switch (p.record) {
            case Record::Dispatch: dispatchPass(ctx); break;
            case Record::ClearMedia: recordClearMedia(ctx); break;
            case Record::ShadowCells: recordShadowCells(ctx); break;
            case Record::Composite: recordComposite(ctx); break;
            case Record::Geometry:
                BRUME_TRY(geometry.usePipeline(*device, layout, keys.surfaceSpec, variant.shapes, mesh.sphereVertices > 0));
                geometry.record(ctx);
                break;
            case Record::TemporalCopy: recordTemporal(ctx); break;
            case Record::Integrate: recordIntegrate(ctx); break;
            case Record::ColumnEnds: recordColumnEnds(ctx); break;
            case Record::DebugView: recordDebugView(ctx); break;
            case Record::Glow: recordGlow(ctx); break;
        }
        for (ResRef r : p.reads) hazards.read(r, stages);
        for (ResRef r : p.writes) hazards.wrote(r, stages);
        timer.end(cmd);
    }
    recordReadback(readBackVolumes, historyWriteIndex);
    return {};
}

void GpuRenderer::State::recordReadback(bool readBackVolumes, int historyWriteIndex) {
    timer.begin(cmd, "readback");
    std::vector<VkImage> sources, kept;
    std::vector<std::pair<const GpuImage*, const Buffer*>> copies;
    size_t k = 0;
    for (const ImageDecl& d : kImages) {
        const Buffer* dst = nullptr;
        const size_t volume = k;
        if ((d.flags & image_flags::OUTPUT) && readBackImage) dst = &res.outputReadback;
        if ((d.flags & image_flags::READBACK) && readBackVolumes) dst = &res.volumeReadback[k];
        if (d.flags & image_flags::READBACK) ++k;
        if (!dst) continue;
        // The resolved S and sigma_t are the history's output (integrate.comp); the history outlives
        // the frame, so it goes back to GENERAL after the copy.
        const GpuImage* src = &res[d.id];
        if (d.id == ImageId::sourceImage) src = &res.image(historyOut(HistoryId::historySource), historyWriteIndex);
        if (d.id == ImageId::mediaExtinction) src = &res.image(historyOut(HistoryId::historyExtinction), historyWriteIndex);
        if (d.flags & image_flags::READBACK) res.volumeReadbackFormat[volume] = src->format;  // readVolume converts
        sources.push_back(src->image.get());
        if (src != &res[d.id]) kept.push_back(src->image.get());
        copies.push_back({src, dst});
    }
    transition(cmd, sources, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
               VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
               VK_ACCESS_TRANSFER_READ_BIT);
    for (const auto& [img, buf] : copies) copyImageToBuffer(cmd, *img, *buf);
    transition(cmd, kept, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
               VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
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
    const VkResult injected = injectedFault(FaultSite::Submit);  // tests only (vk_check.h)
    BRUME_VK(injected != VK_SUCCESS ? injected : vkQueueSubmit(device->queue(), 1, &submit, f), "submit the frame");
    BRUME_VK(vkWaitForFences(device->vk(), 1, &f, VK_TRUE, UINT64_MAX), "wait for the frame to finish");
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace brume::gpu
