// The distant fog (distant.h) as a table: evaluated once per corner of an 8x8 pixel tile at a few view
// depths between the froxel far and the camera far, then interpolated per pixel. The closed form is
// smooth across the screen (a function of the ray's direction and of the view depth only, so depth
// edges of the scene do not matter), and evaluating it per pixel was most of the composite's cost on
// lavapipe (docs/performance.md, "Per-pixel passes"). The GPU's distant_fog.comp fills the table and
// composite.comp reads it; the CPU froxel renderer builds and reads the same table.
//
// Entries: for corner c and j = 1..n, the fog accumulated from the froxel far to view depth d_j along
// the corner's ray, d_j = far_froxel (far_camera / far_froxel)^(j/n) (d_n = the camera far: the sky is
// an entry exactly), n the fewest with a ratio d_j / d_(j-1) <= DISTANT_TABLE_RATIO, at most
// DISTANT_TABLE_DEPTHS. Each step [d_(j-1), d_j] is one piece lit at its geometric middle (the pieces of
// shadows.h, finer). A pixel blends its 4 corners bilinearly, then between entries j-1 and j
// exponentially in ray distance (exact for a homogeneous step: distantTableBlend).
#ifndef BRUME_SHARED_DISTANT_TABLE_H
#define BRUME_SHARED_DISTANT_TABLE_H

#include "froxel.h"
#include "integrate.h"

BRUME_NAMESPACE_BEGIN

BRUME_CONST int DISTANT_TILE_PX = 8;
BRUME_CONST int DISTANT_TABLE_DEPTHS = 16;
BRUME_CONST float DISTANT_TABLE_RATIO = 1.1f;

// Corners per row and column for an image of `size` pixels (pixel centres lie between corners).
BRUME_FUNC ivec2 distantTableCorners(ivec2 size) {
    return ivec2((size.x - 1) / DISTANT_TILE_PX + 2, (size.y - 1) / DISTANT_TILE_PX + 2);
}

// The distant fog pass reads the depth tiles around each corner to leave the entries no pixel reads
// unwritten (distant_fog.comp), only when the table has more than this many entries (at `high` it has
// one).
BRUME_CONST int DISTANT_TABLE_SCAN_FROM = 2;

// The scene depth's 8x8 pixel tiles (tile t holds pixels [8 t, 8 t + 7], cut at the image's edge):
// tiles per row and column, and the index of tile t in the depthTiles buffer. Corner c's pixels (those
// whose lookup takes it, [8 (c - 1), 8 c + 7]) are exactly tiles c - 1 and c in each axis, those that
// exist: the deepest of them is the deepest of at most 4 tile maxima.
BRUME_FUNC ivec2 depthTileCount(ivec2 size) {
    return ivec2((size.x - 1) / DISTANT_TILE_PX + 1, (size.y - 1) / DISTANT_TILE_PX + 1);
}

BRUME_FUNC int depthTileIndex(ivec2 tiles, ivec2 t) { return t.y * tiles.x + t.x; }

// A tile whose shallowest pixel lies past the froxel far by this fraction of it goes to the composite
// all far (tile_lists.comp): every pixel's sliceTFromViewDepth is then clamped to exactly 1, even if
// the division were rounded a few ulps low, so each reads the integrated volume's last entry alone.
BRUME_CONST float DISTANT_ALL_FAR_MARGIN = 1.0e-3f;

// The volume kinds that go on past the froxel far (height and depth fog). The GPU tabulates the distant
// fog (SPEC_DISTANT_FOG) where the scene has one and the froxels end before the camera far.
BRUME_FUNC bool distantFogKind(int kind) {
    return kind == VOLUME_HEIGHT_EXPONENTIAL || kind == VOLUME_HEIGHT_LINEAR || kind == VOLUME_DEPTH;
}

// Entries per corner this frame: 0 when the froxels reach the camera far (no distant fog).
BRUME_FUNC int distantTableEntries(FrameUniforms f) {
    float froxelFar = f.froxelRange.y;
    float cameraFar = f.projection.w;
    if (!(cameraFar > froxelFar)) return 0;
    float n = ceil(log(cameraFar / froxelFar) / log(DISTANT_TABLE_RATIO));
    return int(clamp(n, 1.0f, float(DISTANT_TABLE_DEPTHS)));
}

// View depth of entry j of n (0: the froxel far; n: the camera far exactly).
BRUME_FUNC float distantTableDepth(FrameUniforms f, int j, int n) {
    if (j <= 0) return f.froxelRange.y;
    if (j >= n) return f.projection.w;
    return f.froxelRange.y * pow(f.projection.w / f.froxelRange.y, float(j) / float(n));
}

// Index of corner c's entry j (1..n) in the table: scattering at 2 i, transmittance at 2 i + 1.
BRUME_FUNC int distantTableIndex(ivec2 corners, ivec2 c, int j) {
    return ((c.y * corners.x + c.x) * DISTANT_TABLE_DEPTHS + (j - 1)) * 2;
}

// Where pixel (centre) `pixel` at `viewDepth` (> the froxel far) reads the table.
struct DistantTableLookup {
    ivec4 corners;  // x0, y0, x1, y1
    vec2 weights;   // toward x1, y1
    int entry;      // j: between entries j-1 and j (entry 0 = nothing accumulated)
    float blend;    // position between them in ray distance, 0..1
};

// The 4 corners around pixel (centre) `pixel` and its bilinear weights toward x1, y1.
struct DistantCorners {
    ivec4 corners;  // x0, y0, x1, y1
    vec2 weights;   // toward x1, y1
};

BRUME_FUNC DistantCorners distantCornersAround(vec2 pixel) {
    DistantCorners k;
    vec2 t = pixel / float(DISTANT_TILE_PX);
    vec2 c0 = floor(t);
    k.corners = ivec4(int(c0.x), int(c0.y), int(c0.x) + 1, int(c0.y) + 1);
    k.weights = t - c0;
    return k;
}

BRUME_FUNC DistantTableLookup distantTableLookup(vec2 pixel, float viewDepth, FrameUniforms f, int n) {
    DistantTableLookup k;
    DistantCorners around = distantCornersAround(pixel);
    k.corners = around.corners;
    k.weights = around.weights;
    float froxelFar = f.froxelRange.y;
    float u = float(n) * log(viewDepth / froxelFar) / log(f.projection.w / froxelFar);
    k.entry = int(clamp(ceil(u), 1.0f, float(n)));
    float d0 = distantTableDepth(f, k.entry - 1, n);
    float d1 = distantTableDepth(f, k.entry, n);
    k.blend = clamp((viewDepth - d0) / max(d1 - d0, 1.0e-30f), 0.0f, 1.0f);
    return k;
}

// One channel of distantTableBlend: scattering s0 -> s1 and transmittance t0 -> t1 over a step whose
// own transmittance is t1 / t0; the part of the step up to fraction b of its length, as if the step
// were homogeneous (transmittance ratio^b, scattering (1 - ratio^b) / (1 - ratio) of the step's).
BRUME_FUNC vec2 distantBlendChannel(float s0, float t0, float s1, float t1, float b) {
    float ratio = t0 > 0.0f ? clamp(t1 / t0, 0.0f, 1.0f) : 1.0f;
    float part = pow(ratio, b);
    float w = 1.0f - ratio > 1.0e-4f ? (1.0f - part) / (1.0f - ratio) : b;
    return vec2(s0 + (s1 - s0) * w, t0 * part);
}

// Between entries a0 (j-1) and a1 (j) at fraction b of the step.
BRUME_FUNC Accumulated distantTableBlend(Accumulated a0, Accumulated a1, float b) {
    vec2 r = distantBlendChannel(a0.scattering.x, a0.transmittance.x, a1.scattering.x, a1.transmittance.x, b);
    vec2 g = distantBlendChannel(a0.scattering.y, a0.transmittance.y, a1.scattering.y, a1.transmittance.y, b);
    vec2 bl = distantBlendChannel(a0.scattering.z, a0.transmittance.z, a1.scattering.z, a1.transmittance.z, b);
    Accumulated a;
    a.scattering = vec3(r.x, g.x, bl.x);
    a.transmittance = vec3(r.y, g.y, bl.y);
    return a;
}

// The sky: a pixel at the camera far (sceneDepth's clear value: no surface; the CPU's ray that meets
// nothing). With distant fog its fog is the integrated volume's last entry (integratedLookup's
// entries.y past the froxel far) followed by the table's last entry, both blended bilinearly: the
// whole ray. Written out so, it needs neither its depth, nor the depth mappings (a pow, two logs), nor
// the table's entry n - 1 and the step's blend, whose b is 1 at the camera far: the composite sky
// reads 16 texels where a pixel past the far reads 24 (docs/performance.md, "sky"). The same values as
// the lookups, up to the rounding of mix(empty, a, 1) and of distantTableBlend at b = 1 (a few ulps).
BRUME_FUNC bool isSkyDepth(float viewDepth, FrameUniforms f) { return viewDepth >= f.projection.w; }

// front, then back behind it.
BRUME_FUNC Accumulated composeAccumulated(Accumulated front, Accumulated back) {
    Accumulated a;
    a.scattering = front.scattering + front.transmittance * back.scattering;
    a.transmittance = front.transmittance * back.transmittance;
    return a;
}

BRUME_NAMESPACE_END

#endif
