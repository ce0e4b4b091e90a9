// The pass table: the froxel frame's passes in execution order, each with what it reads and writes
// (the executor, frame_executor.cpp, derives the barriers from these lists), its dispatch rule and its
// shader variants. Adding a pass is one entry here, its shader, and (only if it needs more than bind
// + dispatch) its record code in a pass_*.cpp file.
#include "frame_table.h"

#include "shaders/shared/brume.h"

namespace brume::gpu {
namespace {

using B = BufferId;
using I = ImageId;
using H = HistoryId;
using T = TexelViewId;

}  // namespace

// clang-format off
const std::array<PassDecl, 18> kPasses{{
    // Each shadowing light's fog transmittance on the reduced grid (shared/shadow_volume.h); the
    // light passes read it, and with vdb grids the geometry pass's surfaces its vdb layers: in scenes
    // with vdb grids it runs here, before them (the entry after the column ends is left out).
    {"shadow volume", "shadow_volume", Variant::ShadowVolumeVdb, Dispatch::ShadowCells, When::VdbScene, Record::ShadowCells,
     {B::frame, T::volumeTexels, B::lights, B::lightClusters, T::vdbGridTexels},
     {B::shadowTransmittance}, true, true},
    // Planes, boxes and spheres rasterized and shaded like core/geometry.cpp shadeSurface with the
    // fog's shadow and the shadow maps; sky = ambient at the camera far. Specialized with the volumes
    // out of the surfaces' reach culled (core/media_region.h surfaceVolumesInReach; frame_executor.cpp).
    {"geometry", "geometry", Variant::None, Dispatch::Raster, When::SurfacesChanged, Record::Geometry,
     {B::frame, T::lightTexels, T::lightClusterTexels, T::shadowTexels, T::sunShadowTexels, T::localShadowTexels,
      T::volumeTexels, B::surfaceLights},
     {I::sceneColor, I::sceneDepth}, true},
    // The deepest and shallowest scene depth of each 8x8 pixel tile: integrate keeps the entries of
    // each column its pixels can read, and with distant fog the distant fog pass's corners and the
    // composite's tile lists read it (shared/distant_table.h).
    {"depth tiles", "depth_tiles", Variant::None, Dispatch::DepthTiles, When::SurfacesChanged, Record::Dispatch,
     {B::frame, I::sceneDepth}, {B::depthTiles}, true},
    // Each froxel column's entries that lookups read and its walk end (shaders/column_entries.glsl): the
    // froxels behind its deepest stored integrated entry are neither lit nor resolved. Into this frame's
    // half of columnEnds; the other half keeps the previous frame's, which the temporal and integrate
    // passes read for the history.
    {"column ends", "column_ends", Variant::None, Dispatch::Columns, When::Always, Record::ColumnEnds,
     {B::frame, T::depthTileTexels}, {B::columnEnds}, true},
    // The shadow volume in scenes without vdb grids (the surfaces read none of it): after the column
    // ends, each cell column only down to the deepest cell this frame's froxels read (shadow_volume.comp).
    {"shadow volume", "shadow_volume", Variant::Shapes, Dispatch::ShadowCells, When::NoVdbScene, Record::ShadowCells,
     {B::frame, T::volumeTexels, B::lights, B::lightClusters, T::vdbGridTexels, T::columnEndTexels},
     {B::shadowTransmittance}, true, true},
    // Media of every volume at each froxel's sample point, over the froxels that can hold media
    // (core/media_region.h); the rest of the media and source images is cleared to 0.
    // Specialized: SPEC_INFLUENCERS compiles the influencers' factor out of scenes without them.
    {"voxelize", "voxelize", Variant::Voxelize, Dispatch::MediaFroxels, When::Always, Record::ClearMedia,
     {B::frame, T::volumeTexels, T::vdbGridTexels, T::influenceTexels},
     {I::mediaScatteringG, I::mediaExtinction, I::mediaEmission, I::sourceImage, I::sourceExtinction}, true, true},
    // Source S = sigma_s x (lights x fog transmittance x shadow maps + ambient) + emission, with the
    // shadow volume's trusted blends; lists the froxels where a blend is not trusted (light_body.glsl).
    // Without vdb volumes (_media) it computes the media itself (VariantKey::inlineMedia). S and sigma_t
    // go out in 6 words, sourceImage (S, sigma_t.r) and sourceExtinction (sigma_t.gb).
    // Each column only down to its walk end (columnEnds): the froxels behind are never read.
    {"light", "light", Variant::LightMedia, Dispatch::RegionLightRuns, When::Always, Record::Dispatch,
     {B::frame, T::volumeTexels, T::lightTexels, T::lightClusterTexels, T::shadowTexels, T::sunShadowTexels,
      T::localShadowTexels, T::vdbGridTexels, T::influenceTexels, I::mediaScatteringG, I::mediaExtinction, I::mediaEmission,
      T::columnEndTexels},
     {I::sourceImage, I::sourceExtinction, B::counters, B::exactList}, true, true},
    // S again at the listed froxels only, with the exact closed-form transmittance where needed.
    {"light exact", "light_exact", Variant::LightMedia, Dispatch::Indirect, When::Always, Record::Dispatch,
     {B::frame, T::volumeTexels, T::lightTexels, T::lightClusterTexels, T::shadowTexels, T::sunShadowTexels,
      T::localShadowTexels, T::vdbGridTexels, T::influenceTexels, I::mediaScatteringG, I::mediaExtinction, I::mediaEmission,
      B::exactList},
     {I::sourceImage}, true, true, B::exactList},
    // S and sigma_t blended with the reprojected history (shared/temporal.h) over the temporal region
    // (core/media_region.h) into the history's output, which the later passes read. At rest it only
    // clears stale history: integrate_rest resolves each froxel itself.
    {"temporal", "temporal", Variant::None, Dispatch::RegionRuns, When::Always, Record::TemporalCopy,
     {B::frame, B::previousFrame, I::sourceImage, I::sourceExtinction, historyIn(H::historySource),
      historyIn(H::historyExtinction), T::columnEndTexels},
     {historyOut(H::historySource), historyOut(H::historyExtinction)}},
    // Front to back along each froxel column (closed-form slabs), over the temporal region's columns.
    // At rest (_rest) it first resolves each froxel with its own history, writing the history's output
    // as the temporal pass would have. The resolved S and sigma_t are read from the history's output
    // from here on (glow, debug view, readback): in motion the temporal pass wrote them there too.
    {"integrate", "integrate", Variant::Temporal, Dispatch::IntegrateColumns, When::Always, Record::Integrate,
     {B::frame, T::columnEndTexels, I::sourceImage, I::sourceExtinction, historyIn(H::historySource), historyIn(H::historyExtinction),
      historyOut(H::historySource), historyOut(H::historyExtinction)},
     {I::integratedScattering, I::integratedTransmittance, historyOut(H::historySource), historyOut(H::historyExtinction)}},
    // The height and depth fog past the froxel far, in closed form per tile corner and depth
    // (shared/distant_table.h), up to the deepest entry the corner's pixels read (their depth tiles);
    // the composite interpolates it.
    {"distant fog", "distant_fog", Variant::Shapes, Dispatch::TileCorners, When::SurfacesChanged, Record::Dispatch,
     {B::frame, T::volumeTexels, T::lightTexels, T::lightClusterTexels, T::depthTileTexels, B::surfaceLights},
     {B::distantTable}, true},
    // With distant fog, the tiles within the froxel far, those past it, those all sky and the others,
    // as four indirect dispatches (one invocation per row of depth tiles: tile_lists.comp).
    {"tile lists", "tile_lists", Variant::None, Dispatch::TileRows, When::Always, Record::Dispatch,
     {B::frame, T::depthTileTexels}, {B::nearTiles, B::farTiles, B::allFarTiles, B::skyTiles}, true},
    // Fog over the surfaces from the integrated volume: the region's pixels, or with distant fog the
    // near tiles (composite_body.glsl).
    {"composite", "composite", Variant::None, Dispatch::CompositePixels, When::Always, Record::Composite,
     {B::frame, T::nearTileTexels, I::integratedScattering, I::integratedTransmittance, I::sceneColor, I::sceneDepth},
     {I::outputImage}, true},
    // The far tiles: fog continued past the froxel far from the distant fog table.
    {"composite far", "composite_far", Variant::None, Dispatch::Indirect, When::Always, Record::Dispatch,
     {B::frame, T::farTileTexels, T::distantTexels, I::integratedScattering, I::integratedTransmittance, I::sceneColor,
      I::sceneDepth},
     {I::outputImage}, true, false, B::farTiles},
    // The tiles wholly past the froxel far: as the far tiles, the integrated volume's last entry read once.
    {"composite all far", "composite_all_far", Variant::None, Dispatch::Indirect, When::Always, Record::Dispatch,
     {B::frame, T::allFarTileTexels, T::distantTexels, I::integratedScattering, I::integratedTransmittance, I::sceneColor,
      I::sceneDepth},
     {I::outputImage}, true, false, B::allFarTiles},
    // The tiles whose pixels are all sky: the integrated volume's last entry and the table's, no depth.
    {"composite sky", "composite_sky", Variant::None, Dispatch::Indirect, When::Always, Record::Dispatch,
     {B::frame, T::skyTileTexels, T::distantTexels, I::integratedScattering, I::integratedTransmittance, I::sceneColor},
     {I::outputImage}, true, false, B::skyTiles},
    // The point and spot lights' glow per pixel (shared/glow.h, which reads the media at the light),
    // added to the output over each glowing light's screen rectangle only.
    // Specialized like the froxel passes: the _media variants evaluate the froxel passes' volume list.
    {"glow", "glow", Variant::GlowMedia, Dispatch::GlowRects, When::Always, Record::Glow,
     {B::frame, T::lightTexels, T::volumeTexels, T::vdbGridTexels, T::influenceTexels, I::integratedTransmittance, I::sceneDepth,
      I::mediaScatteringG, historyOut(H::historySource), historyOut(H::historyExtinction), I::outputImage},
     {I::outputImage}, true, true},
    // One depth slice of density, scattering or transmittance over the output (only when asked).
    {"debug view", "debug_view", Variant::None, Dispatch::Screen, When::DebugView, Record::DebugView,
     {B::frame, historyOut(H::historyExtinction), historyOut(H::historySource), I::integratedTransmittance},
     {I::outputImage}},
}};
// clang-format on

VkFormat vkFormat(ImageFormat f) {
    switch (f) {
        case ImageFormat::rgba16: return VK_FORMAT_R16G16B16A16_UNORM;
        case ImageFormat::r32f: return VK_FORMAT_R32_SFLOAT;
        case ImageFormat::r32i: return VK_FORMAT_R32_SINT;
        case ImageFormat::rgba32i: return VK_FORMAT_R32G32B32A32_SINT;
        case ImageFormat::rg32f: return VK_FORMAT_R32G32_SFLOAT;
        case ImageFormat::rgba32f: break;
    }
    return VK_FORMAT_R32G32B32A32_SFLOAT;
}

VkDeviceSize texelBytes(ImageFormat f) {
    if (f == ImageFormat::r32f || f == ImageFormat::r32i) return 4;
    return f == ImageFormat::rgba16 || f == ImageFormat::rg32f ? 8 : 16;
}

VkDescriptorType descriptorType(BufferKind k) {
    return k == BufferKind::UNIFORM ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
}

bool hostWrites(BufferKind k) { return k == BufferKind::UNIFORM || k == BufferKind::STORAGE; }

std::array<BindingDecl, kBindingCount> bindingTable() {
    std::array<BindingDecl, kBindingCount> t{};
    for (BindingDecl& b : t) b.binding = -1;
    auto put = [&](int binding, BindingDecl d) {
        if (binding >= 0 && binding < kBindingCount) t[static_cast<size_t>(binding)] = d;
    };
    // Buffers are named by their GLSL block, images by their variable.
#define BRUME_CPP_BUFFER_BINDING(id, binding, kind, layout, qualifiers, block, body) \
    put(binding, {binding, #block, descriptorType(BufferKind::kind), false, ImageFormat::rgba32f, false});
    BRUME_FRAME_BUFFERS(BRUME_CPP_BUFFER_BINDING)
#undef BRUME_CPP_BUFFER_BINDING
    for (const ImageDecl& d : kImages)
        put(d.binding, {d.binding, d.name, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, true, d.format, true});
    for (const HistoryDecl& d : kHistory) {
        put(d.inBinding, {d.inBinding, d.inName, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, true, d.format, true});
        put(d.outBinding, {d.outBinding, d.outName, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, true, d.format, true});
    }
    // Texel views reach the geometry pass too (it reads the fog transmittance volume's vdb layers).
    for (const TexelViewDecl& d : kTexelViews)
        put(d.binding, {d.binding, d.name, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, true, d.format, false});
    return t;
}

std::string variantShaderName(const char* shader, Variant v, const VariantKey& k) {
    std::string name = shader;
    const bool quantized = k.vdb && k.encoding != VdbEncoding::Float;
    if (v == Variant::Voxelize) {
        if (k.vdb) name += "_vdb";
        if (k.textures) name += "_texture";
        if (quantized) name += std::string("_") + toString(k.encoding);
    } else if (v == Variant::ShadowVolumeVdb) {
        name += "_vdb";
        if (quantized) name += std::string("_") + toString(k.encoding);
    }
    if ((v == Variant::LightMedia || v == Variant::GlowMedia) && k.inlineMedia()) {
        name += "_media";
        if (k.textures) name += "_texture";
    }
    if ((v == Variant::ShadowVolumeVdb || v == Variant::Shapes || v == Variant::LightMedia) && k.shapes) name += "_shapes";
    if (v == Variant::Temporal && k.temporalRest) name += "_rest";
    return name + ".comp";
}

VkPipelineStageFlags passStages(const PassDecl& p) {
    if (p.dispatch == Dispatch::Raster)
        return VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT |
               VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    if (p.record == Record::TemporalCopy || p.record == Record::Integrate) return VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
    if (p.dispatch == Dispatch::Indirect || p.dispatch == Dispatch::CompositePixels)
        return VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT;  // reads its group count
    return VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
}

}  // namespace brume::gpu
