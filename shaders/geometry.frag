// Lambert direct light x the fog's transmittance toward the light + ambient + emission, as
// core/geometry.cpp shadeSurface with the froxel renderer's fog shadow. Writes radiance and view depth for the composite.
#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// Lights, clusters and volumes through texel views (resources.glsl; docs/performance.md "light3").
#define BRUME_LIGHT_TEXELS
#define BRUME_VOLUME_TEXELS
#include "resources.glsl"
#include "fog_shadow.glsl"
#include "sun_shadow.glsl"
#include "local_shadow.glsl"
#ifdef BRUME_SPHERE
#include "sphere_ray.glsl"
#endif

#ifdef BRUME_SPHERE
// Built as geometry_sphere.frag: a sphere proxy's fragment (geometry_mesh.h), shaded where the ray
// cast hits the sphere, at the depth the pre-pass wrote (geometry_sphere_depth.frag).
layout(location = 0) flat in vec4 sphere;  // xyz centre [m], w radius [m]
layout(location = 1) flat in vec3 albedo;
layout(location = 2) flat in vec3 emission;
#else
layout(location = 0) in vec3 worldPos;
layout(location = 1) in vec3 worldNormal;
layout(location = 2) in vec3 albedo;
layout(location = 3) in vec3 emission;
layout(location = 4) in float viewDepth;
#endif

layout(location = 0) out vec4 outRadiance;
layout(location = 1) out float outViewDepth;

// What every light's term needs of the fragment, computed once.
struct SurfacePoint {
    vec3 position;  // on the surface [m]
    vec3 normal;    // unit, facing the camera
    vec3 albedo;
    vec3 origin;    // the shadow rays' start, off the surface
    SurfaceShadowLookup shadow;
    FogVolumes volumes;
    float sunVisibility;  // through the sun shadow map, for the light it serves
};

// Light i's radiance off the surface (l: its data): Lambert x the fog's transmittance toward it x its
// shadow maps' visibility; 0 where the surface faces away from it.
vec3 surfaceLightTerm(LightData l, int i, SurfacePoint f) {
    LightSample ls = evalLight(l, f.position);
    vec3 direct = lambert(f.albedo, f.normal, ls);
    if (direct == vec3(0.0f)) return vec3(0.0f);
    return direct * surfaceFogTransmittance(f.volumes, l, i, f.shadow, f.origin, ls.toLight, ls.distance) *
           (i == frame.sunShadowLight - 1 ? f.sunVisibility : 1.0f) * localShadowVisibility(l, f.origin);
}

// Surface slot s (shared/bindings.h SurfaceLights) with its kind the pipeline's constant: the same light
// as lightAt(surfaceLights.index[s].x), and only its kind's code is built.
LightData surfaceSlot(int s) {
    LightData l = surfaceLights.light[s];
    l.kind.x = BRUME_SPEC_SURFACE_LIGHT_KIND(SPEC_SURFACE_LIGHTS, s);
    return l;
}

void main() {
#ifdef BRUME_SPHERE
    SphereRayHit h = sphereRayHit(sphere.xyz, sphere.w);
    if (!h.hit) discard;
    gl_FragDepth = h.depth;
    vec3 worldPos = h.position;
    vec3 n = h.normal;
    float viewDepth = h.viewDepth;
#else
    vec3 n = normalize(worldNormal);
    // Two-sided like the CPU's ray queries: the normal faces the camera.
    if (dot(n, frame.cameraPosition.xyz - worldPos) < 0.0f) n = -n;
#endif
    vec3 radiance = emission + albedo * frame.ambient.rgb;
    SurfacePoint f;
    f.position = worldPos;
    f.normal = n;
    f.albedo = albedo;
    // The same offset off the surface as the CPU's shadow rays (surfaceRayOffset).
    vec3 m = abs(worldPos);
    f.origin = worldPos + n * (1.0e-4f + 2.0e-6f * max(m.x, max(m.y, m.z)));
    f.shadow = shadowLookupAt(froxelCoordFromWorld(f.origin, frame).xyz, frame, frame.shadowReduction);
    // The volumes of the fog transmittance, fetched once for every light (fog_shadow.glsl fogVolumes).
    f.volumes = fogVolumes();
    // The sun shadow map serves one light (frame.sunShadowLight): looked up once, not in every light's
    // term (lavapipe runs the lookup for every light, mapped or not: docs/performance.md).
    f.sunVisibility = sunShadowVisibility(frame.sunShadowLight - 1, f.origin);
    // Only the lights that can reach the view frustum (core/light_reach.h), directional ones first.
    if (SPEC_SURFACE_LIGHTS >= 0) {
        // Unrolled over the slots the constant lists: no reach list to read, each light's uniforms at a
        // constant offset, and each slot's kind a constant (docs/performance.md, "surfacelights"). A
        // loop, not the slots written out: Mesa inlines every written-out copy before it folds the
        // count, and compiled 8 copies' worth (2.6 s for a first frame); it unrolls this one to the count.
        [[unroll]] for (int s = 0; s < BRUME_SPEC_SURFACE_LIGHT_COUNT(SPEC_SURFACE_LIGHTS); ++s)
            radiance += surfaceLightTerm(surfaceSlot(s), surfaceLights.index[s].x, f);
    } else {
        int reach = lightReachOffset(frame.froxelDims.xyz);
        int count = clusterInt(reach);
        for (int k = 0; k < count; ++k) {
            int i = clusterInt(reach + 1 + k);
            radiance += surfaceLightTerm(lightAt(i), i, f);
        }
    }
    outRadiance = vec4(radiance, 1.0f);
    outViewDepth = viewDepth;
}
