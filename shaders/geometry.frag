// The surfaces' G-buffer: the light-independent part of core/geometry.cpp shadeSurface (emission +
// ambient), the view depth with the two-sided normal, and the albedo. The lights are added by the
// surface passes (surface_body.glsl), which evaluate the fog's transmittance toward them per tile
// corner rather than per fragment (shared/surface_corners.h).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "resources.glsl"

layout(location = 0) in vec3 worldPos;
layout(location = 1) in vec3 worldNormal;
layout(location = 2) in vec3 albedo;
layout(location = 3) in vec3 emission;
layout(location = 4) in float viewDepth;

layout(location = 0) out vec4 outRadiance;     // sceneColor
layout(location = 1) out vec4 outDepthNormal;  // sceneDepth: view depth, normal
layout(location = 2) out vec4 outAlbedo;       // sceneAlbedo: albedo, 1 = a surface

void main() {
    vec3 n = normalize(worldNormal);
    // Two-sided like the CPU's ray queries: the normal faces the camera.
    if (dot(n, frame.cameraPosition.xyz - worldPos) < 0.0f) n = -n;
    outRadiance = vec4(emission + albedo * frame.ambient.rgb, 1.0f);
    outDepthNormal = vec4(viewDepth, n);
    outAlbedo = vec4(albedo, 1.0f);
}
