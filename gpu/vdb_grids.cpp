// The vdb grid buffer (BINDING_VDB_GRIDS): every vdb volume's NanoVDB grid uploaded as is, back to
// back at the offsets compileScene wrote into VolumeData.kind.y, each followed by its occupancy cells
// (kind.w), then every density texture's grid (VolumeData.textureMin.w). No dense copy: GPU memory is
// the sum of the NanoVDB sizes plus the cells (0.3% on the smoke; no geometric growth as for the other
// buffers).
#include <algorithm>
#include <cstring>
#include <string>

#include "renderer_state.h"
#include "vk_check.h"

namespace brume::gpu {
namespace {

std::string mib(VkDeviceSize bytes) {
    return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB";
}

}  // namespace

Result<void> GpuRenderer::State::ensureVdbGrids(const CompiledScene& cs, bool& dirty) {
    std::vector<DensityGridPtr> grids;
    VkDeviceSize total = 0;
    for (const auto* list : {&cs.grids, &cs.textures})
        for (const DensityGridPtr& g : *list) {
            if (!g) continue;
            grids.push_back(g);
            total += g->size();
        }
    if (res.vdbGrids.buffer && grids == res.vdbGridsUploaded) return {};
    // One binding addresses the whole buffer; lavapipe allows 128 MiB (its maxStorageBufferRange).
    const VkDeviceSize limit = device->limits().maxStorageBufferRange;
    if (total > limit)
        return Error{"The scene's vdb grids take " + mib(total) + " as NanoVDB, more than the " + mib(limit) +
                     " one GPU storage buffer can address on this device; use fewer or smaller grids.",
                     /*badInput=*/true};
    const VkDeviceSize size = std::max<VkDeviceSize>(total, 32);
    if (!res.vdbGrids.buffer || res.vdbGrids.size != size) {
        res.vdbGrids = Buffer{};
        Result<Buffer> b = createBuffer(*device, size, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, Memory::Upload, "vdb grids");
        if (!b) return b.error();
        res.vdbGrids = std::move(b.value());
        dirty = true;
    }
    // The previous frame has completed (render() waits on its fence), so the buffer is free to write.
    auto* dst = static_cast<std::byte*>(res.vdbGrids.mapped);
    size_t offset = 0;
    for (const DensityGridPtr& g : grids) {
        std::memcpy(dst + offset, g->data(), g->size());
        offset += g->size();
    }
    res.vdbGridsUploaded = std::move(grids);
    return {};
}

Result<void> GpuRenderer::State::chooseVoxelizeVariant(const CompiledScene& cs) {
    auto any = [](const std::vector<DensityGridPtr>& list) {
        return std::any_of(list.begin(), list.end(), [](const DensityGridPtr& g) { return g != nullptr; });
    };
    frameHasVdbVolumes = any(cs.grids);
    frameHasTextures = any(cs.textures);
    ComputePass& pass = voxelizeTexture[frameHasVdbVolumes ? 1 : 0];
    if (!frameHasTextures || pass.pipeline) return {};
    Result<ComputePass> p = createVoxelizeTexturePass(*device, bindings.pipelineLayout.get(), frameHasVdbVolumes);
    if (!p) return p.error();
    pass = std::move(p.value());
    return {};
}

const ComputePass& GpuRenderer::State::voxelizeVariant() const {
    if (frameHasTextures) return voxelizeTexture[frameHasVdbVolumes ? 1 : 0];
    return frameHasVdbVolumes ? voxelizeVdb : voxelize;
}

}  // namespace brume::gpu
