// Lambert direct light x the fog's transmittance toward the light + ambient + emission, as
// core/geometry.cpp shadeSurface with the froxel renderer's fog shadow. Writes radiance and view depth for the composite.
#version 450
#extension GL_GOOGLE_include_directive : require
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
    // The same offset off the surface as the CPU's shadow rays (surfaceRayOffset).
    vec3 m = abs(worldPos);
    vec3 origin = worldPos + n * (1.0e-4f + 2.0e-6f * max(m.x, max(m.y, m.z)));
    SurfaceShadowLookup shadow = shadowLookupAt(froxelCoordFromWorld(origin, frame).xyz, frame, frame.shadowReduction);
    // The sun shadow map serves one light (frame.sunShadowLight): looked up once, not in every trip of
    // the light loop (lavapipe runs the lookup for every light, mapped or not: docs/performance.md).
    int sunLight = frame.sunShadowLight - 1;
    // The volumes of the fog transmittance, fetched once for every light (fog_shadow.glsl fogVolumes).
    FogVolumes volumes = fogVolumes();
    float sunVisibility = sunShadowVisibility(sunLight, origin);
    // Only the lights that can reach the view frustum (core/light_reach.h), directional ones first.
    int reach = lightReachOffset(frame.froxelDims.xyz);
    int count = clusterInt(reach);
    for (int k = 0; k < count; ++k) {
        int i = clusterInt(reach + 1 + k);
        LightSample ls = evalLight(lightAt(i), worldPos);
        vec3 direct = lambert(albedo, n, ls);
        if (direct == vec3(0.0f)) continue;
        radiance += direct * surfaceFogTransmittance(volumes, i, shadow, origin, ls.toLight, ls.distance) *
                    (i == sunLight ? sunVisibility : 1.0f) * localShadowVisibility(i, origin);
    }
    outRadiance = vec4(radiance, 1.0f);
    outViewDepth = viewDepth;
}
