// Shadow volume pass for scenes with vdb grids (core: computeShadowVolume): shadow_volume.comp's
// analytic layer plus, when vdb shadows are on (frame.vdbShadowSamples), each light's vdb layer (optical depth)
// (shared/vdb_shadow.h). A variant for the same reason as voxelize_vdb.comp: the inlined PNanoVDB
// walk would slow the pass for every scene. It runs before the geometry pass, whose surfaces read the
// vdb layers, so before the column ends are known: every cell of the pushed region is computed.
#version 450
#extension GL_GOOGLE_include_directive : require
// The volumes through their texel view (resources.glsl volumeAt; docs/performance.md "light3"); the
// lights through the storage buffer (lightAt: the view measured no gain here; the index is uniform).
#define BRUME_VOLUME_TEXELS
#include "resources.glsl"
#include "fog_shadow.glsl"
#include "vdb_sample.glsl"
#include "vdb_shadow.glsl"

layout(local_size_x = FROXEL_GROUP_X, local_size_y = FROXEL_GROUP_Y, local_size_z = FROXEL_GROUP_Z) in;
layout(push_constant) uniform RegionBlock { FroxelRegionParams region; };  // cells, not froxels; lo.w: the light

#include "shadow_cells.glsl"

void main() {
    ivec3 cells = shadowVolumeDims(frame.froxelDims.xyz, frame.shadowReduction);
    // As shadow_volume.comp: one dispatch per computed layer, over its cells, its light in region.lo.w.
    ivec3 first = shadowRunFirst();
    if (any(greaterThanEqual(first, region.hi.xyz))) return;
    int light = region.lo.w;
    LightData l = lightAt(light);
    FogVolumes volumes = fogVolumes();  // fetched once for the run (fog_shadow.glsl)
    for (int z = first.z; z < min(first.z + SHADOW_RUN, region.hi.z); ++z) {
        ivec3 cell = ivec3(first.xy, z);
        ShadowCellRay r = writeAnalyticShadowCell(l, volumes, cells, cell);
        if (frame.vdbShadowSamples > 0)
            shadowTransmittance[shadowVolumeIndex(cells, vdbShadowLayer(light, frame.counts.w), cell)] =
                vec4(vdbFogOpticalDepth(l, r.p, r.ls.toLight, r.ls.distance), 0.0f);
    }
}
