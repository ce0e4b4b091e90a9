// Shadow volume pass: each shadowing light's fog transmittance at the reduced grid's cells
// (shared/shadow_volume.h; core: computeShadowVolume). Lights' layers are stacked along z in memory;
// the dispatch covers the layers the light reach lists, one after the other, and in each only the
// cells of the pushed region (the cells the light pass's media region reads); the others are never read.
#version 450
#extension GL_GOOGLE_include_directive : require
// The volumes through their texel view (resources.glsl volumeAt; docs/performance.md "light3"); the
// lights and clusters through the storage buffers (lightAt, clusterInt: the views measured no gain here).
#define BRUME_VOLUME_TEXELS
#include "resources.glsl"
#include "fog_shadow.glsl"

layout(local_size_x = FROXEL_GROUP_X, local_size_y = FROXEL_GROUP_Y, local_size_z = FROXEL_GROUP_Z) in;
layout(push_constant) uniform RegionBlock { FroxelRegionParams region; };  // cells, not froxels

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID);
    ivec3 cells = shadowVolumeDims(frame.froxelDims.xyz, frame.shadowReduction);
    // Only the layers some reader needs, listed by the light reach (core/light_reach.h); the others
    // are never read.
    int layers = lightReachOffset(frame.froxelDims.xyz) + 1 + frame.counts.w;
    // Over the cells some reader needs (region: core/media_region.h shadowCellRegion): the others
    // are never read this frame.
    int depth = region.hi.z - region.lo.z;
    int k = smallQuotient(id.z, depth);
    ivec3 cell = ivec3(id.xy, id.z - k * depth) + region.lo.xyz;
    if (cell.x >= cells.x || cell.y >= cells.y || k >= clusterInt(layers)) return;
    int light = clusterInt(layers + 1 + k);
    LightData l = lightAt(light);
    ivec3 froxel = shadowCellFroxel(cell, frame.froxelDims.xyz, frame.shadowReduction);
    vec3 p = worldFromFroxelCoord(vec3(froxel) + frame.jitter.xyz, frame);
    LightSample ls = evalLight(l, p);
    shadowTransmittance[shadowVolumeIndex(cells, light, cell)] =
        vec4(lightFogTransmittance(l, p, ls.toLight, ls.distance), 0.0f);
}
