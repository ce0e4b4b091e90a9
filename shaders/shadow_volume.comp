// Shadow volume pass: each shadowing light's fog transmittance at the reduced grid's cells
// (shared/shadow_volume.h; core: computeShadowVolume). Lights' layers are stacked along z in memory;
// one dispatch per layer the light reach lists, over the cells of the pushed region (those the light
// passes read around the media region's froxels whose clusters list the light), and in each cell column
// only down to the deepest cell this frame's froxels read (column_entries.glsl shadowCellEnd): it runs
// after the column ends pass. The others are never read.
#version 450
#extension GL_GOOGLE_include_directive : require
// The volumes through their texel view (resources.glsl volumeAt; docs/performance.md "light3"); the
// lights through the storage buffer (lightAt: the view measured no gain here; the index is uniform).
#define BRUME_VOLUME_TEXELS
#include "resources.glsl"
#include "fog_shadow.glsl"

layout(local_size_x = FROXEL_GROUP_X, local_size_y = FROXEL_GROUP_Y, local_size_z = FROXEL_GROUP_Z) in;
layout(push_constant) uniform RegionBlock { FroxelRegionParams region; };  // cells, not froxels; lo.w: the light

#include "column_entries.glsl"
#include "shadow_cells.glsl"

void main() {
    ivec3 cells = shadowVolumeDims(frame.froxelDims.xyz, frame.shadowReduction);
    // One dispatch per layer some reader needs (the light reach lists them: core/light_reach.h), over
    // the cells of that layer some reader needs, its light in region.lo.w (gpu/frame_executor.cpp
    // recordShadowCells): the others are never read this frame.
    ivec3 first = shadowRunFirst();
    // Only the loop's bound skips work on lavapipe (it leaves a loop once no lane of its 8 runs it; an
    // early return costs the body under a mask): adjacent cell columns end at similar depths.
    int end = min(region.hi.z, shadowCellEnd(first.xy, frame.shadowReduction, cells.z));
    if (any(greaterThanEqual(first, ivec3(region.hi.xy, end)))) return;
    LightData l = lightAt(region.lo.w);
    FogVolumes volumes = fogVolumes();  // fetched once for the run (fog_shadow.glsl)
    for (int z = first.z; z < min(first.z + SHADOW_RUN, end); ++z)
        writeAnalyticShadowCell(l, volumes, cells, ivec3(first.xy, z));
}
