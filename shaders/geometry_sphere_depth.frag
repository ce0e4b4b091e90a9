// The depth pre-pass of sphere proxies (gpu/geometry_mesh.h): the ray cast's depth where the pixel's
// ray hits the sphere, nothing elsewhere.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "resources.glsl"
#include "sphere_ray.glsl"

layout(location = 0) flat in vec4 sphere;  // xyz centre [m], w radius [m]

void main() {
    SphereRayHit h = sphereRayHit(sphere.xyz, sphere.w);
    if (!h.hit) discard;
    gl_FragDepth = h.depth;
}
