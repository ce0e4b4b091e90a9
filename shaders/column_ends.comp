// The column ends pass, after the depth tiles: each froxel column's entries that lookups read and its
// walk end this frame (column_entries.glsl columnEntryRange, columnWalkEnd), into this frame's half of
// columnEnds, which the light, temporal and integrate passes read; the other half keeps the previous
// frame's, which says which froxels of the history it wrote.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "resources.glsl"

layout(local_size_x = INTEGRATE_GROUP_X, local_size_y = INTEGRATE_GROUP_Y, local_size_z = 1) in;
// lo.w .. hi.w: the entries stored in every column (pass_temporal.cpp storedEverywhere).
layout(push_constant) uniform RegionBlock { FroxelRegionParams region; };

#include "column_entries.glsl"

void main() {
    ivec2 column = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(column, frame.froxelDims.xy))) return;
    ivec2 read = columnEntryRange(column);
    columnEnd[columnEndIndex(column, int(frame.temporal.w))] = ivec4(read, columnWalkEnd(read, region.hi.w), 0);
}
