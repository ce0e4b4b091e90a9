// Synthetic OpenVDB files for the VDB tests (written with the OpenVDB API into a temp folder).
#pragma once

#include <cmath>
#include <filesystem>
#include <functional>
#include <string>

#include <openvdb/openvdb.h>

namespace brume::test {

inline std::filesystem::path sharedVdbDir() { return std::filesystem::path(BRUME_SOURCE_DIR) / ".." / "shared" / "vdb"; }

// A float fog grid with value f(index) on every voxel of [lo, hi]^3 (values <= 0 left inactive unless
// keepAll), under the given world-from-index transform.
inline openvdb::FloatGrid::Ptr makeGrid(const std::string& name, int lo, int hi,
                                        const std::function<float(openvdb::Coord)>& f,
                                        openvdb::math::Transform::Ptr xform, bool keepAll = false) {
    openvdb::FloatGrid::Ptr g = openvdb::FloatGrid::create(0.0f);
    g->setName(name);
    g->setGridClass(openvdb::GRID_FOG_VOLUME);
    g->setTransform(xform);
    auto acc = g->getAccessor();
    for (int k = lo; k <= hi; ++k)
        for (int j = lo; j <= hi; ++j)
            for (int i = lo; i <= hi; ++i) {
                const float v = f(openvdb::Coord(i, j, k));
                if (keepAll || v > 0.0f) acc.setValue(openvdb::Coord(i, j, k), v);
            }
    return g;
}

// Rotated (30 deg about Y, then 20 deg about X) and non-uniformly scaled (0.05, 0.08, 0.11 m voxels),
// translated to (0.3, 1.0, -0.2).
inline openvdb::math::Transform::Ptr skewedTransform() {
    openvdb::Mat4d m = openvdb::Mat4d::identity();
    m.preScale(openvdb::Vec3d(0.05, 0.08, 0.11));
    m.postRotate(openvdb::math::Y_AXIS, 30.0 * M_PI / 180.0);
    m.postRotate(openvdb::math::X_AXIS, 20.0 * M_PI / 180.0);
    m.postTranslate(openvdb::Vec3d(0.3, 1.0, -0.2));
    return openvdb::math::Transform::createLinearTransform(m);
}

inline void writeGrids(const std::filesystem::path& path, const openvdb::GridPtrVec& grids) {
    openvdb::initialize();
    openvdb::io::File file(path.string());
    file.write(grids);
    file.close();
}

}  // namespace brume::test

// GTEST_SKIP returns only from the function it is written in, so this must be a macro used in the
// test body itself: a helper function would skip nothing and the test would run on without data.
#define BRUME_REQUIRE_SHARED_VDB()                                                         \
    if (!std::filesystem::is_directory(brume::test::sharedVdbDir()))                       \
    GTEST_SKIP() << "../shared/vdb is absent (a fresh clone has no ../shared); real-file test skipped"
