// PNanoVDB (GLSL) over the grids' bytes through the texel view vdbGridTexels (shared/frame_table.h):
// vdb volumes' grids and density textures back to back (VolumeData.kind.y, textureMin.w: byte
// offsets). PNanoVDB's own GLSL buffer reads index the storage buffer vdbGridWords, which lavapipe
// loads lane by lane (8 guarded scalar loads per word); a texel view's texelFetch is one vector gather
// (docs/performance.md, "shadowskip"). Its custom-buffer hook (PNANOVDB_BUF_CUSTOM) takes the buffer
// type, the two reads and the grid-type table's accessor from here. Included once by vdb_sample.glsl
// and density_texture.glsl.
#ifndef BRUME_PNANOVDB_TEXELS_GLSL
#define BRUME_PNANOVDB_TEXELS_GLSL

#define PNANOVDB_GLSL
#define PNANOVDB_BUF_CUSTOM
struct pnanovdb_buf_t {
    uint unused;  // the reads go to the one view; GLSL wants a member
};
// The word at byte_offset (a multiple of 4): r32i texels hold the words' bits (uint(int) keeps them).
uint pnanovdb_buf_read_uint32(pnanovdb_buf_t buf, uint byte_offset) {
    return uint(texelFetch(vdbGridTexels, int(byte_offset >> 2u)).x);
}
uvec2 pnanovdb_buf_read_uint64(pnanovdb_buf_t buf, uint byte_offset) {
    return uvec2(pnanovdb_buf_read_uint32(buf, byte_offset), pnanovdb_buf_read_uint32(buf, byte_offset + 4u));
}
#define pnanovdb_grid_type_t uint
#define PNANOVDB_GRID_TYPE_GET(grid_typeIn, nameIn) pnanovdb_grid_type_constants[grid_typeIn].nameIn
#include "nanovdb/PNanoVDB.h"

// Word i of the grids' bytes (the occupancy cells after each grid: vdb_sample.glsl vdbOccupied).
uint vdbGridWord(uint i) { return uint(texelFetch(vdbGridTexels, int(i)).x); }

#endif
