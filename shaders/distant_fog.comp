// The distant fog table (shared/distant_table.h): per corner of each 8x8 pixel tile, height and depth
// fog from the froxel far to each entry's view depth in closed form (shared/distant.h; core:
// buildDistantTable), lit by the directional lights (times the fog transmittance toward them, once
// per step) and the ambient. composite.comp interpolates it per pixel.
#version 450
#extension GL_GOOGLE_include_directive : require
#define BRUME_FROXEL_IMAGES
// Lights, clusters and volumes through texel views (resources.glsl; docs/performance.md "light3").
#define BRUME_LIGHT_TEXELS
#define BRUME_VOLUME_TEXELS
#include "resources.glsl"
#include "fog_shadow.glsl"
#include "distant_table.h"

layout(local_size_x = SCREEN_GROUP_X, local_size_y = SCREEN_GROUP_Y, local_size_z = 1) in;
#include "balanced_groups.glsl"

// Volume i's density length over the piece [s0, s1] (shared/distant.h). With the scene's volume list
// specialized (SPEC_VOLUME_COUNT >= 0; this pass gets the scene's whole list, none culled) the sums
// below are unrolled, i is a constant and so is its kind: only that kind's form is built for it, a box
// none, and the light sum's lengths are the volume sum's expressions again. The loop over
// frame.counts.z ran every used kind's form for every volume, twice per light (lavapipe runs every
// branch): docs/performance.md, "pixel" of round six.
// v: volume i (fetched once per invocation for the listed volumes: fogVolumes()).
float pieceLength(int i, VolumeData v, vec3 dir, float s0, float s1) {
    if (SPEC_VOLUME_COUNT >= 0) v.kind.x = listedVolumeKind(i);  // the same value, as a constant
    return distantDensityLength(v, frame.cameraPosition.xyz, dir, s0, s1);
}

// Height and depth fog along the camera ray between ray distances s0 and s1 as one piece, lit by the
// directional lights (their fog transmittance at the piece's geometric middle) and the ambient.
// Each light's transmittance is evaluated once per piece, outside the sum over volumes (it does not
// depend on the volume). The sums run over the volumes in order, as the CPU's (buildDistantTable).
// vs: the listed volumes, fetched once per invocation for all its pieces (fog_shadow.glsl
// fogVolumes; docs/performance.md "hoist").
Accumulated accumulateDistantPiece(FogVolumes vs, Accumulated a, vec3 dir, float s0, float s1) {
    vec3 middle = frame.cameraPosition.xyz + dir * sqrt(s0 * s1);
    DistantSegment seg = emptyDistantSegment();
    if (SPEC_VOLUME_COUNT >= 0) {
#define BRUME_DISTANT_VOLUME(i) \
    if (BRUME_SPEC_VOLUME_LISTED(i)) seg = addDistantVolume(seg, vs.v##i, pieceLength(i, vs.v##i, dir, s0, s1), frame.ambient.rgb);
        BRUME_EACH_LISTED_VOLUME(BRUME_DISTANT_VOLUME)
#undef BRUME_DISTANT_VOLUME
    } else {
        for (int i = 0; i < frame.counts.z; ++i) {
            VolumeData v = volumeAt(i);
            seg = addDistantVolume(seg, v, pieceLength(i, v, dir, s0, s1), frame.ambient.rgb);
        }
    }
    // The surface lights (core/light_reach.h) hold every directional light that shines, in
    // increasing order, before any other: the CPU's sum over all lights, stopping at the first
    // local one (a skipped trip would cost as much as a taken one on lavapipe). Specialized: exactly
    // the directional lights, a fixed trip count.
    // With their count a constant that the surface light slots hold (shared/bindings.h SurfaceLights: the
    // reach's first lights, the directional ones), each light comes from its slot's uniforms at a
    // constant offset with its kind a constant, not through the reach list and lightTexels' gathers
    // (docs/performance.md, "surfacelights").
    const bool slots = SPEC_DIRECTIONAL_LIGHTS >= 0 && SPEC_DIRECTIONAL_LIGHTS <= SURFACE_LIGHT_SLOTS;
    int reach = lightReachOffset(frame.froxelDims.xyz);
    int listed = SPEC_DIRECTIONAL_LIGHTS >= 0 ? SPEC_DIRECTIONAL_LIGHTS : clusterInt(reach);
    for (int k = 0; k < listed; ++k) {
        LightData l;
        if (slots) {
            l = surfaceLights.light[k];
            l.kind.x = LIGHT_DIRECTIONAL;
        } else {
            l = lightAt(clusterInt(reach + 1 + k));
        }
        if (SPEC_DIRECTIONAL_LIGHTS < 0 && l.kind.x != LIGHT_DIRECTIONAL) break;
        vec3 t = lightFogTransmittance(vs, l, middle, -l.direction.xyz, BRUME_HUGE);
        if (SPEC_VOLUME_COUNT >= 0) {
#define BRUME_DISTANT_LIGHT(i)                                                                                   \
    if (BRUME_SPEC_VOLUME_LISTED(i))                                                                             \
        seg = addDistantLight(seg, vs.v##i, pieceLength(i, vs.v##i, dir, s0, s1),                                \
                              distantLightPerSigmaS(l, dir, vs.v##i.sigmaS_g.w) * t);
            BRUME_EACH_LISTED_VOLUME(BRUME_DISTANT_LIGHT)
#undef BRUME_DISTANT_LIGHT
        } else {
            for (int i = 0; i < frame.counts.z; ++i) {
                VolumeData v = volumeAt(i);
                seg = addDistantLight(seg, v, pieceLength(i, v, dir, s0, s1), distantLightPerSigmaS(l, dir, v.sigmaS_g.w) * t);
            }
        }
    }
    return accumulateDistant(a, seg);
}

// How many of corner c's n entries the composite can read: its pixels are those whose bilinear
// lookup (distantTableLookup) takes this corner, [8 (c - 1), 8 c + 7] in x and y; one reads entries
// j - 1 and j for its depth's j, and nothing at or before the froxel far. The entries past the
// deepest pixel's are left unwritten: at `low` (froxel far 48 m, camera far 100 m: 8 entries) most
// of the default scene's corners see only ground and walls within the froxels. The deepest pixel is
// the deepest of the corner's tiles c - 1 and c per axis (the depth tiles pass, depth_tiles.comp: a
// pixel read once, not by 4 corners). Only where more than DISTANT_TABLE_SCAN_FROM entries are at
// stake: at `high` the table has one entry, and the depth tiles pass writes nothing.
int distantTableEntriesRead(ivec2 c, int n) {
    if (n <= DISTANT_TABLE_SCAN_FROM) return n;
    ivec2 tiles = depthTileCount(frame.counts.xy);
    ivec2 first = max(c - 1, ivec2(0));
    ivec2 last = min(c, tiles - 1);
    float deepest = 0.0f;
    for (int y = first.y; y <= last.y; ++y)
        for (int x = first.x; x <= last.x; ++x) deepest = max(deepest, texelFetch(depthTileTexels, depthTileIndex(tiles, ivec2(x, y))).x);
    if (!(deepest > frame.froxelRange.y)) return 0;
    // One entry more than the deepest pixel's: the lookup's log and ceil need not match bit for bit.
    return min(distantTableLookup(vec2(0.0f), deepest, frame, n).entry + 1, n);
}

void main() {
    // SPEC_DISTANT_FOG 0: no height or depth fog past the froxel far; nothing to tabulate.
    if (SPEC_DISTANT_FOG == 0) return;
    ivec2 corners = distantTableCorners(frame.counts.xy);
    // Workgroups interleaved between lavapipe's threads (balanced_groups.glsl): the sky's corners walk
    // every entry of the table, the ground's those up to their pixels' depths.
    ivec2 c = ivec2(balancedGlobalID().xy);
    if (any(greaterThanEqual(c, corners))) return;
    int n = distantTableEntries(frame);
    int needed = distantTableEntriesRead(c, n);
    vec3 viewRay = viewRayFromPixel(vec2(c * DISTANT_TILE_PX), frame);
    float rayPerDepth = length(viewRay);
    vec3 dir = normalize(vec3(frame.worldFromView * vec4(viewRay, 0.0f)));
    Accumulated a = emptyAccumulated();
    // Each step starts where the previous one ended: one distantTableDepth (a pow) per step, not two.
    float stepStart = distantTableDepth(frame, 0, n) * rayPerDepth;
    FogVolumes volumes = fogVolumes();
    for (int j = 1; j <= needed; ++j) {
        float stepEnd = distantTableDepth(frame, j, n) * rayPerDepth;
        a = accumulateDistantPiece(volumes, a, dir, stepStart, stepEnd);
        stepStart = stepEnd;
        int index = distantTableIndex(corners, c, j);
        distantTable[index] = vec4(a.scattering, 0.0f);
        distantTable[index + 1] = vec4(a.transmittance, 0.0f);
    }
}
