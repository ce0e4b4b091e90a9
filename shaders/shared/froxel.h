// Froxel grid mapping, written once for the CPU froxel renderer and the GPU passes.
//
// Depth slices follow a power law in view depth z (distance along the camera's -Z axis):
//     z(t) = near + (far - near) * t^k,      t = slice coordinate / slice count in [0, 1]
//     t(z) = ((z - near) / (far - near))^(1/k)
// k = 1 spaces slices evenly; k > 1 packs them near the camera, where froxels are small on screen.
// Froxel (i, j, s) covers pixels [i*tile, (i+1)*tile) x [j*tile, (j+1)*tile) and depths z(s/N)..z((s+1)/N).
// Integration starts at the camera (z = 0): the first slice also holds the gap [0, near].
#ifndef BRUME_SHARED_FROXEL_H
#define BRUME_SHARED_FROXEL_H

#include "types.h"

BRUME_NAMESPACE_BEGIN

int brumeDivRoundUp(int n, int d) { return (n + d - 1) / d; }

float viewDepthFromSliceT(float t, float zNear, float zFar, float exponent) {
    float tc = clamp(t, 0.0f, 1.0f);
    return zNear + (zFar - zNear) * pow(tc, exponent);
}

float sliceTFromViewDepth(float z, float zNear, float zFar, float exponent) {
    float u = clamp((z - zNear) / (zFar - zNear), 0.0f, 1.0f);
    return pow(u, 1.0f / exponent);
}

// View-space direction through a pixel-space position (pixels, origin top-left, y down), scaled so
// that its z is -1: the point at view depth z is ray * z.
vec3 viewRayFromPixel(vec2 pixel, FrameUniforms f) {
    float ndcX = 2.0f * pixel.x / float(f.counts.x) - 1.0f;
    float ndcY = 1.0f - 2.0f * pixel.y / float(f.counts.y);
    return vec3(ndcX * f.projection.x, ndcY * f.projection.y, -1.0f);
}

// World position of a point given in froxel coordinates (x, y in tiles, z in slices; fractional).
vec3 worldFromFroxelCoord(vec3 coord, FrameUniforms f) {
    vec2 pixel = vec2(coord.x, coord.y) * float(f.froxelDims.w);
    float t = coord.z / float(f.froxelDims.z);
    float z = viewDepthFromSliceT(t, f.froxelRange.x, f.froxelRange.y, f.froxelRange.z);
    vec3 viewPos = viewRayFromPixel(pixel, f) * z;
    return vec3(f.worldFromView * vec4(viewPos, 1.0f));
}

// Length of the camera ray inside slice s of the pixel column through `pixel` [m].
float sliceRayLength(int s, vec2 pixel, FrameUniforms f) {
    float n = float(f.froxelDims.z);
    float z0 = s == 0 ? 0.0f
                      : viewDepthFromSliceT(float(s) / n, f.froxelRange.x, f.froxelRange.y, f.froxelRange.z);
    float z1 = viewDepthFromSliceT(float(s + 1) / n, f.froxelRange.x, f.froxelRange.y, f.froxelRange.z);
    return (z1 - z0) * length(viewRayFromPixel(pixel, f));
}

// The integrated volume stores, at slice s, the result from the camera to the far boundary of s,
// i.e. at t = (s + 1) / N. Given a view depth, returns the continuous slice-entry coordinate w
// (entry index + fraction) to interpolate at; w < 0 means "between the camera and entry 0", to be
// blended with the empty result (scattering 0, transmittance 1) by (w + 1).
float integratedEntryFromViewDepth(float z, FrameUniforms f) {
    float t = sliceTFromViewDepth(z, f.froxelRange.x, f.froxelRange.y, f.froxelRange.z);
    return t * float(f.froxelDims.z) - 1.0f;
}

BRUME_NAMESPACE_END

#endif
