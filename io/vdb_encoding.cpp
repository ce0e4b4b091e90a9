#include "vdb_encoding.h"

#include <exception>

#include <nanovdb/util/NanoToOpenVDB.h>
#include <nanovdb/util/OpenToNanoVDB.h>
#include <openvdb/openvdb.h>

namespace brume {
namespace {

// Through OpenVDB rather than a NanoVDB GridBuilder: the converter keeps the leaves' inactive
// values and the tiles as they are, so only the quantization changes the grid (this is also how
// tests/test_vdb_encoding.cpp measured the trade on gaffer_smoke).
// The voxel transform is copied over afterwards: NanoToOpenVDB (OpenVDB 10) transposes the 3x3 of
// the map, which rotated and sheared transforms show (tests/test_vdb_encoding.cpp, synthetic grid).
template <class BuildT>
DensityGridPtr encodeAs(const nanovdb::NanoGrid<float>& grid) {
    const openvdb::FloatGrid::Ptr open = nanovdb::nanoToOpenVDB(grid);
    auto handle = nanovdb::openToNanoVDB<nanovdb::HostBuffer, openvdb::FloatTree, BuildT>(*open);
    auto* data = reinterpret_cast<nanovdb::GridData*>(handle.data());
    const auto* source = reinterpret_cast<const nanovdb::GridData*>(&grid);
    data->mMap = source->mMap;
    data->mWorldBBox = source->mWorldBBox;
    return std::make_shared<const DensityGrid>(handle.data(), handle.size());
}

}  // namespace

Result<DensityGridPtr> encodeDensityGrid(const DensityGridPtr& grid, VdbEncoding encoding, const std::string& path) {
    if (!grid || grid->encoding() == encoding) return grid;
    if (grid->encoding() != VdbEncoding::Float)
        return Error{path + ": cannot re-encode a grid stored as " + toString(grid->encoding()) + " as " +
                     toString(encoding) + " (only float grids are re-encoded)."};
    const auto* nano = static_cast<const nanovdb::NanoGrid<float>*>(grid->data());
    try {
        openvdb::initialize();
        return encoding == VdbEncoding::Fp16 ? encodeAs<nanovdb::Fp16>(*nano) : encodeAs<nanovdb::Fp8>(*nano);
    } catch (const std::exception& e) {
        return Error{path + ": cannot encode the grid as " + toString(encoding) + " (" + e.what() + ")."};
    }
}

}  // namespace brume
