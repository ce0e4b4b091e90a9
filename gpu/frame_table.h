// The GPU froxel frame as data: the resource tables of shaders/shared/frame_table.h expanded for C++,
// and the pass table (frame_table.cpp) that names what each pass reads and writes. The executor
// (frame_executor.cpp) derives the rest: creation and debug names, the descriptor layout, pool and
// writes, layout transitions, barriers, labels, timestamps, the readback order, and one pipeline per
// shader variant. Not a general render graph: the chain is fixed and short, nothing is aliased but
// the texel views (each reads its buffer's memory) and everything runs on one queue.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>

#include <vulkan/vulkan.h>

#include "core/density_grid.h"
#include "shaders/shared/frame_table.h"

namespace brume::gpu {

// ---- Resources (expanded from shaders/shared/frame_table.h) ----

enum class BufferId : uint8_t {
#define BRUME_CPP_BUFFER_ID(id, ...) id,
    BRUME_FRAME_BUFFERS(BRUME_CPP_BUFFER_ID)
#undef BRUME_CPP_BUFFER_ID
};
enum class ImageId : uint8_t {
#define BRUME_CPP_IMAGE_ID(id, ...) id,
    BRUME_FRAME_IMAGES(BRUME_CPP_IMAGE_ID)
#undef BRUME_CPP_IMAGE_ID
};
enum class HistoryId : uint8_t {
#define BRUME_CPP_HISTORY_ID(id, ...) id,
    BRUME_FRAME_HISTORY(BRUME_CPP_HISTORY_ID)
#undef BRUME_CPP_HISTORY_ID
};
enum class TexelViewId : uint8_t {
#define BRUME_CPP_TEXEL_VIEW_ID(id, ...) id,
    BRUME_FRAME_TEXEL_VIEWS(BRUME_CPP_TEXEL_VIEW_ID)
#undef BRUME_CPP_TEXEL_VIEW_ID
};

// The table's kind, format and shape tokens, given meaning.
enum class BufferKind : uint8_t { UNIFORM, STORAGE, STORAGE_GPU, STORAGE_READBACK, STORAGE_INDIRECT };
// r32i and rgba32i: texel views only (lightClusters, lights as their stored bits). rgba16: 16-bit
// unsigned normalized, for a froxel volume in [0, 1] (shared/frame_table.h: the integrated transmittance).
enum class ImageFormat : uint8_t { rgba32f, rgba16, r32f, r32i, rgba32i, rg32f };
enum class ImageShape : uint8_t { image2D, image3D };
namespace image_flags {
inline constexpr unsigned FRAME = 1u, READBACK = 2u, TARGET = 4u, OUTPUT = 8u, MEDIA = 16u;
inline constexpr unsigned FRAME_READBACK = FRAME | READBACK, FRAME_OUTPUT = FRAME | OUTPUT;
inline constexpr unsigned FRAME_READBACK_MEDIA = FRAME_READBACK | MEDIA, FRAME_MEDIA = FRAME | MEDIA;
}  // namespace image_flags

struct BufferDecl {
    BufferId id;
    const char* name;
    int binding;
    BufferKind kind;
};
struct ImageDecl {
    ImageId id;
    const char* name;
    int binding;
    ImageFormat format;
    ImageShape shape;  // image3D: the froxel grid; image2D: the screen
    unsigned flags;    // image_flags
};
// A uniform texel buffer view of `buffer` (its whole range, as `format` texels).
struct TexelViewDecl {
    TexelViewId id;
    const char* name;
    int binding;
    BufferId buffer;
    ImageFormat format;
};
struct HistoryDecl {
    HistoryId id;
    const char* name;
    const char* inName;
    int inBinding;
    const char* outName;
    int outBinding;
    ImageFormat format;
};

inline constexpr std::array kBuffers{
#define BRUME_CPP_BUFFER(id, binding, kind, layout, qualifiers, block, body) \
    BufferDecl{BufferId::id, #id, binding, BufferKind::kind},
    BRUME_FRAME_BUFFERS(BRUME_CPP_BUFFER)
#undef BRUME_CPP_BUFFER
};
inline constexpr std::array kImages{
#define BRUME_CPP_IMAGE(id, binding, format, shape, flags) \
    ImageDecl{ImageId::id, #id, binding, ImageFormat::format, ImageShape::shape, image_flags::flags},
    BRUME_FRAME_IMAGES(BRUME_CPP_IMAGE)
#undef BRUME_CPP_IMAGE
};
inline constexpr std::array kHistory{
#define BRUME_CPP_HISTORY(id, inName, inBinding, outName, outBinding, format, shape) \
    HistoryDecl{HistoryId::id, #id, #inName, inBinding, #outName, outBinding, ImageFormat::format},
    BRUME_FRAME_HISTORY(BRUME_CPP_HISTORY)
#undef BRUME_CPP_HISTORY
};
inline constexpr std::array kTexelViews{
#define BRUME_CPP_TEXEL_VIEW(id, binding, buffer, format) \
    TexelViewDecl{TexelViewId::id, #id, binding, BufferId::buffer, ImageFormat::format},
    BRUME_FRAME_TEXEL_VIEWS(BRUME_CPP_TEXEL_VIEW)
#undef BRUME_CPP_TEXEL_VIEW
};
inline constexpr int kBindingCount =
    static_cast<int>(kBuffers.size() + kImages.size() + 2 * kHistory.size() + kTexelViews.size());

constexpr const BufferDecl& decl(BufferId id) { return kBuffers[static_cast<size_t>(id)]; }
constexpr const ImageDecl& decl(ImageId id) { return kImages[static_cast<size_t>(id)]; }
constexpr const HistoryDecl& decl(HistoryId id) { return kHistory[static_cast<size_t>(id)]; }
constexpr const TexelViewDecl& decl(TexelViewId id) { return kTexelViews[static_cast<size_t>(id)]; }
// Whether some texel view reads buffer `id` (its usage then includes uniform texel buffer).
constexpr bool hasTexelView(BufferId id) {
    for (const TexelViewDecl& v : kTexelViews)
        if (v.buffer == id) return true;
    return false;
}

VkFormat vkFormat(ImageFormat f);
// Bytes per texel of format f.
VkDeviceSize texelBytes(ImageFormat f);
VkDescriptorType descriptorType(BufferKind k);
// Whether the host fills the buffer (mapped upload memory) rather than the passes.
bool hostWrites(BufferKind k);

// One descriptor binding of the set, whatever resource is behind it (tests check these against the
// shaders' reflection).
struct BindingDecl {
    int binding;
    const char* glslName;  // the variable (images, texel views) or block (buffers) name in GLSL
    VkDescriptorType type;
    bool image;            // a GLSL variable (storage image or texel view), else a block
    ImageFormat format;    // images and texel views only
    bool computeOnly;      // storage images: only compute stages see them
};
std::array<BindingDecl, kBindingCount> bindingTable();

// ---- Passes ----

// A resource a pass reads or writes. History: the pair's input (read) or output (written) side.
// TexelView: read only; its memory is its buffer's (memoryOf).
struct ResRef {
    enum class Kind : uint8_t { None, Buffer, Image, HistoryIn, HistoryOut, TexelView } kind = Kind::None;
    uint8_t index = 0;
    constexpr ResRef() = default;
    constexpr ResRef(BufferId b) : kind(Kind::Buffer), index(static_cast<uint8_t>(b)) {}
    constexpr ResRef(ImageId i) : kind(Kind::Image), index(static_cast<uint8_t>(i)) {}
    constexpr ResRef(TexelViewId v) : kind(Kind::TexelView), index(static_cast<uint8_t>(v)) {}
    constexpr ResRef(Kind k, uint8_t i) : kind(k), index(i) {}
    constexpr bool operator==(const ResRef&) const = default;
};
constexpr ResRef historyIn(HistoryId h) { return {ResRef::Kind::HistoryIn, static_cast<uint8_t>(h)}; }
constexpr ResRef historyOut(HistoryId h) { return {ResRef::Kind::HistoryOut, static_cast<uint8_t>(h)}; }
// The resource whose memory r reads or writes: a texel view's buffer, else r itself (barriers).
constexpr ResRef memoryOf(ResRef r) {
    return r.kind == ResRef::Kind::TexelView ? ResRef(kTexelViews[r.index].buffer) : r;
}

struct ResList {
    static constexpr size_t kCapacity = 16;
    std::array<ResRef, kCapacity> items{};
    int count = 0;
    // More entries than kCapacity: the rest are dropped and this is set (tests/test_frame_table.cpp
    // checks that no pass's list overflows).
    bool overflow = false;
    constexpr ResList(std::initializer_list<ResRef> list) : overflow(list.size() > kCapacity) {
        for (ResRef r : list)
            if (static_cast<size_t>(count) < kCapacity) items[static_cast<size_t>(count++)] = r;
    }
    constexpr const ResRef* begin() const { return items.data(); }
    constexpr const ResRef* end() const { return items.data() + count; }
    constexpr bool contains(ResRef r) const {
        for (ResRef x : *this)
            if (x == r) return true;
        return false;
    }
};

// How many invocations a compute pass runs (workgroup sizes: shaders/shared/types.h).
enum class Dispatch : uint8_t {
    MediaFroxels, // one per froxel of the media region (FrameResources::mediaOrigin, mediaExtent), FROXEL_GROUP_*
    RegionLightRuns,  // one per run of LIGHT_RUN froxels along z of the temporal region (pushed), LIGHT_GROUP_*
                      // (bindings.h)
    RegionRuns,     // one per run of TEMPORAL_RUN froxels along z of the temporal region, TEMPORAL_GROUP_* (bindings.h)
    IntegrateColumns,  // one per froxel column of integrateColumns (passes.h), INTEGRATE_GROUP_*
    Columns,      // one per froxel column, INTEGRATE_GROUP_*
    Screen,       // one per pixel, SCREEN_GROUP_*
    CompositePixels,  // one per pixel that can read fog (FrameResources::compositeLo, compositeHi), SCREEN_GROUP_*;
                      // with distant fog (FrameResources::distantFog) one workgroup per nearTiles entry (indirect)
    Indirect,     // the workgroups PassDecl::indirect's list header counts (the exact froxels' groups, one
                  // per listed tile of shaders/tile_lists.comp)
    TileRows,     // one invocation per row of 8x8 pixel tiles, TILE_LIST_GROUP rows per workgroup, with
                  // distant fog only (the tile lists)
    ShadowCells,  // one per shadow volume cell some reader needs, a dispatch per layer (FrameResources::shadowLayers)
    TileCorners,  // one per corner of the screen's 8x8 pixel tiles (shared/distant_table.h), SCREEN_GROUP_*,
                  // with distant fog only (FrameResources::distantFog)
    DepthTiles,   // one per 8x8 pixel tile of the screen (shared/distant_table.h depthTileCount), SCREEN_GROUP_*,
                  // with distant fog only (as TileCorners)
    GlowRects,    // one dispatch per glowing light over its screen rectangle (shared/glow.h), SCREEN_GROUP_*
    Raster,       // the geometry pass's draw (not a dispatch)
};

// Which shader variants exist (shaders/CMakeLists.txt builds one SPIR-V per variant).
enum class Variant : uint8_t {
    None,          // the shader as named
    Voxelize,      // _vdb when the scene has vdb volumes, _texture with density textures, _fp16/_fp8 per encoding
    ShadowVolumeVdb,  // _vdb, then _fp16/_fp8 per encoding (the vdb volumes' encoding); then _shapes as Shapes:
                      // the shadow volume's place for scenes with vdb volumes (When::VdbScene)
    Shapes,        // _shapes when some volume needs the sampled fog shadow integral (shared/shadows.h)
    LightMedia,    // the light passes: _media (then _texture with density textures) without vdb volumes
                   // (VariantKey::inlineMedia), then _shapes as Shapes
    GlowMedia,     // the glow: _media (then _texture) without vdb volumes
    Temporal,      // _rest when the view rests or there is no history (shared/temporal.h temporalAtRest):
                   // integrate_rest resolves the history, and the temporal pass dispatches nothing
};

// What selects a variant; one per frame.
struct VariantKey {
    bool vdb = false;       // the scene has vdb volumes
    bool textures = false;  // some volume has a density texture
    VdbEncoding encoding = VdbEncoding::Float;
    bool shapes = false;    // some volume needs the sampled fog shadow integral (shd::needsShapeShadows)
    bool temporalRest = false;  // this frame's shd::temporalAtRest(frame.temporal)
    bool operator==(const VariantKey&) const = default;
    // Without vdb volumes the light passes and the glow compute the media where they use them
    // (shaders/media_at.glsl; their _media variants), and voxelize runs only when the media volumes are
    // read back: its stores cost more than the media's arithmetic (docs/performance.md, "fuse"). With vdb
    // volumes the grid walk would cost every froxel of the light pass, so voxelize stores the media.
    bool inlineMedia() const { return !vdb; }
};

// The embedded SPIR-V name of `shader`'s variant for key k, e.g. "voxelize_vdb_texture_fp16.comp".
std::string variantShaderName(const char* shader, Variant v, const VariantKey& k);

// Whether a pass runs this frame.
// SurfacesChanged: skipped when the GPU renderer keeps the previous frame's output of the pass
// (RenderRequest::reuseSurfaces; gpu_renderer.cpp surfaceInputs): the pass reads nothing that
// changed since, and its outputs (scene colour and depth, the distant fog table) outlive frames.
// VdbScene / NoVdbScene: the shadow volume pass's two places in the frame. With vdb grids (VariantKey::
// vdb) it runs first, since the geometry pass's surfaces read its vdb layers; without, after the column
// ends pass, so that it computes only the cells this frame's froxels read (shadow_volume.comp).
enum class When : uint8_t { Always, DebugView, SurfacesChanged, VdbScene, NoVdbScene };

// Pass-specific recording beyond bind + dispatch (pass_*.cpp).
enum class Record : uint8_t {
    Dispatch,      // bind the pipeline and the set, dispatch by the rule
    Geometry,      // the raster pass (pass_geometry.cpp)
    TemporalCopy,  // the history's output cleared where stale, the dispatch, then (in motion) the
                   // history's output copied over source and extinction (pass_temporal.cpp)
    Integrate,     // the integrated volumes cleared outside a partial temporal region, then the dispatch
    ColumnEnds,    // push the entries stored in every column (pass_temporal.cpp storedEverywhere), dispatch
    ClearMedia,    // clear the media and source images outside a partial media region, then dispatch (frame_executor.cpp)
    DebugView,     // push the debug parameters, then dispatch (pass_debug_view.cpp)
    Glow,          // per glowing light: push its rectangle, dispatch, barrier (pass_glow.cpp)
    ShadowCells,   // per computed layer: push its light and cells, dispatch (frame_executor.cpp)
    Composite,     // copy the background where no fog is, push the pixels, dispatch (frame_executor.cpp)
};

struct PassDecl {
    const char* label;   // debug label and timing name
    const char* shader;  // base shader name (without ".comp"); the raster pass names its own
    Variant variant;
    Dispatch dispatch;
    When when;
    Record record;
    ResList reads;
    ResList writes;
    // Built with this frame's specialization constants (shaders/shared/specialization.h, pipeline.h
    // SpecKey): code for what the scene lacks is compiled out. Otherwise the shader's defaults.
    bool specialized = false;
    // With `specialized`: the froxel passes' key, where the volumes out of this frame's froxel reach
    // are listed as SPEC_CULLED_VOLUME (core/media_region.h froxelVolumesInReach), unless the frame
    // takes the fallbacks (renderer_state.h FrameKeys). The raster pass (geometry) takes the key with
    // the volumes out of the surfaces' reach culled instead, or its own fallback.
    bool culledVolumes = false;
    // With Dispatch::Indirect: the list whose header (ExactListHeader) holds the dispatch's group count,
    // written by an earlier pass (the light pass, tile_lists.comp).
    std::optional<BufferId> indirect{};
};

// In execution order; the reads and writes of each entry decide the barriers before it.
extern const std::array<PassDecl, 18> kPasses;

// Pipeline stages a pass runs in (barriers).
VkPipelineStageFlags passStages(const PassDecl& p);

}  // namespace brume::gpu
