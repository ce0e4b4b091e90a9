// The float / Fp16 / Fp8 NanoVDB trade on a real smoke (gaffer_smoke.vdb, 1.05 M active voxels):
// memory, per-voxel error against the float grid and lookup time. Brume renders float grids today;
// this measures what the quantized encodings would give (docs/vdb.md, "Encodings"), with the
// tolerances an `encoding` volume key would have to meet. Timings are printed, never asserted.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>

#include <nanovdb/util/OpenToNanoVDB.h>
#include <openvdb/openvdb.h>

#include "vdb_test_util.h"

namespace {

struct Measured {
    uint64_t bytes = 0;
    double relMeanAbsError = 0.0;  // sum |q - f| / sum |f| over the active voxels
    double maxAbsError = 0.0;      // in the grid's units (smoke density 0..5.71)
    double nsPerLookup = 0.0;
};

template <class BuildT>
Measured measure(const openvdb::FloatGrid& grid) {
    auto handle = nanovdb::openToNanoVDB<nanovdb::HostBuffer, openvdb::FloatTree, BuildT>(grid);
    const auto* nano = handle.template grid<BuildT>();
    EXPECT_NE(nano, nullptr);
    Measured m;
    if (!nano) return m;
    m.bytes = handle.size();
    auto acc = nano->getAccessor();
    double sumErr = 0.0, sum = 0.0, checksum = 0.0;
    uint64_t n = 0;
    const auto start = std::chrono::steady_clock::now();
    for (auto it = grid.cbeginValueOn(); it.test(); ++it) {
        const openvdb::Coord c = it.getCoord();
        const float q = acc.getValue(nanovdb::Coord(c.x(), c.y(), c.z()));
        checksum += q;
        sumErr += std::abs(double(q) - double(*it));
        sum += std::abs(double(*it));
        m.maxAbsError = std::max(m.maxAbsError, std::abs(double(q) - double(*it)));
        ++n;
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    m.relMeanAbsError = sumErr / std::max(sum, 1e-30);
    m.nsPerLookup = seconds * 1e9 / double(std::max<uint64_t>(n, 1));
    EXPECT_GT(checksum, 0.0);
    return m;
}

}  // namespace

TEST(VdbEncoding, Fp16AndFp8TradeMemoryForErrorOnARealSmoke) {
    const std::filesystem::path file = brume::test::sharedVdbDir() / "gaffer_smoke.vdb";
    if (!std::filesystem::exists(file)) GTEST_SKIP() << "../shared/vdb is absent; encoding measurement skipped";
    openvdb::initialize();
    openvdb::io::File f(file.string());
    f.open(false);
    auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(f.readGrid("density"));
    f.close();
    ASSERT_TRUE(grid);
    const Measured fp32 = measure<float>(*grid), fp16 = measure<nanovdb::Fp16>(*grid), fp8 = measure<nanovdb::Fp8>(*grid);
    for (const auto& [name, m] : {std::pair{"float", fp32}, std::pair{"Fp16", fp16}, std::pair{"Fp8", fp8}})
        std::printf("%-5s %8.3f MiB  rel. mean abs error %.2e  max abs error %.2e  %.1f ns/lookup\n", name,
                    double(m.bytes) / (1024.0 * 1024.0), m.relMeanAbsError, m.maxAbsError, m.nsPerLookup);
    EXPECT_EQ(fp32.relMeanAbsError, 0.0);  // the float grid is the reference itself
    EXPECT_LT(fp16.bytes, fp32.bytes * 7 / 10);
    EXPECT_LT(fp8.bytes, fp16.bytes);
    // Quantization per 8^3 leaf between its min and max: 16 bits keep ~1e-5 of a leaf's range, 8 bits ~4e-3.
    EXPECT_LT(fp16.relMeanAbsError, 1e-3);
    EXPECT_LT(fp8.relMeanAbsError, 2e-2);
    EXPECT_GT(fp8.relMeanAbsError, fp16.relMeanAbsError);  // the measurement sees the quantization
}
