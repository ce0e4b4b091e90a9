// Preview geometry: world-space triangles (tessellated on the CPU by gpu/geometry_mesh.cpp). Built with
// BRUME_SPHERE as geometry_sphere.vert for the sphere proxies: their fragments ray cast the sphere
// (sphere_ray.glsl), which they get flat with its colours; with BRUME_SPHERE_DEPTH too as
// geometry_sphere_depth.vert, the sphere alone for the depth pre-pass.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "resources.glsl"

layout(location = 0) in vec4 inPosition;  // xyz world [m]
layout(location = 1) in vec4 inNormal;    // xyz world, unit
layout(location = 2) in vec4 inAlbedo;
layout(location = 3) in vec4 inEmission;

#ifdef BRUME_SPHERE
layout(location = 0) flat out vec4 sphere;  // xyz centre [m], w radius [m]
#ifndef BRUME_SPHERE_DEPTH
layout(location = 1) flat out vec3 albedo;
layout(location = 2) flat out vec3 emission;
#endif

void main() {
    sphere = inNormal;
#ifndef BRUME_SPHERE_DEPTH
    albedo = inAlbedo.rgb;
    emission = inEmission.rgb;
#endif
    gl_Position = frame.clipFromWorld * vec4(inPosition.xyz, 1.0f);
}
#else
layout(location = 0) out vec3 worldPos;
layout(location = 1) out vec3 worldNormal;
layout(location = 2) out vec3 albedo;
layout(location = 3) out vec3 emission;
layout(location = 4) out float viewDepth;
// The depth pre-pass and the shading pass must rasterize the same depths (EQUAL test).
invariant gl_Position;

void main() {
    worldPos = inPosition.xyz;
    worldNormal = inNormal.xyz;
    albedo = inAlbedo.rgb;
    emission = inEmission.rgb;
    // Perspective-correct interpolation of view z is exact on a planar triangle.
    viewDepth = -(frame.viewFromWorld * vec4(inPosition.xyz, 1.0f)).z;
    gl_Position = frame.clipFromWorld * vec4(inPosition.xyz, 1.0f);
}
#endif
