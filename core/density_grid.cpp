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
    const auto* grid = reinterpret_cast<const nanovdb::NanoGrid<float>*>(storage_.data());
    auto acc = grid->getAccessor();
    const shd::VdbCell c = shd::vdbCell(indexPos);
    auto at = [&](int dx, int dy, int dz) {
        return acc.getValue(nanovdb::Coord(c.base.x + dx, c.base.y + dy, c.base.z + dz));
    };
    const glm::vec4 lo(at(0, 0, 0), at(1, 0, 0), at(0, 1, 0), at(1, 1, 0));
    const glm::vec4 hi(at(0, 0, 1), at(1, 0, 1), at(0, 1, 1), at(1, 1, 1));
    return shd::vdbTrilinear(lo, hi, c.frac);
}

}  // namespace brume
