// Pass 3: front to back along each froxel column; entry s holds camera -> far boundary of slice s
// (core: integrateColumn). Slab lengths are measured along the column-centre ray.
// Dispatched over the columns of the temporal region only (region.lo.xy + invocation; core/
// media_region.h temporalFroxelRegion): S and sigma_t are 0 outside it, so the frame clears the
// integrated volumes to scattering 0 and transmittance 1 first (in front of the region and in the
// columns outside it), and behind the region each column keeps its value at the region's far end.
#version 450
#extension GL_GOOGLE_include_directive : require
#define BRUME_FROXEL_IMAGES
#include "resources.glsl"

layout(local_size_x = INTEGRATE_GROUP_X, local_size_y = INTEGRATE_GROUP_Y, local_size_z = 1) in;
layout(push_constant) uniform RegionBlock { FroxelRegionParams region; };

void main() {
    ivec2 column = region.lo.xy + ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(column, region.hi.xy))) return;
    vec2 pixel = (vec2(column) + vec2(0.5f)) * float(frame.froxelDims.w);
    Accumulated acc = emptyAccumulated();
    for (int s = region.lo.z; s < region.hi.z; ++s) {
        ivec3 id = ivec3(column, s);
        float d = sliceRayLength(s, pixel, frame);
        acc = accumulateSlab(acc, imageLoad(sourceImage, id).rgb, imageLoad(mediaExtinction, id).rgb, d);
        imageStore(integratedScattering, id, vec4(acc.scattering, 0.0f));
        imageStore(integratedTransmittance, id, vec4(acc.transmittance, 0.0f));
    }
    for (int s = region.hi.z; s < frame.froxelDims.z; ++s) {
        ivec3 id = ivec3(column, s);
        imageStore(integratedScattering, id, vec4(acc.scattering, 0.0f));
        imageStore(integratedTransmittance, id, vec4(acc.transmittance, 0.0f));
    }
}
