// Froxel grid mapping, written once for the CPU froxel renderer and the GPU passes.
//
// Depth slices follow a power law in view depth z (distance along the camera's -Z axis):
//     z(t) = near + (far - near) * t^k,      t = slice coordinate / slice count in [0, 1]
//     t(z) = ((z - near) / (far - near))^(1/k)
// k = 1 spaces slices evenly; k > 1 packs them near the camera, where froxels are small on screen.
// Froxel (i, j, s) covers pixels [i*tile, (i+1)*tile) x [j*tile, (j+1)*tile) and depths z(s/N)..z((s+1)/N).
// Integration starts at the camera (z = 0): the first slice also holds the gap [0, near].
#ifndef BRUME_SHARED_FROXEL_H
#define BRUME_SHARED_FROXEL_H

#include "types.h"

BRUME_NAMESPACE_BEGIN

BRUME_FUNC int brumeDivRoundUp(int n, int d) { return (n + d - 1) / d; }

BRUME_FUNC float viewDepthFromSliceT(float t, float zNear, float zFar, float exponent) {
    float tc = clamp(t, 0.0f, 1.0f);
    return zNear + (zFar - zNear) * pow(tc, exponent);
}

BRUME_FUNC float sliceTFromViewDepth(float z, float zNear, float zFar, float exponent) {
    float u = clamp((z - zNear) / (zFar - zNear), 0.0f, 1.0f);
    return pow(u, 1.0f / exponent);
}

// View-space direction through a pixel-space position (pixels, origin top-left, y down), scaled so
// that its z is -1: the point at view depth z is ray * z.
BRUME_FUNC vec3 viewRayFromPixel(vec2 pixel, FrameUniforms f) {
    float ndcX = 2.0f * pixel.x / float(f.counts.x) - 1.0f;
    float ndcY = 1.0f - 2.0f * pixel.y / float(f.counts.y);
    return vec3(ndcX * f.projection.x, ndcY * f.projection.y, -1.0f);
}

// World position of a point given in froxel coordinates (x, y in tiles, z in slices; fractional).
BRUME_FUNC vec3 worldFromFroxelCoord(vec3 coord, FrameUniforms f) {
    vec2 pixel = vec2(coord.x, coord.y) * float(f.froxelDims.w);
    float t = coord.z / float(f.froxelDims.z);
    float z = viewDepthFromSliceT(t, f.froxelRange.x, f.froxelRange.y, f.froxelRange.z);
    vec3 viewPos = viewRayFromPixel(pixel, f) * z;
    return vec3(f.worldFromView * vec4(viewPos, 1.0f));
}

// Continuous froxel coordinate (x, y in tiles, z in slices) of a world position in frame f: the
// inverse of worldFromFroxelCoord. w = 1 inside the grid, 0 outside (behind the camera, outside the
// tiles, past the froxel far). Depths in front of the froxel near belong to slice 0.
BRUME_FUNC vec4 froxelCoordFromWorld(vec3 p, FrameUniforms f) {
    vec3 v = vec3(f.viewFromWorld * vec4(p, 1.0f));
    float z = -v.z;
    if (!(z > 0.0f)) return vec4(0.0f);
    float ndcX = v.x / (z * f.projection.x);
    float ndcY = v.y / (z * f.projection.y);
    vec2 pixel = vec2((ndcX + 1.0f) * 0.5f * float(f.counts.x), (1.0f - ndcY) * 0.5f * float(f.counts.y));
    vec2 tile = pixel / float(f.froxelDims.w);
    float slice = sliceTFromViewDepth(z, f.froxelRange.x, f.froxelRange.y, f.froxelRange.z) * float(f.froxelDims.z);
    bool inside = tile.x >= 0.0f && tile.y >= 0.0f && tile.x <= float(f.froxelDims.x) &&
                  tile.y <= float(f.froxelDims.y) && z <= f.froxelRange.y;
    return vec4(tile, slice, inside ? 1.0f : 0.0f);
}

// Radius of froxel slice s's cells [m]: half the diagonal of its tile-by-tile footprint at the slice's
// middle depth and its thickness. The scale below which a froxel cannot resolve detail.
BRUME_FUNC float froxelRadius(int s, FrameUniforms f) {
    float n = float(f.froxelDims.z);
    float z0 = viewDepthFromSliceT(float(s) / n, f.froxelRange.x, f.froxelRange.y, f.froxelRange.z);
    float z1 = viewDepthFromSliceT(float(s + 1) / n, f.froxelRange.x, f.froxelRange.y, f.froxelRange.z);
    float zc = 0.5f * (z0 + z1);
    float tile = float(f.froxelDims.w);
    float w = 2.0f * f.projection.x * zc * tile / float(f.counts.x);
    float h = 2.0f * f.projection.y * zc * tile / float(f.counts.y);
    return 0.5f * sqrt(w * w + h * h + (z1 - z0) * (z1 - z0));
}

// Length of the camera ray inside slice s of the pixel column through `pixel` [m].
// View depth of slice boundary s (0 = the camera, froxelDims.z = the froxel far): slice s spans
// boundaries s and s + 1.
BRUME_FUNC float sliceBoundaryDepth(int s, FrameUniforms f) {
    return s == 0 ? 0.0f
                  : viewDepthFromSliceT(float(s) / float(f.froxelDims.z), f.froxelRange.x, f.froxelRange.y,
                                        f.froxelRange.z);
}

BRUME_FUNC float sliceRayLength(int s, vec2 pixel, FrameUniforms f) {
    return (sliceBoundaryDepth(s + 1, f) - sliceBoundaryDepth(s, f)) * length(viewRayFromPixel(pixel, f));
}

// The integrated volume stores, at slice s, the result from the camera to the far boundary of s,
// i.e. at t = (s + 1) / N. Given a view depth, returns the continuous slice-entry coordinate w
// (entry index + fraction) to interpolate at; w < 0 means "between the camera and entry 0", to be
// blended with the empty result (scattering 0, transmittance 1) by (w + 1).
BRUME_FUNC float integratedEntryFromViewDepth(float z, FrameUniforms f) {
    float t = sliceTFromViewDepth(z, f.froxelRange.x, f.froxelRange.y, f.froxelRange.z);
    return t * float(f.froxelDims.z) - 1.0f;
}

// The entries integratedLookup (below) can read for view depths in [zLo, zHi]: its e0 at zLo to its
// e1 at zHi, widened by one entry on each side (the depth-to-entry mapping's rounding need not be
// monotonic to the last bit), within the grid. The integrate pass stores only the entries some pixel
// or the glow can read (integrate.comp).
BRUME_FUNC ivec2 integratedEntryRange(float zLo, float zHi, FrameUniforms f) {
    int last = f.froxelDims.z - 1;
    float lastEntry = float(last);
    int e0 = int(floor(max(min(integratedEntryFromViewDepth(zLo, f), lastEntry), 0.0f)));
    int e1 = min(int(floor(max(min(integratedEntryFromViewDepth(zHi, f), lastEntry), 0.0f))) + 1, last);
    return ivec2(max(e0 - 1, 0), min(e1 + 1, last));
}

// Where the composite reads the integrated volume for a pixel (pixel-space position, e.g. the
// pixel centre x + 0.5) at a view depth. The rule, identical on CPU and GPU:
//   1. for each of entries.x and entries.y, bilinear between the four column centres
//      ((i + 0.5) * tile px): mix(mix(c(x0,y0), c(x1,y0), w.x), mix(c(x0,y1), c(x1,y1), w.x), w.y)
//      (columns = (x0, y0, x1, y1); coordinates clamped at the grid border);
//   2. mix(entry0 result, entry1 result, w.z);
//   3. mix(empty (scattering 0, transmittance 1), that, entryWeight): entryWeight < 1 only in front
//      of entry 0's far boundary, where w from integratedEntryFromViewDepth is negative.
// Depths past the froxel far read the last entry (no fog is added beyond the froxel range).
struct IntegratedLookup {
    ivec4 columns;      // x0, y0, x1, y1
    ivec2 entries;      // slice entries e0, e1
    vec3 weights;       // fractions toward x1, y1, e1
    float entryWeight;  // weight of the interpolated entries against the empty result
};

// Step 1's columns alone: for a lookup that knows its entry (integratedLookupAtLastEntry).
BRUME_FUNC IntegratedLookup integratedColumnsLookup(vec2 pixel, FrameUniforms f) {
    IntegratedLookup r;
    vec2 maxColumn = vec2(float(f.froxelDims.x - 1), float(f.froxelDims.y - 1));
    vec2 c = clamp(pixel / float(f.froxelDims.w) - vec2(0.5f), vec2(0.0f), maxColumn);
    ivec2 lo = ivec2(floor(c));
    ivec2 hi = min(lo + ivec2(1), ivec2(maxColumn));
    r.columns = ivec4(lo.x, lo.y, hi.x, hi.y);
    r.entries = ivec2(0);
    r.weights = vec3(c.x - floor(c.x), c.y - floor(c.y), 0.0f);
    r.entryWeight = 1.0f;
    return r;
}

BRUME_FUNC IntegratedLookup integratedLookup(vec2 pixel, float viewDepth, FrameUniforms f) {
    IntegratedLookup r = integratedColumnsLookup(pixel, f);
    float lastEntry = float(f.froxelDims.z - 1);
    float w = min(integratedEntryFromViewDepth(viewDepth, f), lastEntry);
    float wc = max(w, 0.0f);
    int e0 = int(floor(wc));
    r.entries = ivec2(e0, min(e0 + 1, f.froxelDims.z - 1));
    r.weights.z = wc - floor(wc);
    r.entryWeight = clamp(w + 1.0f, 0.0f, 1.0f);
    return r;
}

// Step 1 at the last entry: a sky pixel's (distant_table.h isSkyDepth), without the depth mapping. The
// last entry is integratedLookup's entries.y for any depth past the froxel far.
BRUME_FUNC IntegratedLookup integratedLookupAtLastEntry(vec2 pixel, FrameUniforms f) {
    IntegratedLookup r = integratedColumnsLookup(pixel, f);
    r.entries = ivec2(f.froxelDims.z - 1);
    return r;
}

BRUME_NAMESPACE_END

#endif
