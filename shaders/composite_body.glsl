// Pass 4: fog over the rasterized scene, read from the integrated volume with the shared lookup
// rule (shd::integratedLookup; core: sampleIntegrated / compositeRow), then, past the froxel far,
// continued to the surface with the distant fog table (shared/distant_table.h, distant_fog.comp).
// The lights' glow is added after it by glow.comp, over the pixels near each glowing light only.
//
// Four builds of this body: composite.comp without the distant fog table's lookup, over the region's
// pixels or (with distant fog) the tiles whose pixels all lie within the froxel far; composite_far.comp
// (BRUME_COMPOSITE_FAR) with it, over the tiles that straddle the far; composite_all_far.comp (both
// defines) with it and one entry of the integrated volume, over the tiles whose pixels all lie past
// the far; composite_sky.comp (BRUME_COMPOSITE_SKY) with the two last entries alone, over the tiles
// whose pixels are all sky (tile_lists.comp). Lavapipe runs an untaken branch under a mask, so a
// single shader paid for the 16 table reads on every pixel (docs/performance.md, "pixel"), the far
// one for 8 integrated loads that an all-far pixel reads twice ("allfar"), and the sky for its depth,
// the depth mappings, the table's entry n - 1 and the step's blend ("sky"); split by tile, each pixel
// computes what a single shader would: a sky pixel (distant_table.h isSkyDepth) the same in the far
// builds as in the composite sky.

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

// The integrated volume's lookup at viewDepth; lastEntry: its entry k.entries.y blended, the last entry
// for any depth past the froxel far (a sky pixel's, skyFogAt).
Accumulated sampleIntegrated(vec2 pixel, float viewDepth, out Accumulated lastEntry) {
    IntegratedLookup k = integratedLookup(pixel, viewDepth, frame);
    Accumulated first = integratedEntry(k, k.entries.x);
#ifdef BRUME_COMPOSITE_ALL_FAR
    // Every pixel of an all-far tile reads the last entry twice (tile_lists.comp): the same 8 loads and
    // blends give the second bit for bit.
    lastEntry = first;
#else
    lastEntry = integratedEntry(k, k.entries.y);
#endif
    return integratedResult(k, first, lastEntry);
}

#if defined(BRUME_COMPOSITE_FAR) || defined(BRUME_COMPOSITE_SKY)
// The distant fog table (shared/distant_table.h) at one corner and entry.
Accumulated distantTableAt(ivec2 corners, int x, int y, int j) {
    Accumulated a;
    if (j <= 0) return emptyAccumulated();
    int index = distantTableIndex(corners, ivec2(x, y), j);
    a.scattering = texelFetch(distantTexels, index).rgb;
    a.transmittance = texelFetch(distantTexels, index + 1).rgb;
    return a;
}

// The table's entry j at the 4 corners c (x0, y0, x1, y1) around a pixel, blended bilinearly (w).
Accumulated distantEntryAt(ivec2 corners, ivec4 c, vec2 w, int j) {
    Accumulated row0 = mixAccumulated(distantTableAt(corners, c.x, c.y, j), distantTableAt(corners, c.z, c.y, j), w.x);
    Accumulated row1 = mixAccumulated(distantTableAt(corners, c.x, c.w, j), distantTableAt(corners, c.z, c.w, j), w.x);
    return mixAccumulated(row0, row1, w.y);
}
#endif

#ifdef BRUME_COMPOSITE_FAR
// Height and depth fog from the froxel far to viewDepth: the 4 corners around the pixel blended
// bilinearly at entries j-1 and j, then between the two in ray distance. lastEntry: the blend at j,
// the table's last entry at the camera far (a sky pixel's, skyFogAt).
Accumulated distantFogAt(vec2 pixel, float viewDepth, out Accumulated lastEntry) {
    ivec2 corners = distantTableCorners(frame.counts.xy);
    DistantTableLookup k = distantTableLookup(pixel, viewDepth, frame, distantTableEntries(frame));
    Accumulated first = distantEntryAt(corners, k.corners, k.weights, k.entry - 1);
    lastEntry = distantEntryAt(corners, k.corners, k.weights, k.entry);
    return distantTableBlend(first, lastEntry, k.blend);
}
#endif

#ifdef BRUME_COMPOSITE_SKY
// A sky pixel's fog (distant_table.h isSkyDepth): the integrated volume's last entry, then the table's.
Accumulated skyFogAt(vec2 pixel) {
    IntegratedLookup k = integratedLookupAtLastEntry(pixel, frame);
    Accumulated froxels = integratedEntry(k, k.entries.y);
    DistantCorners c = distantCornersAround(pixel);
    Accumulated distant = distantEntryAt(distantTableCorners(frame.counts.xy), c.corners, c.weights, distantTableEntries(frame));
    return composeAccumulated(froxels, distant);
}
#endif

// The pixel this invocation composites: with distant fog (SPEC_DISTANT_FOG), the workgroup's 8x8 tile
// from the list of its variant (tile_lists.comp); else the region's pixels (the push constants).
ivec2 compositePixel() {
    // Through the list's texel view: lavapipe loads a storage buffer lane by lane (shared/frame_table.h).
    int listed = TILE_LIST_HEADER_TEXELS + int(gl_WorkGroupID.x);
#if defined(BRUME_COMPOSITE_SKY)
    uint tile = uint(texelFetch(skyTileTexels, listed).x);
#elif defined(BRUME_COMPOSITE_ALL_FAR)
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
    vec2 pixel = vec2(px) + vec2(0.5f);
#ifdef BRUME_COMPOSITE_SKY
    // Every pixel of a sky tile is sky: no depth to read.
    Accumulated fog = skyFogAt(pixel);
#else
    float viewDepth = imageLoad(sceneDepth, px).r;
    Accumulated integratedLast;
    Accumulated fog = sampleIntegrated(pixel, viewDepth, integratedLast);
#ifdef BRUME_COMPOSITE_FAR
    float froxelFar = frame.froxelRange.y;
    // Only the tiles with a pixel past the froxel far are dispatched here; the others' pixels would not
    // take the branch (composite.comp compiles it out).
    Accumulated distantLast;
    Accumulated distant = distantFogAt(pixel, viewDepth, distantLast);
    if (viewDepth > froxelFar) fog = composeAccumulated(fog, distant);
    // A sky pixel of a tile that is not all sky: what the composite sky computes (skyFogAt).
    if (isSkyDepth(viewDepth, frame)) fog = composeAccumulated(integratedLast, distantLast);
#endif
#endif
    vec3 color = compositeFog(background, fog);
    imageStore(outputImage, px, vec4(color, 1.0f));
}
