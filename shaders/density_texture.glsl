// Density textures on the GPU (core: densityTextureFactor): the 8 voxels of shared/density_texture.h's
// textureCell, read with PNanoVDB from the same bytes the CPU samples (the texture grids follow the
// vdb volumes' grids in the texel view vdbGridTexels (pnanovdb_texels.glsl); VolumeData.textureMin.w is a
// texture's byte offset), mixed by vdbTrilinear.
#include "pnanovdb_texels.glsl"

float textureVoxel(pnanovdb_buf_t buf, inout pnanovdb_readaccessor_t acc, ivec3 ijk) {
    return pnanovdb_read_float(buf, pnanovdb_readaccessor_get_value_address(PNANOVDB_GRID_TYPE_FLOAT, buf, acc, ijk));
}

// Factor on volume v's density at a world position at the frame's scene time (1 without a texture):
// the texture's factor times its detail layer's (shared/density_texture.h). The two layers run one
// loop body, so the walk's code is emitted once.
float densityTextureFactor(VolumeData v, vec3 worldPos) {
    if (!hasDensityTexture(v)) return 1.0f;
    pnanovdb_buf_t buf = pnanovdb_buf_t(0u);  // the reads go to vdbGridTexels (pnanovdb_texels.glsl)
    float factor = 1.0f;
    int layers = hasDetailTexture(v) ? 2 : 1;
    for (int layer = 0; layer < layers; ++layer) {
        bool detail = layer == 1;
        vec4 params = detail ? v.detailParams : v.textureParams;
        ivec4 boxMin = detail ? v.detailMin : v.textureMin;
        pnanovdb_grid_handle_t grid;
        grid.address.byte_offset = uint(boxMin.w);
        pnanovdb_readaccessor_t acc;
        pnanovdb_readaccessor_init(acc, pnanovdb_tree_get_root(buf, pnanovdb_grid_get_tree(buf, grid)));
        TextureCell c = textureLayerCell(params, detail ? v.detailScroll : v.textureScroll, boxMin,
                                         detail ? v.detailSize : v.textureSize, worldPos, frame.ambient.w);
        // One fetch in a loop rather than 8 inlined ones: the walk's code is what costs on lavapipe.
        vec4 lo, hi;
        for (int corner = 0; corner < 8; ++corner) {
            ivec3 ijk = ivec3((corner & 1) != 0 ? c.hi.x : c.lo.x, (corner & 2) != 0 ? c.hi.y : c.lo.y,
                              (corner & 4) != 0 ? c.hi.z : c.lo.z);
            float value = textureShape(textureVoxel(buf, acc, ijk), params.w);
            if (corner < 4) lo[corner] = value;
            else hi[corner - 4] = value;
        }
        factor *= textureLayerFactor(params, vdbTrilinear(lo, hi, c.frac));
    }
    return factor;
}
