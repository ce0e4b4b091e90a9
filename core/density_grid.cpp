#include "density_grid.h"

#include <cstring>

#include <nanovdb/NanoVDB.h>

#include "../shaders/shared/density_texture.h"
#include "../shaders/shared/vdb.h"

namespace brume {

const char* toString(VdbEncoding e) {
    switch (e) {
        case VdbEncoding::Float: return "float";
        case VdbEncoding::Fp16: return "fp16";
        case VdbEncoding::Fp8: return "fp8";
    }
    return "float";
}

// Every reader is a template over the grid's value storage; the accessors of all three return float.
template <class F>
auto DensityGrid::visit(F&& f) const {
    const void* p = storage_.data();
    switch (encoding_) {
        case VdbEncoding::Fp16: return f(*reinterpret_cast<const nanovdb::NanoGrid<nanovdb::Fp16>*>(p));
        case VdbEncoding::Fp8: return f(*reinterpret_cast<const nanovdb::NanoGrid<nanovdb::Fp8>*>(p));
        case VdbEncoding::Float: break;
    }
    return f(*reinterpret_cast<const nanovdb::NanoGrid<float>*>(p));
}

DensityGrid::DensityGrid(const void* bytes, size_t size)
    : storage_((size + sizeof(Block) - 1) / sizeof(Block)), size_(storage_.size() * sizeof(Block)), nanoVdbSize_(size_) {
    std::memcpy(storage_.data(), bytes, size);
    const nanovdb::GridType type = reinterpret_cast<const nanovdb::GridData*>(storage_.data())->mGridType;
    encoding_ = type == nanovdb::GridType::Fp16  ? VdbEncoding::Fp16
                : type == nanovdb::GridType::Fp8 ? VdbEncoding::Fp8
                                                 : VdbEncoding::Float;
    visit([this](const auto& grid) { readHeader(grid); });
    buildOccupancy();
}

template <class GridT>
void DensityGrid::readHeader(const GridT& grid) {
    activeVoxels_ = grid.activeVoxelCount();
    const nanovdb::CoordBBox box = grid.indexBBox();
    empty_ = activeVoxels_ == 0 || box.empty();
    if (!empty_) {
        indexMin_ = glm::vec3(box.min()[0], box.min()[1], box.min()[2]) - glm::vec3(1.0f);
        indexMax_ = glm::vec3(box.max()[0], box.max()[1], box.max()[2]) + glm::vec3(1.0f);
    }
    // NanoVDB's Map holds the affine matrix row-major (world = M * index + translation).
    const nanovdb::Map& map = grid.map();
    glm::mat4 m(1.0f);
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) m[c][r] = static_cast<float>(map.mMatD[r * 3 + c]);
        m[3][r] = static_cast<float>(map.mVecD[r]);
    }
    gridFromIndex_ = m;
}

void DensityGrid::buildOccupancy() {
    if (empty_) return;
    std::vector<uint32_t> words = visit([](const auto& grid) { return occupancyWords(grid); });
    if (words.empty()) return;
    occupancyOffset_ = size_;
    const size_t bytes = words.size() * sizeof(uint32_t);
    storage_.resize(storage_.size() + (bytes + sizeof(Block) - 1) / sizeof(Block));
    std::memcpy(reinterpret_cast<std::byte*>(storage_.data()) + occupancyOffset_, words.data(), bytes);
    size_ = storage_.size() * sizeof(Block);
}

// The header and cells of shared/vdb.h's occupancy block; none (empty) for a grid with active tiles.
template <class GridT>
std::vector<uint32_t> DensityGrid::occupancyWords(const GridT& grid) {
    const auto& tree = grid.tree();
    if (tree.activeTileCount(1) + tree.activeTileCount(2) + tree.activeTileCount(3) > 0) return {};
    // Lower corners run from the active box's min - 1 to its max: the cells that hold them.
    const nanovdb::CoordBBox box = grid.indexBBox();
    const glm::ivec3 lo = glm::ivec3(box.min()[0] - 1, box.min()[1] - 1, box.min()[2] - 1) >> shd::VDB_OCCUPANCY_SHIFT;
    const glm::ivec3 hi = glm::ivec3(box.max()[0], box.max()[1], box.max()[2]) >> shd::VDB_OCCUPANCY_SHIFT;
    const glm::ivec3 dims = hi - lo + glm::ivec3(1);
    std::vector<uint32_t> words(static_cast<size_t>(shd::VDB_OCCUPANCY_HEADER_WORDS) +
                                static_cast<size_t>(dims.x) * static_cast<size_t>(dims.y) * static_cast<size_t>(dims.z));
    const int header[8] = {lo.x, lo.y, lo.z, 0, dims.x, dims.y, dims.z, 0};
    std::memcpy(words.data(), header, sizeof(header));
    // A leaf with a non-zero value (active or not) marks its own cell and the cells just below it,
    // whose taps reach its first voxels.
    const auto* leaf = tree.getFirstLeaf();
    for (uint32_t n = 0; n < tree.nodeCount(0); ++n, ++leaf) {
        bool nonZero = false;
        for (uint32_t i = 0; i < 512 && !nonZero; ++i) nonZero = leaf->getValue(i) != 0.0f;
        if (!nonZero) continue;
        const glm::ivec3 cell = glm::ivec3(leaf->origin()[0], leaf->origin()[1], leaf->origin()[2]) >> shd::VDB_OCCUPANCY_SHIFT;
        for (int d = 0; d < 8; ++d) {
            const glm::ivec3 below = cell - glm::ivec3(d & 1, (d >> 1) & 1, d >> 2);
            const int w = shd::vdbOccupancyWord(below << shd::VDB_OCCUPANCY_SHIFT, lo, dims);  // a voxel of it
            if (w >= 0) words[static_cast<size_t>(shd::VDB_OCCUPANCY_HEADER_WORDS + w)] = 1u;
        }
    }
    return words;
}

bool DensityGrid::occupied(glm::vec3 indexPos) const {
    if (occupancyOffset_ == 0) return true;
    const auto* words = reinterpret_cast<const uint32_t*>(reinterpret_cast<const std::byte*>(storage_.data()) + occupancyOffset_);
    const auto* header = reinterpret_cast<const int32_t*>(words);
    const int w = shd::vdbOccupancyWord(shd::vdbCell(indexPos).base, glm::ivec3(header[0], header[1], header[2]),
                                        glm::ivec3(header[4], header[5], header[6]));
    return w >= 0 && words[shd::VDB_OCCUPANCY_HEADER_WORDS + w] != 0u;
}

float DensityGrid::sampleIndex(glm::vec3 indexPos) const {
    if (empty_) return 0.0f;
    const shd::VdbCell c = shd::vdbCell(indexPos);
    return sampleCorners(c.base, c.base + glm::ivec3(1), c.frac);
}

float DensityGrid::sampleCorners(glm::ivec3 a, glm::ivec3 b, glm::vec3 frac, float exponent) const {
    if (empty_) return 0.0f;
    return visit([&](const auto& grid) {
        auto acc = grid.getAccessor();
        auto at = [&](int x, int y, int z) {
            return shd::textureShape(float(acc.getValue(nanovdb::Coord(x, y, z))), exponent);
        };
        const glm::vec4 lo(at(a.x, a.y, a.z), at(b.x, a.y, a.z), at(a.x, b.y, a.z), at(b.x, b.y, a.z));
        const glm::vec4 hi(at(a.x, a.y, b.z), at(b.x, a.y, b.z), at(a.x, b.y, b.z), at(b.x, b.y, b.z));
        return shd::vdbTrilinear(lo, hi, frac);
    });
}

double DensityGrid::activeBoxMean(float exponent) const {
    if (empty_) return 0.0;
    return visit([exponent](const auto& grid) {
        auto acc = grid.getAccessor();
        const nanovdb::CoordBBox box = grid.indexBBox();
        double sum = 0.0;
        for (auto it = box.begin(); it; ++it) sum += static_cast<double>(shd::textureShape(float(acc.getValue(*it)), exponent));
        return sum / static_cast<double>(box.volume());
    });
}

}  // namespace brume
