// Shadow volume pass: each shadowing light's fog transmittance at the reduced grid's cells
// (shared/shadow_volume.h; core: computeShadowVolume). Lights' layers are stacked along z in memory;
// one dispatch per layer the light reach lists, over the cells of the pushed region (those the light
// passes read around the media region's froxels whose clusters list the light); the others are never
// read.
#version 450
#extension GL_GOOGLE_include_directive : require
// The volumes through their texel view (resources.glsl volumeAt; docs/performance.md "light3"); the
// lights through the storage buffer (lightAt: the view measured no gain here; the index is uniform).
#define BRUME_VOLUME_TEXELS
#include "resources.glsl"
#include "fog_shadow.glsl"

layout(local_size_x = FROXEL_GROUP_X, local_size_y = FROXEL_GROUP_Y, local_size_z = FROXEL_GROUP_Z) in;
layout(push_constant) uniform RegionBlock { FroxelRegionParams region; };  // cells, not froxels; lo.w: the light

void main() {
    ivec3 cells = shadowVolumeDims(frame.froxelDims.xyz, frame.shadowReduction);
    // One dispatch per layer some reader needs (the light reach lists them: core/light_reach.h), over
    // the cells of that layer some reader needs, its light in region.lo.w (gpu/frame_executor.cpp
    // recordShadowCells): the others are never read this frame.
    ivec3 cell = ivec3(gl_GlobalInvocationID) + region.lo.xyz;
    if (any(greaterThanEqual(cell, region.hi.xyz))) return;
    int light = region.lo.w;
    LightData l = lightAt(light);
    ivec3 froxel = shadowCellFroxel(cell, frame.froxelDims.xyz, frame.shadowReduction);
    vec3 p = worldFromFroxelCoord(vec3(froxel) + frame.jitter.xyz, frame);
    LightSample ls = evalLight(l, p);
    shadowTransmittance[shadowVolumeIndex(cells, light, cell)] =
        vec4(lightFogTransmittance(l, p, ls.toLight, ls.distance), 0.0f);
}
