#include "density_grid.h"

#include <cstring>

#include <nanovdb/NanoVDB.h>

#include "../shaders/shared/vdb.h"

namespace brume {

DensityGrid::DensityGrid(const void* bytes, size_t size)
    : storage_((size + sizeof(Block) - 1) / sizeof(Block)), size_(storage_.size() * sizeof(Block)) {
    std::memcpy(storage_.data(), bytes, size);
    const auto* grid = reinterpret_cast<const nanovdb::NanoGrid<float>*>(storage_.data());
    activeVoxels_ = grid->activeVoxelCount();
    const nanovdb::CoordBBox box = grid->indexBBox();
    empty_ = activeVoxels_ == 0 || box.empty();
    if (!empty_) {
        indexMin_ = glm::vec3(box.min()[0], box.min()[1], box.min()[2]) - glm::vec3(1.0f);
        indexMax_ = glm::vec3(box.max()[0], box.max()[1], box.max()[2]) + glm::vec3(1.0f);
    }
    // NanoVDB's Map holds the affine matrix row-major (world = M * index + translation).
    const nanovdb::Map& map = grid->map();
    glm::mat4 m(1.0f);
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) m[c][r] = static_cast<float>(map.mMatD[r * 3 + c]);
        m[3][r] = static_cast<float>(map.mVecD[r]);
    }
    gridFromIndex_ = m;
}

float DensityGrid::sampleIndex(glm::vec3 indexPos) const {
    if (empty_) return 0.0f;
    const shd::VdbCell c = shd::vdbCell(indexPos);
    return sampleCorners(c.base, c.base + glm::ivec3(1), c.frac);
}

float DensityGrid::sampleCorners(glm::ivec3 a, glm::ivec3 b, glm::vec3 frac) const {
    if (empty_) return 0.0f;
    const auto* grid = reinterpret_cast<const nanovdb::NanoGrid<float>*>(storage_.data());
    auto acc = grid->getAccessor();
    auto at = [&](int x, int y, int z) { return acc.getValue(nanovdb::Coord(x, y, z)); };
    const glm::vec4 lo(at(a.x, a.y, a.z), at(b.x, a.y, a.z), at(a.x, b.y, a.z), at(b.x, b.y, a.z));
    const glm::vec4 hi(at(a.x, a.y, b.z), at(b.x, a.y, b.z), at(a.x, b.y, b.z), at(b.x, b.y, b.z));
    return shd::vdbTrilinear(lo, hi, frac);
}

double DensityGrid::activeBoxMean() const {
    if (empty_) return 0.0;
    const auto* grid = reinterpret_cast<const nanovdb::NanoGrid<float>*>(storage_.data());
    auto acc = grid->getAccessor();
    const nanovdb::CoordBBox box = grid->indexBBox();
    double sum = 0.0;
    for (auto it = box.begin(); it; ++it) sum += static_cast<double>(acc.getValue(*it));
    return sum / static_cast<double>(box.volume());
}

}  // namespace brume
