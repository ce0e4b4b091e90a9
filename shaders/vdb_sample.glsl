// Grid sampling of vdb volumes with PNanoVDB (core: DensityGrid::sampleIndex through NanoVDB): the
// same 8 voxels of shared/vdb.h's vdbCell, mixed by the same vdbTrilinear, read from the very bytes
// the CPU samples (the texel view vdbGridTexels holds them back to back: pnanovdb_texels.glsl;
// VolumeData.kind.y is a grid's offset).

#include "pnanovdb_texels.glsl"

// One encoding per compiled variant (docs/vdb.md "Encodings"): shaders/CMakeLists.txt builds the vdb
// shaders again with BRUME_VDB_FP16 or BRUME_VDB_FP8 defined. A runtime branch on the grid type
// would cost every scene on lavapipe, which runs the untaken side too. A quantized grid stores its
// tiles and background as floats; only leaf voxels are decoded (core: NanoGrid<Fp16|Fp8> accessors).
#if defined(BRUME_VDB_FP16) || defined(BRUME_VDB_FP8)
#ifdef BRUME_VDB_FP16
#define BRUME_VDB_GRID_TYPE PNANOVDB_GRID_TYPE_FP16
#define BRUME_VDB_LOG_BITS 4u
#else
#define BRUME_VDB_GRID_TYPE PNANOVDB_GRID_TYPE_FP8
#define BRUME_VDB_LOG_BITS 3u
#endif
float vdbVoxel(pnanovdb_buf_t buf, inout pnanovdb_readaccessor_t acc, ivec3 ijk) {
    uint level = 0u;
    pnanovdb_address_t a = pnanovdb_readaccessor_get_value_address_and_level(BRUME_VDB_GRID_TYPE, buf, acc, ijk, level);
    return level == 0u ? pnanovdb_leaf_fp_read_float(buf, a, ijk, BRUME_VDB_LOG_BITS) : pnanovdb_read_float(buf, a);
}
#else
float vdbVoxel(pnanovdb_buf_t buf, inout pnanovdb_readaccessor_t acc, ivec3 ijk) {
    return pnanovdb_read_float(buf, pnanovdb_readaccessor_get_value_address(PNANOVDB_GRID_TYPE_FLOAT, buf, acc, ijk));
}
#endif

// Whether the trilinear cell with lower corner `base` may be non-zero (core: DensityGrid::occupied;
// shared/vdb.h vdbOccupancyWord), read from the cells after the grid (VolumeData.kind.w).
bool vdbOccupied(VolumeData v, ivec3 base) {
    uint h = uint(vdbGridOffset(v) + vdbOccupancyOffset(v)) / 4u;
    ivec3 origin = ivec3(int(vdbGridWord(h)), int(vdbGridWord(h + 1u)), int(vdbGridWord(h + 2u)));
    ivec3 dims = ivec3(int(vdbGridWord(h + 4u)), int(vdbGridWord(h + 5u)), int(vdbGridWord(h + 6u)));
    int w = vdbOccupancyWord(base, origin, dims);
    return w >= 0 && vdbGridWord(h + uint(VDB_OCCUPANCY_HEADER_WORDS + w)) != 0u;
}

// Density of vdb volume v at a world position, without bounds test (core: plainVolumeDensity), with
// its height_falloff (shared/media.h localHeightFactor: 1 without). Cells the
// occupancy grid marks empty return 0 without walking the tree.
float vdbDensity(VolumeData v, vec3 worldPos) {
    if (!vdbHasGrid(v)) return 0.0f;
    if (vdbOccupancyOffset(v) != 0 && !vdbOccupied(v, vdbCell(vdbIndexPos(v, worldPos)).base)) return 0.0f;
    pnanovdb_buf_t buf = pnanovdb_buf_t(0u);  // the reads go to vdbGridTexels (pnanovdb_texels.glsl)
    pnanovdb_grid_handle_t grid;
    grid.address.byte_offset = uint(vdbGridOffset(v));
    pnanovdb_readaccessor_t acc;
    pnanovdb_readaccessor_init(acc, pnanovdb_tree_get_root(buf, pnanovdb_grid_get_tree(buf, grid)));
    VdbCell c = vdbCell(vdbIndexPos(v, worldPos));
    ivec3 b = c.base;
    vec4 lo = vec4(vdbVoxel(buf, acc, b), vdbVoxel(buf, acc, b + ivec3(1, 0, 0)), vdbVoxel(buf, acc, b + ivec3(0, 1, 0)),
                   vdbVoxel(buf, acc, b + ivec3(1, 1, 0)));
    vec4 hi = vec4(vdbVoxel(buf, acc, b + ivec3(0, 0, 1)), vdbVoxel(buf, acc, b + ivec3(1, 0, 1)),
                   vdbVoxel(buf, acc, b + ivec3(0, 1, 1)), vdbVoxel(buf, acc, b + ivec3(1, 1, 1)));
    return v.params.x * vdbTrilinear(lo, hi, c.frac) * localHeightFactor(v, worldPos.y);
}
