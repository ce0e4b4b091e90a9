// The lights on the surfaces (core/geometry.cpp shadeSurface with the froxel renderer's fog shadow
// and shadow maps), added to the geometry pass's emission + ambient in sceneColor. The fog's
// transmittance toward each light is the blend of the tile's corners where trusted
// (shared/surface_corners.h); elsewhere the exact closed form, which lavapipe would run for every
// pixel if it were behind a branch here (docs/performance.md), so it has a pass of its own:
//   surface_light.comp (every pixel): the trusted blends only; a pixel where some light's blend is
//     not trusted is appended to surfaceList and its sceneColor left for the second pass;
//   surface_exact.comp (indirect, one invocation per listed pixel): the whole sum, with the exact
//     form where the blend is not trusted, in the same order.
#define BRUME_FROXEL_IMAGES
#include "resources.glsl"
#include "fog_shadow.glsl"
#include "sun_shadow.glsl"
#include "local_shadow.glsl"
#include "surface.glsl"

#ifdef BRUME_SURFACE_EXACT
layout(local_size_x = SURFACE_EXACT_GROUP) in;
#else
layout(local_size_x = SCREEN_GROUP_X, local_size_y = SCREEN_GROUP_Y) in;

// Appends pixel px to surfaceList; the invocation that opens a workgroup's worth of entries adds
// that workgroup to the indirect dispatch.
void appendExact(ivec2 px) {
    uint slot = atomicAdd(surfaceList.count, 1u);
    surfaceExactPixels[slot] = uint(px.x + frame.counts.x * px.y);
    if (slot % uint(SURFACE_EXACT_GROUP) == 0u) atomicAdd(surfaceList.groupsX, 1u);
}
#endif

// rgb: the corner's transmittance toward the light; a: 1 where the tile the corner opens may blend it
// (no bounded volume in the way: surface_corners.comp).
vec4 cornerTransmittance(ivec2 dims, int cx, int cy, int light) {
    return surfaceCorners[surfaceCornerIndex(dims, ivec2(cx, cy), frame.counts.w, 1 + light)];
}

float cornerDepth(ivec2 dims, int cx, int cy) {
    return surfaceCorners[surfaceCornerIndex(dims, ivec2(cx, cy), frame.counts.w, 0)].x;
}

void main() {
#ifdef BRUME_SURFACE_EXACT
    uint slot = gl_GlobalInvocationID.x;
    if (slot >= surfaceList.count) return;
    uint linear = surfaceExactPixels[slot];
    ivec2 px = ivec2(int(linear % uint(frame.counts.x)), int(linear / uint(frame.counts.x)));
#else
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(px, frame.counts.xy))) return;
#endif
    vec4 albedo = imageLoad(sceneAlbedo, px);
    if (albedo.w == 0.0f) return;  // the sky: ambient, from the geometry pass's clear
    SurfacePoint s = surfacePointAt(px);
    vec3 radiance = imageLoad(sceneColor, px).rgb;  // emission + ambient (geometry.frag)
    ivec2 dims = surfaceCornerDims(frame.counts.xy);
    SurfaceCornerLookup k = surfaceCornerLookup(px, frame.counts.xy);
    bool covered = surfaceCornersCover(cornerDepth(dims, k.corners.x, k.corners.y), cornerDepth(dims, k.corners.z, k.corners.y),
                                       cornerDepth(dims, k.corners.x, k.corners.w), cornerDepth(dims, k.corners.z, k.corners.w),
                                       k.weights, s.viewDepth);
    // The vdb layer's lookup, once for all lights (fog_shadow.glsl surfaceFogTransmittance).
    SurfaceShadowLookup shadow = shadowLookupAt(froxelCoordFromWorld(s.origin, frame).xyz, frame, frame.shadowReduction);
    int sunLight = frame.sunShadowLight - 1;
    float sunVisibility = sunShadowVisibility(sunLight, s.origin);
    bool listed = false;
    // Only the lights that can reach the view frustum (core/light_reach.h), directional ones first.
    int reach = lightReachOffset(frame.froxelDims.xyz);
    int count = lightClusters[reach];
    for (int j = 0; j < count; ++j) {
        int i = lightClusters[reach + 1 + j];
        LightSample ls = evalLight(lights[i], s.worldPos);
        vec3 direct = lambert(albedo.rgb, s.normal, ls);
        if (direct == vec3(0.0f)) continue;
        vec4 c00 = cornerTransmittance(dims, k.corners.x, k.corners.y, i);
        vec3 t00 = c00.rgb;
        vec3 t10 = cornerTransmittance(dims, k.corners.z, k.corners.y, i).rgb;
        vec3 t01 = cornerTransmittance(dims, k.corners.x, k.corners.w, i).rgb;
        vec3 t11 = cornerTransmittance(dims, k.corners.z, k.corners.w, i).rgb;
        bool trusted = covered && c00.a > 0.0f && surfaceCornersAgree(t00, t10, t01, t11);
        vec3 t = surfaceCornerBlend(t00, t10, t01, t11, k.weights);
#ifdef BRUME_SURFACE_EXACT
        if (!trusted) t = lightFogTransmittance(lights[i], s.origin, ls.toLight, ls.distance);
#else
        if (!trusted) listed = true;
#endif
        radiance += direct * (t * surfaceVdbBlend(i, shadow)) * (i == sunLight ? sunVisibility : 1.0f) *
                    localShadowVisibility(i, s.origin);
    }
#ifndef BRUME_SURFACE_EXACT
    if (listed) {
        appendExact(px);
        return;
    }
#endif
    imageStore(sceneColor, px, vec4(radiance, 1.0f));
}
