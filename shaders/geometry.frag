// Lambert direct light + ambient + emission, as core/geometry.cpp shadeSurface without shadows
// (the shadows issue adds shadow maps). Writes radiance and view depth for the composite.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "resources.glsl"

layout(location = 0) in vec3 worldPos;
layout(location = 1) in vec3 worldNormal;
layout(location = 2) in vec3 albedo;
layout(location = 3) in vec3 emission;
layout(location = 4) in float viewDepth;

layout(location = 0) out vec4 outRadiance;
layout(location = 1) out float outViewDepth;

void main() {
    vec3 n = normalize(worldNormal);
    // Two-sided like the CPU's ray queries: the normal faces the camera.
    if (dot(n, frame.cameraPosition.xyz - worldPos) < 0.0f) n = -n;
    vec3 radiance = emission + albedo * frame.ambient.rgb;
    for (int i = 0; i < frame.counts.w; ++i) {
        radiance += lambert(albedo, n, evalLight(lights[i], worldPos));
    }
    outRadiance = vec4(radiance, 1.0f);
    outViewDepth = viewDepth;
}
