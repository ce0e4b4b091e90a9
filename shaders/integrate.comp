// Pass 3: front to back along each froxel column; entry s holds camera -> far boundary of slice s
// (core: integrateColumn). Slab lengths are measured along the column-centre ray.
#version 450
#extension GL_GOOGLE_include_directive : require
#define BRUME_FROXEL_IMAGES
#include "resources.glsl"

layout(local_size_x = INTEGRATE_GROUP_X, local_size_y = INTEGRATE_GROUP_Y, local_size_z = 1) in;

void main() {
    ivec2 column = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(column, frame.froxelDims.xy))) return;
    vec2 pixel = (vec2(column) + vec2(0.5f)) * float(frame.froxelDims.w);
    Accumulated acc = emptyAccumulated();
    for (int s = 0; s < frame.froxelDims.z; ++s) {
        ivec3 id = ivec3(column, s);
        float d = sliceRayLength(s, pixel, frame);
        acc = accumulateSlab(acc, imageLoad(sourceImage, id).rgb, imageLoad(mediaExtinction, id).rgb, d);
        imageStore(integratedScattering, id, vec4(acc.scattering, 0.0f));
        imageStore(integratedTransmittance, id, vec4(acc.transmittance, 0.0f));
    }
}
