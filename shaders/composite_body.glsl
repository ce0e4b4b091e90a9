// Pass 4: fog over the rasterized scene, read from the integrated volume with the shared lookup
// rule (shd::integratedLookup; core: sampleIntegrated / compositeRow), then, past the froxel far,
// continued to the surface with the distant fog table (shared/distant_table.h, distant_fog.comp).
// The lights' glow is added after it by glow.comp, over the pixels near each glowing light only.
//
// Three builds of this body: composite.comp without the distant fog table's lookup, over the region's
// pixels or (with distant fog) the tiles whose pixels all lie within the froxel far; composite_far.comp
// (BRUME_COMPOSITE_FAR) with it, over the tiles that straddle the far; composite_all_far.comp (both
// defines) with it and one entry of the integrated volume, over the tiles whose pixels all lie past
// the far (tile_lists.comp). Lavapipe runs an untaken branch under a mask, so a single shader paid for
// the 16 table reads on every pixel (docs/performance.md, "pixel"), and the far one for 8 integrated
// loads that an all-far pixel reads twice ("allfar"); split by tile, each pixel computes exactly what
// the single shader computed.

layout(local_size_x = SCREEN_GROUP_X, local_size_y = SCREEN_GROUP_Y, local_size_z = 1) in;
// The pixels composited, [lo.xy, hi.xy): those whose lookups can read a froxel column of the temporal
// region, or every pixel with height or depth fog (gpu/gpu_renderer.cpp compositePixels). The others
// would read scattering 0 and transmittance 1 everywhere, which leave the background as it is: the
// frame copies sceneColor over outputImage first (frame_executor.cpp recordComposite). Without distant
// fog the dispatch covers the region; with it, the tiles of the variant's list (tile_lists.comp).
layout(push_constant) uniform RegionBlock { FroxelRegionParams region; };

Accumulated integratedAt(int x, int y, int s) {
    Accumulated a;
    a.scattering = imageLoad(integratedScattering, ivec3(x, y, s)).rgb;
    a.transmittance = imageLoad(integratedTransmittance, ivec3(x, y, s)).rgb;
    return a;
}

#include "integrated_lookup.glsl"

Accumulated sampleIntegrated(vec2 pixel, float viewDepth) {
    IntegratedLookup k = integratedLookup(pixel, viewDepth, frame);
    Accumulated byEntry[2];
#ifdef BRUME_COMPOSITE_ALL_FAR
    // Every pixel of an all-far tile reads the last entry twice (tile_lists.comp): the same 8 loads and
    // blends give byEntry[1] bit for bit.
    const int entriesRead = 1;
#else
    const int entriesRead = 2;
#endif
    for (int e = 0; e < entriesRead; ++e) byEntry[e] = integratedEntry(k, k.entries[e]);
#ifdef BRUME_COMPOSITE_ALL_FAR
    byEntry[1] = byEntry[0];
#endif
    Accumulated entries = mixAccumulated(byEntry[0], byEntry[1], k.weights.z);
    return mixAccumulated(emptyAccumulated(), entries, k.entryWeight);
}

#ifdef BRUME_COMPOSITE_FAR
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
#endif

// The pixel this invocation composites: with distant fog (SPEC_DISTANT_FOG), the workgroup's 8x8 tile
// from the list of its variant (tile_lists.comp); else the region's pixels (the push constants).
ivec2 compositePixel() {
    // Through the list's texel view: lavapipe loads a storage buffer lane by lane (shared/frame_table.h).
    int listed = TILE_LIST_HEADER_TEXELS + int(gl_WorkGroupID.x);
#if defined(BRUME_COMPOSITE_ALL_FAR)
    uint tile = uint(texelFetch(allFarTileTexels, listed).x);
#elif defined(BRUME_COMPOSITE_FAR)
    uint tile = uint(texelFetch(farTileTexels, listed).x);
#else
    uint tile = uint(texelFetch(nearTileTexels, listed).x);
#endif
    ivec2 tiles = depthTileCount(frame.counts.xy);
    ivec2 px = ivec2(int(tile) % tiles.x, int(tile) / tiles.x) * DISTANT_TILE_PX + ivec2(gl_LocalInvocationID.xy);
    return SPEC_DISTANT_FOG != 0 ? px : ivec2(gl_GlobalInvocationID.xy) + region.lo.xy;
}

void main() {
    ivec2 px = compositePixel();
    if (any(greaterThanEqual(px, region.hi.xy))) return;
    vec3 background = imageLoad(sceneColor, px).rgb;
    float viewDepth = imageLoad(sceneDepth, px).r;
    vec2 pixel = vec2(px) + vec2(0.5f);
    Accumulated fog = sampleIntegrated(pixel, viewDepth);
#ifdef BRUME_COMPOSITE_FAR
    float froxelFar = frame.froxelRange.y;
    // Only the tiles with a pixel past the froxel far are dispatched here; the others' pixels would not
    // take the branch (composite.comp compiles it out).
    if (viewDepth > froxelFar) fog = composeAccumulated(fog, distantFogAt(pixel, viewDepth));
#endif
    vec3 color = compositeFog(background, fog);
    imageStore(outputImage, px, vec4(color, 1.0f));
}
