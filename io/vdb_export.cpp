#include "vdb_export.h"

#include <mutex>

#include <openvdb/openvdb.h>

#include "atomic_file.h"

namespace brume {

namespace {

openvdb::FloatGrid::Ptr denseGrid(const std::string& name, int size, const std::vector<float>& values) {
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
    grid->setName(name);
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(1.0 / size));
    openvdb::FloatGrid::Accessor acc = grid->getAccessor();
    size_t index = 0;
    for (int k = 0; k < size; ++k)
        for (int j = 0; j < size; ++j)
            for (int i = 0; i < size; ++i) acc.setValueOn(openvdb::Coord(i, j, k), values[index++]);
    return grid;
}

}  // namespace

Result<void> writeDenseVdb(const std::string& path, const std::string& gridName, int size,
                           const std::vector<float>& values) {
    if (size <= 0 || values.size() != static_cast<size_t>(size) * size * size)
        return Error{path + ": internal error: " + std::to_string(values.size()) + " values for a " +
                     std::to_string(size) + "^3 grid."};
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
    openvdb::FloatGrid::Ptr grid = denseGrid(gridName, size, values);
    return writeFileAtomic(path, [&](const std::string& tmpPath) -> Result<void> {
        try {
            openvdb::io::File file(tmpPath);
            file.write({grid});
            file.close();
        } catch (const std::exception& e) {
            return Error{path + ": cannot write the OpenVDB file (" + std::string(e.what()) + ")."};
        }
        return {};
    });
}

}  // namespace brume
