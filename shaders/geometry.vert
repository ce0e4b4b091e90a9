// Preview geometry: world-space triangles (tessellated on the CPU by gpu/geometry_mesh.cpp).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "resources.glsl"

layout(location = 0) in vec4 inPosition;  // xyz world [m]
layout(location = 1) in vec4 inNormal;    // xyz world, unit
layout(location = 2) in vec4 inAlbedo;
layout(location = 3) in vec4 inEmission;

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
