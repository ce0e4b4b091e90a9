// The buffers and images of the froxel frame (declared in shaders/shared/frame_table.h, expanded in
// frame_table.h), recreated only when their sizes change.
//
//   frame (uniform) ---------------------------------------------------------> every pass
//   volumes, lights (storage) -> voxelize -> media* -> light -> sourceImage -> integrate -> integrated*
//   previousFrame, history in -> temporal or integrate_rest -> history out (resolved S, sigma_t) -> integrate, glow
//   geometry (raster) -> sceneColor, sceneDepth ------------------------------> composite -> outputImage
//
// Memory (rgba32f, 16 B per froxel per volume; the integrated transmittance rgba16, 8 B): 6 froxel
// volumes and 4 history volumes (temporal ping-pong pairs of S and sigma_t); at 1280x720 High
// (160x90x96 froxels) that is 9.5 x 22 MiB = 210 MiB, at Ultra (320x180x128) 9.5 x 113 MiB = 1.0 GiB.
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <memory>
#include <vector>

#include "core/media_region.h"
#include "frame_table.h"
#include "resources.h"

namespace brume::gpu {

struct FrameResources {
    std::array<Buffer, kBuffers.size()> buffers;
    // The texel views of shared/frame_table.h over their buffers (none while a buffer is being
    // replaced). Declared after the buffers: destroyed before them.
    std::array<BufferViewOwner, kTexelViews.size()> texelViews;
    std::array<GpuImage, kImages.size()> images;
    // Each history pair's two images, kept across frames (unlike the others): recreated with the
    // froxel images, then undefined until a first transition (historyUndefined) and unread until a
    // frame has written them. Which one sits behind the *_IN binding alternates every frame.
    std::array<std::array<GpuImage, 2>, kHistory.size()> history;
    bool historyUndefined = true;

    Buffer& operator[](BufferId id) { return buffers[static_cast<size_t>(id)]; }
    const Buffer& operator[](BufferId id) const { return buffers[static_cast<size_t>(id)]; }
    GpuImage& operator[](ImageId id) { return images[static_cast<size_t>(id)]; }
    const GpuImage& operator[](ImageId id) const { return images[static_cast<size_t>(id)]; }
    // The image behind ref this frame (writeIndex: the history side written this frame).
    const GpuImage& image(ResRef ref, int writeIndex) const;

    glm::ivec3 froxelDims{0};  // of the image3D resources
    // Whether the MEDIA images (voxelize's output) have froxelDims too; else one texel each, bound for
    // the descriptors only (frames that do not run voxelize: VariantKey::inlineMedia).
    bool mediaImages = false;
    glm::ivec2 size{0};        // of the image2D resources
    // Each computed layer of the fog transmittance volume: its light, and the cells the shadow volume
    // pass computes in it (core/media_region.h shadowCellRegion of the froxels whose clusters list the
    // light, core/light_reach.h listedFroxelRegions); one dispatch per layer, pushed as
    // shd::FroxelRegionParams with the light in lo.w (shaders/shadow_volume.comp).
    struct ShadowLayer {
        int light = 0;
        FroxelRegion cells;
    };
    std::vector<ShadowLayer> shadowLayers;
    // The pixels the composite dispatch covers, [lo, hi) (gpu_renderer.cpp compositePixels); the
    // others get sceneColor copied (frame_executor.cpp recordComposite).
    glm::ivec2 compositeLo{0};
    glm::ivec2 compositeHi{0};
    int froxelTile = 1;  // pixels per froxel column (FrameUniforms.froxelDims.w)
    // Height or depth fog past the froxel far this frame (SPEC_DISTANT_FOG): the composite dispatches
    // over the nearTiles list (compositeLo, compositeHi then the whole screen), the composite far, all
    // far and sky over farTiles, allFarTiles and skyTiles (shaders/tile_lists.comp). Without it the
    // depth tiles, distant fog and tile lists passes
    // dispatch nothing (their shaders would return at once).
    bool distantFog = false;
    // The froxels the voxelize and light passes dispatch over (core/media_region.h); the rest of
    // the media and source images is cleared to 0 when it is not the whole grid.
    glm::ivec3 mediaOrigin{0};
    glm::ivec3 mediaExtent{0};
    // Whether some volume emits (SPEC_EMISSION): if not, voxelize does not store mediaEmission and the
    // frame clears it to 0 for the read-back volumes (frame_executor.cpp recordClearMedia).
    bool mediaEmits = true;
    // The froxels the temporal and integrate passes compute (core/media_region.h temporalFroxelRegion).
    FroxelRegion temporalRegion;
    // Per history side: the froxels that may hold non-zero values (the last region written there; the
    // whole grid while unknown). The temporal pass clears the side it writes when that is not inside
    // this frame's region, so that no history outside the region lingers (clearHistoryOut).
    std::array<FroxelRegion, 2> historyWritten;
    bool clearHistoryOut = false;

    Buffer vertices;  // GeometryVertex[] of the geometry pass (not in the descriptor set)
    // The grids behind buffers[vdbGrids], in order; held so that a new grid cannot reuse a freed one's address.
    std::vector<std::shared_ptr<const DensityGrid>> vdbGridsUploaded;
    Buffer outputReadback;  // outputImage, every frame
    std::vector<Buffer> volumeReadback;  // the READBACK images, in table order, when asked for
    std::vector<VkFormat> volumeReadbackFormat;  // the format of the image each one was copied from
};

}  // namespace brume::gpu
