// The distant fog table (shared/distant_table.h): per corner of each 8x8 pixel tile, height and depth
// fog from the froxel far to each entry's view depth in closed form (shared/distant.h; core:
// buildDistantTable), lit by the directional lights (times the fog transmittance toward them, once
// per step) and the ambient. composite.comp interpolates it per pixel.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "resources.glsl"
#include "fog_shadow.glsl"
#include "distant_table.h"

layout(local_size_x = SCREEN_GROUP_X, local_size_y = SCREEN_GROUP_Y, local_size_z = 1) in;

// Height and depth fog along the camera ray between ray distances s0 and s1 as one piece, lit by the
// directional lights (their fog transmittance at the piece's geometric middle) and the ambient.
// Each light's transmittance is evaluated once per piece, outside the loop over volumes (it does not
// depend on the volume).
Accumulated accumulateDistantPiece(Accumulated a, vec3 dir, float s0, float s1) {
    vec3 middle = frame.cameraPosition.xyz + dir * sqrt(s0 * s1);
    DistantSegment seg = emptyDistantSegment();
    for (int i = 0; i < frame.counts.z; ++i) {
        float len = distantDensityLength(volumes[i], frame.cameraPosition.xyz, dir, s0, s1);
        seg = addDistantVolume(seg, volumes[i], len, frame.ambient.rgb);
    }
    // The surface lights (core/light_reach.h) hold every directional light that shines, in
    // increasing order, before any other: the CPU's sum over all lights, stopping at the first
    // local one (a skipped trip would cost as much as a taken one on lavapipe). Specialized: exactly
    // the directional lights, a fixed trip count.
    int reach = lightReachOffset(frame.froxelDims.xyz);
    int listed = SPEC_DIRECTIONAL_LIGHTS >= 0 ? SPEC_DIRECTIONAL_LIGHTS : lightClusters[reach];
    for (int k = 0; k < listed; ++k) {
        int j = lightClusters[reach + 1 + k];
        if (SPEC_DIRECTIONAL_LIGHTS < 0 && lights[j].kind.x != LIGHT_DIRECTIONAL) break;
        vec3 t = lightFogTransmittance(lights[j], middle, -lights[j].direction.xyz, BRUME_HUGE);
        for (int i = 0; i < frame.counts.z; ++i) {
            float len = distantDensityLength(volumes[i], frame.cameraPosition.xyz, dir, s0, s1);
            seg = addDistantLight(seg, volumes[i], len, distantLightPerSigmaS(lights[j], dir, volumes[i].sigmaS_g.w) * t);
        }
    }
    return accumulateDistant(a, seg);
}

void main() {
    // SPEC_DISTANT_FOG 0: no height or depth fog past the froxel far; nothing to tabulate.
    if (SPEC_DISTANT_FOG == 0) return;
    ivec2 corners = distantTableCorners(frame.counts.xy);
    ivec2 c = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(c, corners))) return;
    int n = distantTableEntries(frame);
    vec3 viewRay = viewRayFromPixel(vec2(c * DISTANT_TILE_PX), frame);
    float rayPerDepth = length(viewRay);
    vec3 dir = normalize(vec3(frame.worldFromView * vec4(viewRay, 0.0f)));
    Accumulated a = emptyAccumulated();
    for (int j = 1; j <= n; ++j) {
        a = accumulateDistantPiece(a, dir, distantTableDepth(frame, j - 1, n) * rayPerDepth,
                                   distantTableDepth(frame, j, n) * rayPerDepth);
        int index = distantTableIndex(corners, c, j);
        distantTable[index] = vec4(a.scattering, 0.0f);
        distantTable[index + 1] = vec4(a.transmittance, 0.0f);
    }
}
