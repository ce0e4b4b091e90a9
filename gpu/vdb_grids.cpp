// The vdb grid buffer (frame_table.h vdbGrids): every vdb volume's NanoVDB grid uploaded as is, back to
// back at the offsets compileScene wrote into VolumeData.kind.y, each followed by its occupancy cells
// (kind.w), then every density texture's grid (VolumeData.textureMin.w), then every detail layer's
// (detailMin.w). No dense copy: GPU memory is
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
    for (const auto* list : {&cs.grids, &cs.textures, &cs.details})
        for (const DensityGridPtr& g : *list) {
            if (!g) continue;
            grids.push_back(g);
            total += g->size();
        }
    Buffer& buffer = res[BufferId::vdbGrids];
    if (buffer.buffer && grids == res.vdbGridsUploaded) return {};
    // One binding addresses the whole buffer, and the shaders read it through its r32i texel view
    // (vdbGridTexels): the smaller of the two limits. Lavapipe: 128 MiB (its maxStorageBufferRange; its
    // views address 2^27 words, 512 MiB).
    const VkDeviceSize limit = std::min<VkDeviceSize>(device->limits().maxStorageBufferRange,
                                                      VkDeviceSize(device->limits().maxTexelBufferElements) * 4);
    if (total > limit)
        return Error{"The scene's vdb grids take " + mib(total) + " as NanoVDB, more than the " + mib(limit) +
                     " one GPU storage buffer and its texel view can address on this device; use fewer or smaller grids.",
                     /*badInput=*/true};
    const VkDeviceSize size = std::max<VkDeviceSize>(total, 32);
    if (!buffer.buffer || buffer.size != size) {
        // Its texel view (vdbGridTexels, which the shaders read) goes first; ensureTexelViews makes it again.
        res.texelViews[static_cast<size_t>(TexelViewId::vdbGridTexels)].reset();
        buffer = Buffer{};
        Result<Buffer> b = createBuffer(*device, size, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT,
                                        Memory::Upload, decl(BufferId::vdbGrids).name);
        if (!b) return b.error();
        buffer = std::move(b.value());
        dirty = true;
    }
    // The previous frame has completed (render() waits on its fence), so the buffer is free to write.
    auto* dst = static_cast<std::byte*>(buffer.mapped);
    size_t offset = 0;
    for (const DensityGridPtr& g : grids) {
        std::memcpy(dst + offset, g->data(), g->size());
        offset += g->size();
    }
    res.vdbGridsUploaded = std::move(grids);
    return {};
}

// The frame's shader variants (frame_table.h VariantKey). One variant samples every vdb volume of a
// frame, so they must share an encoding (the scene format refuses mixing, io/scene_json.cpp; this
// catches scenes built in code). Density textures
// are always float and read by density_texture.glsl, whatever the variant.
Result<void> GpuRenderer::State::chooseVariant(const CompiledScene& cs) {
    Result<VariantKey> v = variantOf(cs);
    if (!v) return v.error();
    variant = v.value();
    return {};
}

Result<VariantKey> variantOf(const CompiledScene& cs) {
    VariantKey variant;
    for (const DensityGridPtr& g : cs.textures) variant.textures = variant.textures || g != nullptr;
    for (const shd::VolumeData& v : cs.volumes) variant.shapes = variant.shapes || shd::needsShapeShadows(v);
    for (const DensityGridPtr& g : cs.grids) {
        if (!g) continue;
        if (variant.vdb && g->encoding() != variant.encoding)
            return Error{std::string("The scene's vdb volumes mix the encodings ") + toString(variant.encoding) + " and " +
                             toString(g->encoding()) + "; the GPU renders one encoding per scene.",
                         /*badInput=*/true};
        variant.encoding = g->encoding();
        variant.vdb = true;
    }
    return variant;
}

}  // namespace brume::gpu
