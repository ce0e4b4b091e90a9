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
// The temporal region (core/media_region.h temporalFroxelRegion): outside its columns the integrated
// volumes hold scattering 0 and transmittance 1 at every slice (gpu/pass_temporal.cpp's clears).
layout(push_constant) uniform RegionBlock { FroxelRegionParams region; };

// Whether some pixel of this workgroup looks up (integratedLookup: columns floor(pixel / tile - 0.5)
// and the next, clamped) a froxel column of the region. Uniform over the workgroup, so lavapipe
// branches on it instead of running both sides.
bool groupReadsFog() {
    ivec2 first = ivec2(gl_WorkGroupID.xy) * ivec2(SCREEN_GROUP_X, SCREEN_GROUP_Y);
    ivec2 last = first + ivec2(SCREEN_GROUP_X - 1, SCREEN_GROUP_Y - 1);
    int tile = frame.froxelDims.w;
    ivec2 lo = max(first / tile - ivec2(1), ivec2(0));   // at or below every pixel's lower column
    ivec2 hi = last / tile + ivec2(1);                    // at or above every pixel's upper column
    return all(lessThanEqual(region.lo.xy, hi)) && all(greaterThan(region.hi.xy, lo));
}

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
    a.scattering = distantTable[index].rgb;
    a.transmittance = distantTable[index + 1].rgb;
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
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(px, frame.counts.xy))) return;
    vec3 color = imageLoad(sceneColor, px).rgb;
    // Without height or depth fog, and with no column of the region under the workgroup, every
    // lookup reads scattering 0 and transmittance 1, which leave the background as it is: skipped.
    if (SPEC_DISTANT_FOG != 0 || groupReadsFog()) {
        float viewDepth = imageLoad(sceneDepth, px).r;
        vec2 pixel = vec2(px) + vec2(0.5f);
        Accumulated fog = sampleIntegrated(pixel, viewDepth);
        float froxelFar = frame.froxelRange.y;
        // SPEC_DISTANT_FOG 0: no height or depth fog past the froxel far; the closed form is compiled out.
        if (SPEC_DISTANT_FOG != 0 && viewDepth > froxelFar) fog = composeAccumulated(fog, distantFogAt(pixel, viewDepth));
        color = compositeFog(color, fog);
    }
    imageStore(outputImage, px, vec4(color, 1.0f));
}
