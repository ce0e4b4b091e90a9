// Pass 4: fog over the rasterized scene, read from the integrated volume with the shared lookup
// rule (shd::integratedLookup; core: sampleIntegrated / compositeRow), then continued from the
// froxel far to the surface with the distant fog table (shared/distant_table.h, distant_fog.comp).
// The lights' glow is added after it by glow.comp, over the pixels near each glowing light only.
#version 450
#extension GL_GOOGLE_include_directive : require
#define BRUME_FROXEL_IMAGES
#include "resources.glsl"
#include "distant_table.h"

layout(local_size_x = SCREEN_GROUP_X, local_size_y = SCREEN_GROUP_Y, local_size_z = 1) in;
// The pixels dispatched, [lo.xy, hi.xy): those whose lookups can read a froxel column of the temporal
// region, or every pixel with height or depth fog (gpu/gpu_renderer.cpp compositePixels). The others
// would read scattering 0 and transmittance 1 everywhere, which leave the background as it is: the
// frame copies sceneColor over outputImage first (frame_executor.cpp recordComposite).
layout(push_constant) uniform RegionBlock { FroxelRegionParams region; };

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

// The distant fog table (shared/distant_table.h) at one corner and entry.
Accumulated distantTableAt(ivec2 corners, int x, int y, int j) {
    Accumulated a;
    if (j <= 0) return emptyAccumulated();
    int index = distantTableIndex(corners, ivec2(x, y), j);
    a.scattering = texelFetch(distantTexels, index).rgb;
    a.transmittance = texelFetch(distantTexels, index + 1).rgb;
    return a;
}

// Height and depth fog from the froxel far to viewDepth: the 4 corners around the pixel blended
// bilinearly at entries j-1 and j, then between the two in ray distance.
Accumulated distantFogAt(vec2 pixel, float viewDepth) {
    ivec2 corners = distantTableCorners(frame.counts.xy);
    DistantTableLookup k = distantTableLookup(pixel, viewDepth, frame, distantTableEntries(frame));
    Accumulated byEntry[2];
    for (int e = 0; e < 2; ++e) {
        int j = k.entry - 1 + e;
        Accumulated row0 = mixAccumulated(distantTableAt(corners, k.corners.x, k.corners.y, j),
                                          distantTableAt(corners, k.corners.z, k.corners.y, j), k.weights.x);
        Accumulated row1 = mixAccumulated(distantTableAt(corners, k.corners.x, k.corners.w, j),
                                          distantTableAt(corners, k.corners.z, k.corners.w, j), k.weights.x);
        byEntry[e] = mixAccumulated(row0, row1, k.weights.y);
    }
    return distantTableBlend(byEntry[0], byEntry[1], k.blend);
}

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy) + region.lo.xy;
    if (any(greaterThanEqual(px, region.hi.xy))) return;
    vec3 background = imageLoad(sceneColor, px).rgb;
    float viewDepth = imageLoad(sceneDepth, px).r;
    vec2 pixel = vec2(px) + vec2(0.5f);
    Accumulated fog = sampleIntegrated(pixel, viewDepth);
    float froxelFar = frame.froxelRange.y;
    // SPEC_DISTANT_FOG 0: no height or depth fog past the froxel far; the closed form is compiled out.
    if (SPEC_DISTANT_FOG != 0 && viewDepth > froxelFar) fog = composeAccumulated(fog, distantFogAt(pixel, viewDepth));
    vec3 color = compositeFog(background, fog);
    imageStore(outputImage, px, vec4(color, 1.0f));
}
