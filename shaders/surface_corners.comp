// The surfaces' exact fog transmittance toward each light the surfaces see, at every tile corner's
// pixel (shared/surface_corners.h); the surface passes blend it per pixel.
#version 450
#extension GL_GOOGLE_include_directive : require
#define BRUME_FROXEL_IMAGES
#include "resources.glsl"
#include "fog_shadow.glsl"
#include "surface.glsl"

layout(local_size_x = SCREEN_GROUP_X, local_size_y = SCREEN_GROUP_Y) in;

void main() {
    ivec2 dims = surfaceCornerDims(frame.counts.xy);
    ivec2 c = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(c, dims))) return;
    ivec2 px = surfaceCornerPixel(c, frame.counts.xy);
    int lightCount = frame.counts.w;
    bool surface = imageLoad(sceneAlbedo, px).w > 0.0f;
    SurfacePoint s = surfacePointAt(px);
    surfaceCorners[surfaceCornerIndex(dims, c, lightCount, 0)] = vec4(surface ? s.viewDepth : 0.0f, 0.0f, 0.0f, 0.0f);
    if (!surface) return;
    int reach = lightReachOffset(frame.froxelDims.xyz);
    int count = lightClusters[reach];
    for (int k = 0; k < count; ++k) {
        int i = lightClusters[reach + 1 + k];
        LightSample ls = evalLight(lights[i], s.worldPos);
        vec3 t = lightFogTransmittance(lights[i], s.origin, ls.toLight, ls.distance);
        surfaceCorners[surfaceCornerIndex(dims, c, lightCount, 1 + i)] = vec4(t, 0.0f);
    }
}
