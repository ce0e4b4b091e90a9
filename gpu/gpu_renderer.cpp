#include "gpu_renderer.h"

#ifdef __linux__
#include <sys/mman.h>
#endif

#include <algorithm>
#include <array>
#include <chrono>
#include <cstring>
#include <tuple>
#include <utility>
#include <glm/gtc/type_precision.hpp>

#include "core/clusters.h"
#include "core/compile.h"
#include "core/light_reach.h"
#include "core/media_region.h"
#include "core/shadows.h"
#include "core/sun_shadow.h"
#include "core/vdb_shadow.h"
#include "geometry_mesh.h"
#include "renderer_state.h"
#include "shaders/shared/bindings.h"
#include "shaders/shared/glow.h"
#include "shaders/shared/local_shadow.h"
#include "vk_check.h"

namespace brume::gpu {

Result<void> GpuRenderer::State::createCommands() {
    VkCommandPoolCreateInfo poolInfo = vkStruct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = device->queueFamily();
    VkCommandPool pool = VK_NULL_HANDLE;
    BRUME_VK(vkCreateCommandPool(device->vk(), &poolInfo, nullptr, &pool), "create the command pool");
    commandPool = CommandPoolOwner(device->vk(), pool);
    device->name(pool, VK_OBJECT_TYPE_COMMAND_POOL, "brume command pool");
    VkCommandBufferAllocateInfo alloc = vkStruct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
    alloc.commandPool = pool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    BRUME_VK(vkAllocateCommandBuffers(device->vk(), &alloc, &cmd), "allocate the command buffer");
    device->name(cmd, VK_OBJECT_TYPE_COMMAND_BUFFER, "froxel frame");
    VkFenceCreateInfo fenceInfo = vkStruct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
    VkFence f = VK_NULL_HANDLE;
    BRUME_VK(vkCreateFence(device->vk(), &fenceInfo, nullptr, &f), "create a fence");
    fence = FenceOwner(device->vk(), f);
    device->name(f, VK_OBJECT_TYPE_FENCE, "frame done");
    return {};
}

Result<void> GpuRenderer::State::createPasses() {
    const VkFormatFeatureFlags storageAttachment =
        VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT | VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT;
    for (const ImageDecl& d : kImages)
        if (!device->supportsFormat(vkFormat(d.format), storageAttachment))
            return Error{"The Vulkan device " + device->name() +
                         " cannot use 32-bit float and 16-bit normalized images as storage and render targets, "
                         "which brume needs."};
    for (const HistoryDecl& d : kHistory)
        if (!device->supportsFormat(vkFormat(d.format), VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT))
            return Error{"The Vulkan device " + device->name() +
                         " cannot use two-channel 32-bit float images as storage images, which brume needs."};
    if (!device->storageImageExtendedFormats())
        return Error{"The Vulkan device " + device->name() +
                     " has no storage images in 16-bit normalized formats (shaderStorageImageExtendedFormats), "
                     "which brume needs."};
    if (!device->supportsFormat(VK_FORMAT_D32_SFLOAT, VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT))
        return Error{"The Vulkan device " + device->name() + " has no 32-bit float depth buffer, which brume needs."};
    Result<DescriptorBindings> b = createDescriptorBindings(*device);
    if (!b) return b.error();
    bindings = std::move(b.value());
    const VkPipelineLayout layout = bindings.pipelineLayout.get();
    Result<GeometryPass> g = GeometryPass::create(*device, layout);
    if (!g) return g.error();
    geometry = std::move(g.value());
    // No pass's pipeline yet: each frame makes the ones its keys need and the cache lacks, together
    // (frame_executor.cpp recordFrame). A pipeline of the shaders' default constants would rarely be one
    // a scene uses, and lavapipe spends 10-250 ms on each.
    Result<PassTimer> t = PassTimer::create(*device, kMaxPasses);
    if (!t) return t.error();
    timer = std::move(t.value());
    return {};
}

Result<std::unique_ptr<GpuRenderer>> GpuRenderer::create(const GpuOptions& options) {
    auto s = std::make_unique<State>();
    Result<std::unique_ptr<Device>> d = Device::create(options);
    if (!d) return d.error();
    s->device = std::move(d.value());
    s->froxelRegions = options.froxelRegions;
    s->poisonShadowVolume = options.poisonShadowVolume;
    s->poisonIntegrated = options.poisonIntegrated;
    s->poisonSource = options.poisonSource;
    s->skipHidden = options.skipHiddenFroxels;
    BRUME_TRY(s->createCommands());
    BRUME_TRY(s->createPasses());
    return std::unique_ptr<GpuRenderer>(new GpuRenderer(std::move(s)));
}

GpuRenderer::GpuRenderer(std::unique_ptr<State> state) : s_(std::move(state)) {}

GpuRenderer::~GpuRenderer() {
    if (s_ && s_->device) vkDeviceWaitIdle(s_->device->vk());
}

const Device& GpuRenderer::device() const { return *s_->device; }

OutputImage GpuRenderer::outputImage() const {
    return {s_->res[ImageId::outputImage].image.get(), s_->res[ImageId::outputImage].view.get(), s_->res.size,
            s_->debugParams.view.x != shd::DEBUG_VIEW_FINAL};
}

std::string GpuRenderer::deviceName() const { return s_->device->name(); }
bool GpuRenderer::validationEnabled() const { return s_->device->validationEnabled(); }
std::vector<std::string> GpuRenderer::validationMessages() const { return s_->device->validationMessages(); }

}  // namespace brume::gpu

namespace brume::gpu {
namespace {

Result<void> checkLimits(const Device& device, int width, int height, glm::ivec3 dims) {
    const VkPhysicalDeviceLimits& l = device.limits();
    if (static_cast<uint32_t>(std::max(width, height)) > l.maxImageDimension2D)
        return Error{"The image is " + std::to_string(width) + "x" + std::to_string(height) + " pixels but " +
                     device.name() + " allows at most " + std::to_string(l.maxImageDimension2D) + " per side."};
    if (static_cast<uint32_t>(std::max(dims.x, std::max(dims.y, dims.z))) > l.maxImageDimension3D)
        return Error{"The froxel grid is " + std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" +
                     std::to_string(dims.z) + " but " + device.name() + " allows at most " +
                     std::to_string(l.maxImageDimension3D) + " per side; use a larger tile_px or fewer slices."};
    return {};
}

// The resolved S and sigma_t come back as the history's two texels (frame_table.h: S.rgb and
// sigma_t.r, then sigma_t.gb); each is (rgb, 0) again after this.
void unpackHistory(std::vector<glm::vec4>& source, std::vector<glm::vec4>& extinction) {
    for (size_t i = 0; i < source.size() && i < extinction.size(); ++i) {
        extinction[i] = glm::vec4(source[i].w, extinction[i].x, extinction[i].y, 0.0f);
        source[i].w = 0.0f;
    }
}

// A froxel volume copied from an rgba32f image, an rg32f one ((r, g, 0, 0)), or an rgba16 one
// (unsigned normalized: k / 65535).
std::vector<glm::vec4> readVolume(const Buffer& b, glm::ivec3 dims, VkFormat format) {
    const size_t n = static_cast<size_t>(dims.x) * static_cast<size_t>(dims.y) * static_cast<size_t>(dims.z);
    if (format == VK_FORMAT_R32G32_SFLOAT) {
        const auto* p = static_cast<const glm::vec2*>(b.mapped);
        std::vector<glm::vec4> out(n);
        for (size_t i = 0; i < n; ++i) out[i] = glm::vec4(p[i], 0.0f, 0.0f);
        return out;
    }
    if (format != VK_FORMAT_R16G16B16A16_UNORM) {
        const auto* p = static_cast<const glm::vec4*>(b.mapped);
        return std::vector<glm::vec4>(p, p + n);
    }
    const auto* p = static_cast<const glm::u16vec4*>(b.mapped);
    std::vector<glm::vec4> out(n);
    for (size_t i = 0; i < n; ++i) out[i] = glm::vec4(p[i]) / 65535.0f;
    return out;
}

// The read-back image as rgb. A 4K image's 100 MB are a fresh mapping every render (glibc maps
// allocations over 32 MB anew and unmaps them when freed), and this machine's virtual memory makes
// each first touch of a 4 KiB page cost ~20 us: 0.5-0.7 s a 3840x2160 render, as long as the GPU
// frame, before the pages were asked for as 2 MiB huge pages (docs/performance.md, "readback").
// The memory is reserved, advised, then written once (no zero fill first).
Image imageFromReadback(const glm::vec4* pixels, glm::ivec2 size) {
    Image image;
    image.width = size.x;
    image.height = size.y;
    const size_t n = static_cast<size_t>(size.x) * static_cast<size_t>(size.y);
    image.pixels.reserve(n);
#ifdef __linux__
    constexpr uintptr_t kHuge = uintptr_t(2) << 20;
    const auto begin = reinterpret_cast<uintptr_t>(image.pixels.data());
    const uintptr_t first = (begin + kHuge - 1) & ~(kHuge - 1);
    const uintptr_t last = (begin + n * sizeof(glm::vec3)) & ~(kHuge - 1);
    // Advice only: where the kernel declines, the pages are ordinary ones.
    if (last > first) madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#endif
    for (size_t i = 0; i < n; ++i) image.pixels.emplace_back(pixels[i]);
    return image;
}

}  // namespace

Result<GpuRender> GpuRenderer::render(const Scene& scene, const RenderRequest& request, bool readBackVolumes) {
    return renderFrames(scene, request, readBackVolumes, true);
}

namespace {

// What this scene lets the specialized passes leave out (shaders/shared/specialization.h). Every
// frame of a render call has the same settings, so one key serves them all.
SpecKey sceneSpecKey(const CompiledScene& cs, const shd::FrameUniforms& frame, const LightReach& reach) {
    SpecKey k;
    int kinds = 0;
    for (const shd::VolumeData& v : cs.volumes) kinds |= 1 << v.kind.x;
    k[SpecId::SPEC_VOLUME_KINDS] = kinds;
    int directional = 0;
    for (int i : reach.surfaceLights)
        directional += cs.lights[static_cast<size_t>(i)].kind.x == shd::LIGHT_DIRECTIONAL ? 1 : 0;
    k[SpecId::SPEC_DIRECTIONAL_LIGHTS] = directional;
    k[SpecId::SPEC_LOCAL_FOG_SHADOWS] = frame.localFogShadows != 0 ? 1 : 0;
    k[SpecId::SPEC_SUN_SHADOW_MAP] = frame.sunShadowLight != 0 ? 1 : 0;
    bool localMaps = false;
    for (const shd::LightData& l : cs.lights) localMaps = localMaps || shd::localShadowMapped(l, frame.localShadowTexels);
    k[SpecId::SPEC_LOCAL_SHADOW_MAPS] = localMaps ? 1 : 0;
    k[SpecId::SPEC_VDB_SHADOWS] = frame.vdbShadowSamples > 0 ? 1 : 0;
    k[SpecId::SPEC_DISTANT_FOG] = distantFogEntries(cs, frame) > 0 ? 1 : 0;  // as the CPU's table
    k[SpecId::SPEC_INFLUENCERS] = cs.influence.header.count.x > 0 ? 1 : 0;
    k[SpecId::SPEC_SHADOW_REDUCTION] = frame.shadowReduction;
    bool emits = false;  // influencers scale emission, never create it (shared/influence.h)
    for (const shd::VolumeData& v : cs.volumes) emits = emits || glm::vec3(v.emission) != glm::vec3(0.0f);
    k[SpecId::SPEC_EMISSION] = emits ? 1 : 0;
    // Grey fog shadows: every closed-form volume's sigma_t (as the shaders add it, sigma_s + sigma_a)
    // has three equal channels, so the optical depth toward a light does too, and one exp gives the
    // same transmittance as three (fog_shadow.glsl transmittanceOfDepth). Depth and vdb volumes add
    // nothing to it (shared/shadows.h).
    bool grey = true;
    for (const shd::VolumeData& v : cs.volumes) {
        const bool closedForm = v.kind.x == shd::VOLUME_BOX || v.kind.x == shd::VOLUME_HEIGHT_EXPONENTIAL ||
                                v.kind.x == shd::VOLUME_HEIGHT_LINEAR;
        const glm::vec3 sigmaT = glm::vec3(v.sigmaS_g) + glm::vec3(v.sigmaA);
        grey = grey && (!closedForm || (sigmaT.x == sigmaT.y && sigmaT.y == sigmaT.z));
    }
    k[SpecId::SPEC_GREY_FOG_SHADOWS] = grey ? 1 : 0;
    bool spots = false;
    for (const shd::LightData& l : cs.lights) spots = spots || l.kind.x == shd::LIGHT_SPOT;
    k[SpecId::SPEC_SPOT_LIGHTS] = spots ? 1 : 0;
    static_assert(SPEC_MAX_LISTED_VOLUMES == 10, "BRUME_EACH_LISTED_VOLUME (specialization.h) expands 10 volumes");
    if (cs.volumes.size() <= SPEC_MAX_LISTED_VOLUMES) {
        int list = 0;
        for (size_t i = 0; i < cs.volumes.size(); ++i)
            list |= BRUME_SPEC_VOLUME_LIST_ENTRY(static_cast<int>(i), cs.volumes[i].kind.x);
        k[SpecId::SPEC_VOLUME_COUNT] = static_cast<int>(cs.volumes.size());
        k[SpecId::SPEC_VOLUME_LIST] = list;
        // Each box-kind volume's shape and falloff (shared/shadows.h shadowDensityLengthListed).
        int shapes = 0;
        for (size_t i = 0; i < cs.volumes.size(); ++i) {
            const shd::VolumeData& v = cs.volumes[i];
            if (v.kind.x == shd::VOLUME_BOX)
                shapes |= BRUME_SPEC_SHAPE_ENTRY(static_cast<int>(i), shd::boxShape(v), v.params.z > 0.0f);
        }
        k[SpecId::SPEC_SHAPE_LIST] = shapes;
    }
    return k;
}

// The key of the froxel passes or of the geometry pass: a volume out of their reach this frame
// (core/media_region.h froxelVolumesInReach, surfaceVolumesInReach) listed as SPEC_CULLED_VOLUME, so
// its terms (exactly 0) are compiled out rather than evaluated. A scene with too many volumes for the
// list keeps every volume.
SpecKey culledSpecKey(SpecKey k, const std::vector<bool>& inReach) {
    if (k[SpecId::SPEC_VOLUME_COUNT] < 0) return k;
    for (size_t i = 0; i < inReach.size(); ++i) {
        if (inReach[i]) continue;
        const int at = static_cast<int>(i);
        k[SpecId::SPEC_VOLUME_LIST] &= ~BRUME_SPEC_VOLUME_LIST_ENTRY(at, 7);
        k[SpecId::SPEC_VOLUME_LIST] |= BRUME_SPEC_VOLUME_LIST_ENTRY(at, SPEC_CULLED_VOLUME);
    }
    return k;
}

// The geometry pass's key with its surface lights as constants (SPEC_SURFACE_LIGHTS: their count and
// each slot's kind), where they fit the slots of shd::SurfaceLights; else the pass reads the reach list.
SpecKey surfaceLightsSpecKey(SpecKey k, const CompiledScene& cs, const LightReach& reach) {
    static_assert(shd::SURFACE_LIGHT_SLOTS <= 15, "SPEC_SURFACE_LIGHTS holds the count in 4 bits");
    static_assert(4 + 2 * shd::SURFACE_LIGHT_SLOTS <= 31, "SPEC_SURFACE_LIGHTS holds 2 bits a slot from bit 4");
    static_assert(shd::LIGHT_DIRECTIONAL >= 0 && shd::LIGHT_POINT < 4 && shd::LIGHT_SPOT < 4,
                  "a slot's LIGHT_* fits its 2 bits");
    const size_t n = reach.surfaceLights.size();
    if (n > static_cast<size_t>(shd::SURFACE_LIGHT_SLOTS)) return k;
    int spec = static_cast<int>(n);
    for (size_t s = 0; s < n; ++s)
        spec |= BRUME_SPEC_SURFACE_LIGHT_ENTRY(static_cast<int>(s), cs.lights[static_cast<size_t>(reach.surfaceLights[s])].kind.x);
    k[SpecId::SPEC_SURFACE_LIGHTS] = spec;
    return k;
}

// The surface lights in their slots (shd::SurfaceLights), as compiled: the geometry pass reads neither
// the glow radius the light passes' copy carries (writeLightGlowRadii) nor the unused slots (zeros).
void writeSurfaceLights(void* mapped, const std::vector<shd::LightData>& lights, const LightReach& reach) {
    shd::SurfaceLights out{};
    const size_t n = std::min(reach.surfaceLights.size(), static_cast<size_t>(shd::SURFACE_LIGHT_SLOTS));
    for (size_t s = 0; s < n; ++s) {
        const int i = reach.surfaceLights[s];
        out.light[s] = lights[static_cast<size_t>(i)];
        out.index[s] = glm::ivec4(i, 0, 0, 0);
    }
    std::memcpy(mapped, &out, sizeof(out));
}

// The pixels whose composite lookups (shd::integratedLookup: columns floor(pixel / tile - 0.5) and
// the next, clamped) can read a froxel column of the temporal region, [lo, hi); every pixel when
// height or depth fog continues past the froxel far (distantFog). Outside the region's columns the
// integrated volumes hold scattering 0 and transmittance 1 at every slice (pass_temporal.cpp), so the
// other pixels' fog leaves the background as it is.
std::pair<glm::ivec2, glm::ivec2> compositePixels(const FroxelRegion& t, glm::ivec2 size, int tile, bool distantFog) {
    if (distantFog) return {glm::ivec2(0), size};
    if (t.empty()) return {glm::ivec2(0), glm::ivec2(0)};
    // Pixel x reads column c only if floor((x + 0.5) / tile - 0.5) is c - 1 or c: (c - 1) * tile <= x <
    // (c + 1) * tile.
    const glm::ivec2 lo = glm::max((glm::ivec2(t.lo) - 1) * tile, glm::ivec2(0));
    const glm::ivec2 hi = glm::min((glm::ivec2(t.hi) + 1) * tile, size);
    if (glm::any(glm::lessThanEqual(hi, lo))) return {glm::ivec2(0), glm::ivec2(0)};
    return {lo, hi};
}

// Each light's glow radius this frame (shared/glow.h lightGlowRadius: a pow, a matrix product and a
// square root per light) in the uploaded LightData's spot.z, which compileLight leaves 0: the light
// passes read it there instead of evaluating it for every froxel and listed light (light_body.glsl
// lightFroxelSample). The same function and value as the CPU froxel renderer's.
void writeLightGlowRadii(void* mapped, const std::vector<shd::LightData>& lights, const shd::FrameUniforms& frame) {
    auto* uploaded = static_cast<shd::LightData*>(mapped);
    for (size_t i = 0; i < lights.size(); ++i) uploaded[i].spot.z = shd::lightGlowRadius(lights[i], frame);
}

// Appends n bytes at p to out.
void appendBytes(std::vector<uint8_t>& out, const void* p, size_t n) {
    const auto* b = static_cast<const uint8_t*>(p);
    out.insert(out.end(), b, b + n);
}

// Which shadow maps a frame reads, without their megabytes: the caches' maps do not change in place,
// so the same storage with no build since holds the same map (a build makes the key differ).
struct ShadowMapsKey {
    const void* sun;
    uint64_t sunTexels;
    int64_t sunBuilds;
    const void* local;
    uint64_t localTexels;
    int64_t localBuilds;  // 64-bit members only: no padding in the bytes compared
};

// Everything the When::SurfacesChanged passes (geometry, distant fog) read this frame, as bytes:
// the frame's uniforms without what follows the jitter (the jitter, the temporal blend, the media
// origin: neither pass reads them when surfaces take no vdb layer, see below), the volumes and
// lights as uploaded, the light reach (the only part of lightClusters they read), the vertices,
// the shadow maps (ShadowMapsKey), the geometry pass's specialization key and variant. Equal bytes
// mean equal outputs.
std::vector<uint8_t> surfaceInputs(shd::FrameUniforms frame, const FrameResources& r, size_t volumeBytes,
                                   size_t lightBytes, const std::vector<int>& reach, size_t vertexBytes,
                                   const ShadowMapsKey& maps, const SpecKey& surfaceSpec, bool shapes) {
    frame.jitter = glm::vec4(0.0f);
    frame.temporal = glm::vec4(0.0f);
    frame.mediaOriginX = frame.mediaOriginY = frame.mediaOriginZ = 0;
    std::vector<uint8_t> out;
    out.reserve(sizeof(frame) + volumeBytes + lightBytes + reach.size() * sizeof(int) + vertexBytes + 256);
    appendBytes(out, &frame, sizeof(frame));
    appendBytes(out, r[BufferId::volumes].mapped, volumeBytes);
    appendBytes(out, r[BufferId::lights].mapped, lightBytes);
    appendBytes(out, reach.data(), reach.size() * sizeof(int));
    appendBytes(out, r.vertices.mapped, vertexBytes);
    appendBytes(out, r[BufferId::sunShadowMap].mapped, sizeof(shd::SunShadowFit));
    appendBytes(out, &maps, sizeof(maps));
    appendBytes(out, &surfaceSpec, sizeof(surfaceSpec));
    out.push_back(shapes ? 1 : 0);
    return out;
}

}  // namespace

namespace {

// What a call's frames share, from the scene and the request alone (no resource is touched): the
// compiled scene, the frame's uniforms before the jitter, the meshes, the lights' clusters and reach,
// and the specialization keys.
struct FramePlan {
    CompiledScene cs;
    FroxelSettings fs;
    shd::FrameUniforms frame{};
    glm::ivec3 dims{0};
    GeometryMesh mesh;
    LightClusters clusters;
    FroxelRegion media;  // the froxels that can hold media (core/media_region.h)
    LightReach lightReach;
    FrameKeys keys;
};

Result<FramePlan> planFrames(const Scene& scene, const RenderRequest& request, const Device& device, bool froxelRegions) {
    if (request.width < 1 || request.height < 1)
        return Error{"The image size must be at least 1x1 pixels, not " + std::to_string(request.width) + "x" +
                     std::to_string(request.height) + "."};
    FramePlan p;
    p.cs = compileScene(scene);
    CompiledScene& cs = p.cs;
    applyVdbCullingSettings(cs, request);
    p.fs = resolveFroxelSettings(scene, request.quality);
    p.frame = makeFrameUniforms(scene, cs, request.width, request.height, p.fs);
    applyShadowSettings(p.frame, request);
    applySunShadowSettings(p.frame, cs);
    applyVdbShadowSettings(p.frame, cs, request);
    const shd::FrameUniforms& frame = p.frame;
    p.dims = glm::ivec3(frame.froxelDims);
    BRUME_TRY(checkLimits(device, request.width, request.height, p.dims));
    p.mesh = tessellateGeometry(scene.geometry, frame);
    // The clusters do not depend on the jitter: built once for every frame of the call.
    p.clusters = buildLightClusters(cs, frame, request.lightCulling);
    // Voxelize runs over the froxels that can hold media (core/media_region.h). The light pass runs over
    // the temporal region (the media region and its one-froxel shell, Dispatch::RegionLightRuns), but
    // the shell's froxels have no media: their S is their emission, 0, whatever their lights and
    // transmittance cells hold, so the reach and the cells follow the media region's froxels, rounded
    // up to whole workgroups (the light pass's: runs along z).
    p.media = froxelRegions ? mediaFroxelRegion(cs, frame) : FroxelRegion{glm::ivec3(0), p.dims};
    const glm::ivec3 groupSize(shd::LIGHT_GROUP_X, shd::LIGHT_GROUP_Y, shd::LIGHT_RUN);
    const glm::ivec3 extent = p.media.hi - p.media.lo;
    const FroxelRegion lightFroxels{p.media.lo, glm::min(p.media.lo + (extent + groupSize - 1) / groupSize * groupSize, p.dims)};
    p.lightReach = buildLightReach(cs, frame, p.clusters, request.lightCulling, /*surfaces=*/!p.mesh.vertices.empty(),
                                   &lightFroxels);
    FrameKeys& k = p.keys;
    k.spec = sceneSpecKey(cs, frame, p.lightReach);
    k.froxelSpec = culledSpecKey(k.spec, froxelVolumesInReach(cs, frame));
    k.surfaceSpec = surfaceLightsSpecKey(culledSpecKey(k.spec, surfaceVolumesInReach(cs, frame)), cs, p.lightReach);
    k.surfaceFallback = k.spec;
    k.surfaceFallback[SpecId::SPEC_SURFACE_LIGHTS] = -1;
    return p;
}

}  // namespace

Result<bool> GpuRenderer::preparePipelines(const Scene& scene, const RenderRequest& request) {
    const std::pair<Scene, RenderRequest> one{scene, request};
    return preparePipelines(std::span(&one, 1));
}

namespace {

// A planned render and its shader variants (what preparePipelines and hasPipelines look up).
struct PlannedRender {
    FramePlan plan;
    VariantKey variant;
    // The passes of its frames: the temporal pass in motion or at rest is not known before the frame.
    std::array<FramePasses, 2> passes(const RenderRequest& request) const {
        std::array<FramePasses, 2> out;
        for (bool rest : {false, true}) {
            FramePasses& f = out[rest ? 1 : 0];
            f = FramePasses{variant, request.debugView != shd::DEBUG_VIEW_FINAL, false, false, plan.mesh.sphereVertices > 0};
            f.variant.temporalRest = rest;
        }
        return out;
    }
};

Result<PlannedRender> planRender(const Scene& scene, const RenderRequest& request, const Device& device,
                                 bool froxelRegions) {
    Result<FramePlan> planned = planFrames(scene, request, device, froxelRegions);
    if (!planned) return planned.error();
    Result<VariantKey> variant = variantOf(planned.value().cs);
    if (!variant) return variant.error();
    return PlannedRender{std::move(planned.value()), variant.value()};
}

}  // namespace

Result<bool> GpuRenderer::preparePipelines(std::span<const std::pair<Scene, RenderRequest>> renders) {
    // Every plan first: a scene that cannot be planned requests nothing.
    std::vector<PlannedRender> plans;
    for (const auto& [scene, request] : renders) {
        Result<PlannedRender> planned = planRender(scene, request, *s_->device, s_->froxelRegions);
        if (!planned) return planned.error();
        plans.push_back(std::move(planned.value()));
    }
    PipelineBatch batch;
    for (size_t i = 0; i < plans.size(); ++i) {
        const RenderRequest& request = renders[i].second;
        for (const FramePasses& passes : plans[i].passes(request)) {
            s_->requestPipelines(passes, plans[i].plan.keys, batch);
            if (request.pipelineFallbacks) s_->requestPipelines(passes, plans[i].plan.keys.fallbacks(), batch);
        }
    }
    const bool missing = batch.size() > 0;
    BRUME_TRY(batch.run());
    return missing;
}

Result<bool> GpuRenderer::hasPipelines(const Scene& scene, const RenderRequest& request) const {
    Result<PlannedRender> planned = planRender(scene, request, *s_->device, s_->froxelRegions);
    if (!planned) return planned.error();
    const FrameKeys& keys = planned.value().plan.keys;
    for (const FramePasses& passes : planned.value().passes(request))
        if (!s_->hasPipelines(passes, request.pipelineFallbacks ? s_->withFallbacks(passes, keys) : keys)) return false;
    return true;
}

Result<GpuRender> GpuRenderer::renderOnDevice(const Scene& scene, const RenderRequest& request) {
    return renderFrames(scene, request, false, false);
}

Result<GpuRender> GpuRenderer::renderFrames(const Scene& scene, const RenderRequest& request, bool readBackVolumes,
                                            bool readBackImage) {
    s_->compiled = false;
    Result<FramePlan> planned = planFrames(scene, request, *s_->device, s_->froxelRegions);
    if (!planned) return planned.error();
    FramePlan& plan = planned.value();
    CompiledScene& cs = plan.cs;
    const FroxelSettings& fs = plan.fs;
    shd::FrameUniforms frame = plan.frame;
    const glm::ivec3 dims = plan.dims;
    const glm::ivec2 size(request.width, request.height);
    const GeometryMesh& mesh = plan.mesh;

    // The same map as the CPU froxel renderer's (ray cast on the host); it does not follow the jitter.
    const SunShadowMap& sun = s_->sunShadow.get(cs, scene.geometry, frame, sunShadowMapResolution(request.quality),
                                                request.threads);
    const size_t sunBytes = sun.depth.size() * sizeof(float);
    const LocalShadowMaps& local = s_->localShadows.get(cs, scene.geometry, frame.localShadowTexels, request.threads);
    const size_t localBytes = local.depth.size() * sizeof(float);
    BRUME_TRY(s_->prepare(size, dims, cs, mesh.bytes(), frame.shadowReduction, sunBytes, localBytes,
                          readBackVolumes));
    if (readBackVolumes) BRUME_TRY(s_->ensureVolumeReadback(dims));
    FrameResources& r = s_->res;
    if (!cs.volumes.empty()) std::memcpy(r[BufferId::volumes].mapped, cs.volumes.data(), cs.volumes.size() * sizeof(shd::VolumeData));
    if (!cs.lights.empty()) std::memcpy(r[BufferId::lights].mapped, cs.lights.data(), cs.lights.size() * sizeof(shd::LightData));
    std::memcpy(r[BufferId::influence].mapped, &cs.influence.header, sizeof(shd::InfluenceHeader));
    if (!cs.influence.samples.empty())
        std::memcpy(static_cast<char*>(r[BufferId::influence].mapped) + sizeof(shd::InfluenceHeader),
                    cs.influence.samples.data(), cs.influence.samples.size() * sizeof(shd::InfluenceSample));
    const LightClusters& clusters = plan.clusters;
    std::memcpy(r[BufferId::lightClusters].mapped, clusters.records.data(), clusters.records.size() * sizeof(int));
    const FroxelRegion media = plan.media;
    r.mediaOrigin = media.lo;
    r.mediaExtent = media.hi - media.lo;
    const LightReach& lightReach = plan.lightReach;
    const std::vector<int> reach = lightReachRecord(lightReach, cs.lights.size());
    s_->keys = plan.keys;
    // Before the surfaces' reuse check reads the geometry key. The passes of every frame of the call:
    // the temporal pass's variant is the only one a frame decides, and it is not culled.
    if (request.pipelineFallbacks)
        s_->takeFallbacks(FramePasses{s_->variant, request.debugView != shd::DEBUG_VIEW_FINAL, false, readBackVolumes,
                                      mesh.sphereVertices > 0});
    r.mediaEmits = s_->keys.spec[SpecId::SPEC_EMISSION] != 0;
    s_->glow = glowDispatches(cs.lights, frame, lightReach.glowLights);  // the rectangles ignore the jitter
    writeSurfaceLights(r[BufferId::surfaceLights].mapped, cs.lights, lightReach);
    std::memcpy(static_cast<int*>(r[BufferId::lightClusters].mapped) + clusters.records.size(), reach.data(),
                reach.size() * sizeof(int));
    // The shadow volume pass dispatches only the layers some reader needs (core/light_reach.h), and in
    // each only the cells some reader needs: those around the media region's froxels whose clusters
    // list the layer's light (the whole volume when surfaces read vdb layers).
    const std::vector<FroxelRegion> listed = listedFroxelRegions(clusters, cs.lights.size(), media);
    r.shadowLayers.clear();
    for (size_t i = 0; i < cs.lights.size(); ++i) {
        if (lightReach.shadowVolume[i] == 0) continue;
        const FroxelRegion cells = shadowCellRegion(listed[i], frame, /*surfaces=*/!mesh.vertices.empty());
        if (!cells.empty()) r.shadowLayers.push_back({static_cast<int>(i), cells});
    }
    if (!mesh.vertices.empty()) std::memcpy(r.vertices.mapped, mesh.vertices.data(), mesh.bytes());
    std::memcpy(r[BufferId::sunShadowMap].mapped, &sun.fit, sizeof(sun.fit));
    if (sunBytes > 0)
        std::memcpy(static_cast<char*>(r[BufferId::sunShadowMap].mapped) + sizeof(sun.fit), sun.depth.data(), sunBytes);
    if (localBytes > 0) std::memcpy(r[BufferId::localShadowMaps].mapped, local.depth.data(), localBytes);

    // request.frames frames, each with its jitter and the previous one's history (core/temporal.h
    // decides, as for the CPU renderer); only the last is read back.
    s_->debugParams.view = glm::ivec4(request.debugView, request.debugSlice, 0, 0);
    s_->readBackImage = readBackImage;
    const uint64_t sceneKey = temporalSceneKey(cs, scene, dims);
    HistoryMode mode = request.history;
    const int frames = std::max(request.frames, 1);
    double wallMs = 0.0;
    for (int n = 0; n < frames; ++n) {
        const TemporalFrame t = beginTemporalFrame(s_->temporalState, scene, sceneKey, mode);
        mode = HistoryMode::Continue;
        frame = makeFrameUniforms(scene, cs, request.width, request.height, fs, t.jitter);
        writeLightGlowRadii(r[BufferId::lights].mapped, cs.lights, frame);
        applyShadowSettings(frame, request);  // as renderFroxelCpu
        applySunShadowSettings(frame, cs);
        applyVdbShadowSettings(frame, cs, request);
        setTemporalBlend(frame, s_->temporalState, t);
        s_->variant.temporalRest = shd::temporalAtRest(frame.temporal);
        // The light, temporal and integrate passes skip the froxels behind every integrated entry a
        // lookup reads (shaders/column_entries.glsl; docs/temporal.md, "Hidden froxels"); the column
        // ends pass records each column's end in the half of columnEnds this frame writes (w), so that
        // the next frame reads only the history this one wrote.
        frame.temporal.z = s_->skipHidden ? 1.0f : 0.0f;
        frame.temporal.w = static_cast<float>(t.writeIndex);
        // Temporal and integrate run over the media region and its neighbours; the history side written
        // now is cleared first if an older frame left values outside them (FrameResources).
        r.temporalRegion = temporalFroxelRegion(media, dims);
        r.distantFog = s_->keys.spec[SpecId::SPEC_DISTANT_FOG] != 0;
        std::tie(r.compositeLo, r.compositeHi) = compositePixels(r.temporalRegion, size, frame.froxelDims.w, r.distantFog);
        r.froxelTile = frame.froxelDims.w;
        FroxelRegion& written = r.historyWritten[static_cast<size_t>(t.writeIndex)];
        r.clearHistoryOut = !regionContains(r.temporalRegion, written);
        written = FroxelRegion{glm::ivec3(0), dims};  // unknown until the frame has run
        frame.mediaOriginX = media.lo.x, frame.mediaOriginY = media.lo.y, frame.mediaOriginZ = media.lo.z;
        std::memcpy(r[BufferId::frame].mapped, &frame, sizeof(frame));
        std::memcpy(r[BufferId::previousFrame].mapped, &s_->temporalState.frame, sizeof(frame));
        writeHistoryBindings(*s_->device, s_->bindings.set, r, t.writeIndex);
        // The surfaces follow the jitter only through the vdb layers of the shadow volume.
        std::vector<uint8_t> surfaces;
        if (request.reuseSurfaces)
            surfaces = surfaceInputs(frame, r, cs.volumes.size() * sizeof(shd::VolumeData),
                                     cs.lights.size() * sizeof(shd::LightData), reach, mesh.bytes(),
                                     ShadowMapsKey{sun.depth.data(), sun.depth.size(), s_->sunShadow.builds(),
                                                   local.depth.data(), local.depth.size(), s_->localShadows.builds()},
                                     s_->keys.surfaceSpec, s_->variant.shapes);
        s_->reuseSurfaces = request.reuseSurfaces && frame.vdbShadowSamples <= 0 && s_->surfacesValid &&
                            !s_->surfaceInputs.empty() && surfaces == s_->surfaceInputs;
        s_->surfacesValid = false;  // until this frame has run
        const bool last = n == frames - 1;
        BRUME_VK(vkResetCommandBuffer(s_->cmd, 0), "reset the command buffer");
        VkCommandBufferBeginInfo begin = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
        begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        BRUME_VK(vkBeginCommandBuffer(s_->cmd, &begin), "begin recording the frame");
        BRUME_TRY(s_->recordFrame(mesh, cs.ambient, frame.projection.w,
                                  last && readBackVolumes, t.writeIndex));
        BRUME_VK(vkEndCommandBuffer(s_->cmd), "record the frame");
        Result<double> wall = s_->submitAndWait();
        if (!wall) return wall.error();
        wallMs = wall.value();
        written = r.temporalRegion;
        s_->surfaceInputs = std::move(surfaces);
        s_->surfacesValid = true;
        endTemporalFrame(s_->temporalState, t, frame, sceneKey);
    }

    GpuRender out;
    out.wallMs = wallMs;
    out.dims = dims;
    if (readBackImage) out.image = imageFromReadback(static_cast<const glm::vec4*>(r.outputReadback.mapped), size);
    const auto* counters = static_cast<const shd::FroxelCounters*>(r[BufferId::counters].mapped);
    out.litFroxels = counters->litFroxels;
    // The light pass counts the froxels with sigma_t > 0; it skips the others, those outside the
    // media region too (they hold no media).
    out.skippedFroxels = size_t(int64_t(dims.x) * dims.y * dims.z) - out.litFroxels;
    out.overfullClusters = clusters.overfullClusters;
    out.allocated = s_->allocated;
    out.compiled = s_->compiled;
    Result<std::vector<PassTiming>> timings = s_->timer.read();
    if (!timings) return timings.error();
    out.passes = std::move(timings.value());
    if (readBackVolumes) {
        FroxelVolumes& v = out.volumes;
        v.dims = dims;
        v.frame = frame;
        // The READBACK images of the table, in its order.
        const std::array<std::vector<glm::vec4>*, 6> dst{&v.mediaScatteringG, &v.mediaExtinction, &v.mediaEmission,
                                                          &v.source, &v.integratedScattering, &v.integratedTransmittance};
        for (size_t i = 0; i < dst.size() && i < r.volumeReadback.size(); ++i) *dst[i] = readVolume(r.volumeReadback[i], dims, r.volumeReadbackFormat[i]);
        unpackHistory(v.source, v.mediaExtinction);
        v.litFroxels = out.litFroxels;
        v.skippedFroxels = out.skippedFroxels;
        v.overfullClusters = out.overfullClusters;
    }
    if (request.progress) request.progress(1.0f);
    return out;
}

}  // namespace brume::gpu
