// The surfaces' exact fog transmittance toward each light the surfaces see, at every tile corner's
// pixel, and whether each light's blend may be taken on the tile this corner opens (its top-left
// corner): shared/surface_corners.h; the surface passes blend it per pixel.
#version 450
#extension GL_GOOGLE_include_directive : require
#define BRUME_FROXEL_IMAGES
#include "resources.glsl"
#include "fog_shadow.glsl"
#include "surface.glsl"

layout(local_size_x = SCREEN_GROUP_X, local_size_y = SCREEN_GROUP_Y) in;

bool surfaceAt(ivec2 px) { return imageLoad(sceneAlbedo, px).w > 0.0f; }

// Whether no box-kind volume can shade the tile toward light i (surfaceTileMayMeetVolume for each
// volume; core: surfaceTileClear).
bool tileClear(SurfaceTile t, int i) {
    if (!fogShadowsLight(lights[i], localFogShadowsFlag())) return true;  // transmittance 1 everywhere
    bool clear = true;
    for (int v = 0; v < frame.counts.z; ++v)
        if (surfaceTileMayMeetVolume(t, lights[i], volumes[v])) clear = false;
    return clear;
}

void main() {
    ivec2 dims = surfaceCornerDims(frame.counts.xy);
    ivec2 c = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(c, dims))) return;
    ivec2 px = surfaceCornerPixel(c, frame.counts.xy);
    int lightCount = frame.counts.w;
    bool surface = surfaceAt(px);
    SurfacePoint s = surfacePointAt(px);
    surfaceCorners[surfaceCornerIndex(dims, c, lightCount, 0)] = vec4(surface ? s.viewDepth : 0.0f, 0.0f, 0.0f, 0.0f);
    if (!surface) return;
    // The tile this corner opens, when all 4 of its corners are surfaces (else no pixel of it blends).
    bool tile = c.x + 1 < dims.x && c.y + 1 < dims.y;
    ivec2 px10 = surfaceCornerPixel(c + ivec2(1, 0), frame.counts.xy);
    ivec2 px01 = surfaceCornerPixel(c + ivec2(0, 1), frame.counts.xy);
    ivec2 px11 = surfaceCornerPixel(c + ivec2(1, 1), frame.counts.xy);
    tile = tile && surfaceAt(px10) && surfaceAt(px01) && surfaceAt(px11);
    SurfaceTile t = surfaceTileOf(s.worldPos, surfacePointAt(px10).worldPos, surfacePointAt(px01).worldPos,
                                  surfacePointAt(px11).worldPos, frame.cameraPosition.xyz);
    int reach = lightReachOffset(frame.froxelDims.xyz);
    int count = lightClusters[reach];
    for (int k = 0; k < count; ++k) {
        int i = lightClusters[reach + 1 + k];
        LightSample ls = evalLight(lights[i], s.worldPos);
        vec3 tr = lightFogTransmittance(lights[i], s.origin, ls.toLight, ls.distance);
        bool clear = tile && tileClear(t, i);
        surfaceCorners[surfaceCornerIndex(dims, c, lightCount, 1 + i)] = vec4(tr, clear ? 1.0f : 0.0f);
    }
}
