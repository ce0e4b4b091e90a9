// Debug view (after composite, only when asked for): one depth slice of density, scattering or
// transmittance over the output image, with the shared ramp (shared/debug_view.h; core:
// debugViewImage). The output then holds display values, not radiance.
#version 450
#extension GL_GOOGLE_include_directive : require
#define BRUME_FROXEL_IMAGES
#include "resources.glsl"

layout(local_size_x = SCREEN_GROUP_X, local_size_y = SCREEN_GROUP_Y, local_size_z = 1) in;

layout(push_constant) uniform DebugBlock { DebugViewParams debugParams; };

vec4 debugTexel(ivec3 froxel, int view) {
    // The resolved sigma_t and S: the history's *_OUT side (integrate.comp; the layout: resources.glsl).
    vec4 a = imageLoad(historySourceOut, froxel);
    if (view == DEBUG_VIEW_DENSITY) return historyExtinctionOf(a, imageLoad(historyExtinctionOut, froxel));
    if (view == DEBUG_VIEW_SCATTERING) return historySourceOf(a);
    return imageLoad(integratedTransmittance, froxel);
}

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(px, frame.counts.xy))) return;
    int view = debugParams.view.x;
    ivec2 column = debugFroxelColumn(px, frame.froxelDims);
    int slice = debugSliceClamped(debugParams.view.y, frame.froxelDims.z);
    vec3 color = debugViewColor(debugTexel(ivec3(column, slice), view), view);
    imageStore(outputImage, px, vec4(color, 1.0f));
}
