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

size_t quantizedIndex(VdbEncoding e) { return e == VdbEncoding::Fp16 ? 0 : 1; }

// The variant of `shader` (a vdb shader's name without ".comp") built for encoding e
// (shaders/CMakeLists.txt names it shader_fp16.comp / shader_fp8.comp), unless already created.
// label: a string literal (ComputePass keeps the pointer).
Result<void> ensureQuantizedPass(ComputePass& pass, const Device& device, VkPipelineLayout layout, const char* shader,
                                 VdbEncoding e, const char* label) {
    if (pass.pipeline) return {};
    const std::string name = std::string(shader) + "_" + toString(e) + ".comp";
    Result<ComputePass> p = createComputePass(device, layout, name.c_str(), label);
    if (!p) return p.error();
    pass = std::move(p.value());
    return {};
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
    BRUME_TRY(chooseVdbEncoding(cs));
    const VkPipelineLayout layout = bindings.pipelineLayout.get();
    if (frameHasVdbVolumes && frameVdbEncoding != VdbEncoding::Float) {
        const bool fp16 = frameVdbEncoding == VdbEncoding::Fp16;
        BRUME_TRY(ensureQuantizedPass(shadowVolumeVdbQuantized[quantizedIndex(frameVdbEncoding)], *device, layout,
                                      "shadow_volume_vdb", frameVdbEncoding,
                                      fp16 ? "shadow volume (vdb fp16)" : "shadow volume (vdb fp8)"));
        BRUME_TRY(ensureQuantizedPass(voxelizeVdbQuantized[quantizedIndex(frameVdbEncoding)][frameHasTextures ? 1 : 0],
                                      *device, layout, frameHasTextures ? "voxelize_vdb_texture" : "voxelize_vdb",
                                      frameVdbEncoding, fp16 ? "voxelize (vdb fp16)" : "voxelize (vdb fp8)"));
        return {};
    }
    ComputePass& pass = voxelizeTexture[frameHasVdbVolumes ? 1 : 0];
    if (!frameHasTextures || pass.pipeline) return {};
    Result<ComputePass> p = createVoxelizeTexturePass(*device, layout, frameHasVdbVolumes);
    if (!p) return p.error();
    pass = std::move(p.value());
    return {};
}

// One shader variant samples every vdb volume of a frame, so they must share an encoding (the scene
// format refuses mixing, io/scene_json.cpp; this catches scenes built in code). Density textures
// are always float and read by density_texture.glsl, whatever the variant.
Result<void> GpuRenderer::State::chooseVdbEncoding(const CompiledScene& cs) {
    frameVdbEncoding = VdbEncoding::Float;
    bool first = true;
    for (const DensityGridPtr& g : cs.grids) {
        if (!g) continue;
        if (!first && g->encoding() != frameVdbEncoding)
            return Error{std::string("The scene's vdb volumes mix the encodings ") + toString(frameVdbEncoding) + " and " +
                             toString(g->encoding()) + "; the GPU renders one encoding per scene.",
                         /*badInput=*/true};
        frameVdbEncoding = g->encoding();
        first = false;
    }
    return {};
}

const ComputePass& GpuRenderer::State::voxelizeVariant() const {
    if (frameHasVdbVolumes && frameVdbEncoding != VdbEncoding::Float)
        return voxelizeVdbQuantized[quantizedIndex(frameVdbEncoding)][frameHasTextures ? 1 : 0];
    if (frameHasTextures) return voxelizeTexture[frameHasVdbVolumes ? 1 : 0];
    return frameHasVdbVolumes ? voxelizeVdb : voxelize;
}

const ComputePass& GpuRenderer::State::shadowVolumeVariant() const {
    if (!frameHasVdbVolumes) return shadowVolume;
    if (frameVdbEncoding == VdbEncoding::Float) return shadowVolumeVdb;
    return shadowVolumeVdbQuantized[quantizedIndex(frameVdbEncoding)];
}

}  // namespace brume::gpu
