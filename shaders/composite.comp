// Pass 4: fog over the rasterized scene, read from the integrated volume with the shared lookup
// rule (shd::integratedLookup; core: sampleIntegrated / compositeRow), then continued in closed
// form from the froxel far to the surface (shared/distant.h; core: accumulateDistantFog).
#version 450
#extension GL_GOOGLE_include_directive : require
#define BRUME_FROXEL_IMAGES
#include "resources.glsl"
#include "fog_shadow.glsl"

layout(local_size_x = SCREEN_GROUP_X, local_size_y = SCREEN_GROUP_Y, local_size_z = 1) in;

Accumulated integratedAt(int x, int y, int s) {
    Accumulated a;
    a.scattering = imageLoad(integratedScattering, ivec3(x, y, s)).rgb;
    a.transmittance = imageLoad(integratedTransmittance, ivec3(x, y, s)).rgb;
    return a;
}

Accumulated sampleIntegrated(vec2 pixel, float viewDepth) {
    IntegratedLookup k = integratedLookup(pixel, viewDepth, frame);
    Accumulated byEntry[2];
    for (int e = 0; e < 2; ++e) {
        int s = k.entries[e];
        Accumulated row0 = mixAccumulated(integratedAt(k.columns.x, k.columns.y, s),
                                          integratedAt(k.columns.z, k.columns.y, s), k.weights.x);
        Accumulated row1 = mixAccumulated(integratedAt(k.columns.x, k.columns.w, s),
                                          integratedAt(k.columns.z, k.columns.w, s), k.weights.x);
        byEntry[e] = mixAccumulated(row0, row1, k.weights.y);
    }
    Accumulated entries = mixAccumulated(byEntry[0], byEntry[1], k.weights.z);
    return mixAccumulated(emptyAccumulated(), entries, k.entryWeight);
}

// Height and depth fog along the camera ray between ray distances s0 and s1, lit by the
// directional lights (times the fog transmittance toward them, per piece) and the ambient.
// Each light's transmittance is evaluated once per piece, outside the loop over volumes (it does
// not depend on the volume): inside it, the pass cost O(volumes^2) transmittance terms per piece.
Accumulated accumulateDistantFog(Accumulated a, vec3 dir, float s0, float s1) {
    if (!(s1 > s0)) return a;
    // The surface lights (core/light_reach.h) hold every directional light that shines, in
    // increasing order, before any other: the CPU's sum over all lights, stopping at the first
    // local one (a skipped trip would cost as much as a taken one on lavapipe).
    int reach = lightReachOffset(frame.froxelDims.xyz);
    int pieces = distantShadowPieceCount(s0, s1);
    for (int piece = 0; piece < pieces; ++piece) {
        vec2 b = distantShadowPiece(s0, s1, piece, pieces);
        vec3 middle = frame.cameraPosition.xyz + dir * sqrt(b.x * b.y);
        DistantSegment seg = emptyDistantSegment();
        for (int i = 0; i < frame.counts.z; ++i) {
            float len = distantDensityLength(volumes[i], frame.cameraPosition.xyz, dir, b.x, b.y);
            seg = addDistantVolume(seg, volumes[i], len, frame.ambient.rgb);
        }
        for (int k = 0; k < lightClusters[reach]; ++k) {
            int j = lightClusters[reach + 1 + k];
            if (lights[j].kind.x != LIGHT_DIRECTIONAL) break;
            vec3 t = lightFogTransmittance(lights[j], middle, -lights[j].direction.xyz, BRUME_HUGE);
            for (int i = 0; i < frame.counts.z; ++i) {
                float len = distantDensityLength(volumes[i], frame.cameraPosition.xyz, dir, b.x, b.y);
                seg = addDistantLight(seg, volumes[i], len, distantLightPerSigmaS(lights[j], dir, volumes[i].sigmaS_g.w) * t);
            }
        }
        a = accumulateDistant(a, seg);
    }
    return a;
}

// The per-pixel part of the point and spot lights' glow (shared/glow.h; core: compositeRow), summed
// in light order. Lavapipe runs every branch and every loop trip of a batch's slowest lane
// (docs/performance.md): a cheap test counts the lights whose ball this ray meets, and the quadrature
// runs that many trips (once, masked, where none), not once per light.
vec3 lightGlow(vec2 pixel, float viewDepth) {
    vec3 viewRay = viewRayFromPixel(pixel, frame);
    float rayPerDepth = length(viewRay);
    vec3 dir = normalize(vec3(frame.worldFromView * vec4(viewRay, 0.0f)));
    vec3 origin = frame.cameraPosition.xyz;
    float rayEnd = viewDepth * rayPerDepth;
    int hits = 0;
    for (int i = 0; i < frame.counts.w; ++i) {
        if (lightGlowRay(lights[i], frame, origin, dir, rayEnd).radius > 0.0f) ++hits;
    }
    vec3 sum = vec3(0.0f);
    int next = 0;
    for (int k = 0; k < hits; ++k) {
        int i = next;
        LightGlowRay r = lightGlowRay(lights[i], frame, origin, dir, rayEnd);
        while (r.radius <= 0.0f && i + 1 < frame.counts.w) {
            ++i;
            r = lightGlowRay(lights[i], frame, origin, dir, rayEnd);
        }
        next = i + 1;
        ivec3 m = lightGlowFroxel(r, origin, dir, frame);
        vec4 scatteringG = imageLoad(mediaScatteringG, m);
        vec3 sigmaT = imageLoad(mediaExtinction, m).rgb;
        vec3 toEnter = sampleIntegrated(pixel, r.enter / rayPerDepth).transmittance;
        sum += toEnter * scatteringG.rgb * lightGlowPerSigmaS(lights[i], r, origin, dir, sigmaT, scatteringG.a);
    }
    return sum;
}

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(px, frame.counts.xy))) return;
    vec3 background = imageLoad(sceneColor, px).rgb;
    float viewDepth = imageLoad(sceneDepth, px).r;
    vec2 pixel = vec2(px) + vec2(0.5f);
    Accumulated fog = sampleIntegrated(pixel, viewDepth);
    float froxelFar = frame.froxelRange.y;
    if (viewDepth > froxelFar) {
        // viewRay has z = -1: ray distance = view depth * its length.
        vec3 viewRay = viewRayFromPixel(pixel, frame);
        float rayPerDepth = length(viewRay);
        vec3 dir = normalize(vec3(frame.worldFromView * vec4(viewRay, 0.0f)));
        fog = accumulateDistantFog(fog, dir, froxelFar * rayPerDepth, viewDepth * rayPerDepth);
    }
    fog.scattering += lightGlow(pixel, viewDepth);
    vec3 color = compositeFog(background, fog);
    imageStore(outputImage, px, vec4(color, 1.0f));
}
