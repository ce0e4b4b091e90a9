// A density grid in memory: one float NanoVDB grid in a 32-byte aligned buffer, sampled trilinearly
// in index space. core/ knows nothing of OpenVDB: io/vdb_import.* reads the file and fills this.
// NanoVDB (header-only, plain C++, no dependencies) is used here on purpose: the CPU renderers sample
// the very bytes that the GPU uploads and reads with PNanoVDB, so the two cannot disagree on the data,
// and the grid stays sparse on both sides (no dense copy anywhere).
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

namespace nanovdb {
template <typename>
class Grid;
}

namespace brume {

// How a grid's voxel values are stored (docs/vdb.md "Encodings"): 32-bit floats, or quantized per
// 8^3 leaf between the leaf's minimum and maximum with 16 or 8 bits a voxel (NanoVDB Fp16 / Fp8).
// The order is the scene format's ("float|fp16|fp8", core/settings.h volume_encoding).
enum class VdbEncoding { Float, Fp16, Fp8 };
const char* toString(VdbEncoding e);

class DensityGrid {
public:
    // bytes: a NanoVDB buffer holding one grid of float, Fp16 or Fp8 values (nanovdb::NanoGrid<float>,
    // <Fp16>, <Fp8>; io/vdb_encoding.h converts). Values must already be finite and >= 0 (the importer
    // sanitizes them).
    explicit DensityGrid(const void* bytes, size_t size);

    // The raw NanoVDB buffer followed by the occupancy cells (what the GPU uploads); size is a
    // multiple of 32 bytes.
    const void* data() const { return storage_.data(); }
    size_t size() const { return size_; }
    size_t nanoVdbSize() const { return nanoVdbSize_; }
    // Byte offset of the occupancy block in data() (shaders/shared/vdb.h), 0 = none (an empty grid,
    // or one with active tiles, which the cells do not track).
    size_t occupancyOffset() const { return occupancyOffset_; }
    // False where the trilinear cell at indexPos is all zero (sampleIndex returns 0 there): the
    // renderers skip the tree walk. True everywhere without an occupancy block.
    bool occupied(glm::vec3 indexPos) const;

    // Trilinear value at an index-space position (0 outside the active voxels, the background).
    float sampleIndex(glm::vec3 indexPos) const;

    // Trilinear value of the cell whose 8 corners are (lo or hi).xyz per axis: lo and hi need not be
    // neighbours (a density texture wraps hi around to the start of its box at the seam). Each
    // corner's value v is taken as textureShape(v, exponent) (shared/density_texture.h).
    float sampleCorners(glm::ivec3 lo, glm::ivec3 hi, glm::vec3 frac, float exponent = 1.0f) const;
    // Mean of textureShape(value, exponent) over the active voxels' index box (inactive voxels count
    // as the background, 0); 0 when empty. Costs one lookup per voxel of the box: for density
    // textures, at load.
    double activeBoxMean(float exponent = 1.0f) const;

    bool empty() const { return empty_; }
    VdbEncoding encoding() const { return encoding_; }
    // Active voxels' index bounding box, grown by one voxel (trilinear support); empty() when none.
    glm::vec3 indexMin() const { return indexMin_; }
    glm::vec3 indexMax() const { return indexMax_; }
    // Grid-space (the file's world) from index space: the file's affine voxel transform.
    glm::mat4 gridFromIndex() const { return gridFromIndex_; }
    uint64_t activeVoxels() const { return activeVoxels_; }

private:
    struct alignas(32) Block {
        std::byte b[32];
    };
    void buildOccupancy();
    // Calls f with the grid as the NanoGrid of its encoding (every reader goes through here).
    template <class F>
    auto visit(F&& f) const;
    template <class GridT>
    void readHeader(const GridT& grid);
    template <class GridT>
    static std::vector<uint32_t> occupancyWords(const GridT& grid);

    std::vector<Block> storage_;
    size_t size_ = 0;
    size_t nanoVdbSize_ = 0;
    size_t occupancyOffset_ = 0;
    bool empty_ = true;
    VdbEncoding encoding_ = VdbEncoding::Float;
    glm::vec3 indexMin_{0.0f}, indexMax_{0.0f};
    glm::mat4 gridFromIndex_{1.0f};
    uint64_t activeVoxels_ = 0;
};

using DensityGridPtr = std::shared_ptr<const DensityGrid>;

}  // namespace brume
