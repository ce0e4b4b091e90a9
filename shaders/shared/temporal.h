// Temporal integration, written once for the CPU froxel renderer and the GPU temporal pass.
//
// What is blended: the lit froxels, i.e. the source S (rgb, light pass) and the extinction sigma_t
// (rgb, voxelize pass), between the light and the integrate passes (Hillaire 2015 blends the lit
// scattering/extinction volume before integration). Blending before integration keeps the
// integration exact for whatever (S, sigma_t) field results, and it is what removes the slice bands:
// each frame samples S and sigma_t at a different depth inside each froxel (temporalJitter), so the
// history converges to the froxel's average along depth rather than its value at the centre.
//
// Reprojection rule (per froxel (x, y, s) of the current frame):
//   1. p = world position of the froxel's centre (x + 0.5, y + 0.5, s + 0.5) in the current frame;
//   2. c = froxelCoordFromWorld(p, previous frame): tile coordinates from last frame's view and
//      projection, slice coordinate from last frame's slice mapping;
//   3. rejected (weight 0) when c lies outside last frame's grid (behind the camera, outside the
//      tiles, past the froxel far): newly visible froxels have no history;
//   4. history = trilinear read of last frame's resolved volume at c (centres at integer + 0.5,
//      clamped to the outermost centres);
//   5. history is clamped per channel to [min, max] of the current frame's froxel and its six
//      face neighbours (non-finite neighbours skipped): a light switched off or a volume moved
//      cannot leave more than the neighbourhood allows;
//   6. weight = history_weight * max(0, 1 - |c - centre| / TEMPORAL_MOTION_FROXELS), so fast
//      motion (reprojection far from where the froxel was) trusts the history less;
//   7. resolved = mix(current, clamped history, weight). NaN/Inf never enter: a non-finite current
//      value is replaced by the clamped history (or 0), a non-finite history is rejected.
// While the view rests (same view, projection, grid and scene time as the frame that wrote the
// history; FrameUniforms.temporal.y = 1) the history is the mean of the previous n frames' samples
// and the blend makes it the mean of n + 1: weight n / (n + 1) (temporalRestWeight), no clamp (it
// can only pull the mean toward this frame's sample: the scene key already drops the history on
// any edit). Past TEMPORAL_REST_CAP frames the weight stays history_weight, as in motion.
// The reprojection is then the identity: each froxel reads its own history (resolveTemporalAtRest),
// with weight frame.temporal.x exactly; the same function serves frames without history (weight 0).
// (Steps 1-4 evaluated at rest round-trip the centre through the view and slice mapping, off by up to
// 1e-3 froxel, and blended that much of the neighbours' history in every frame.)
#ifndef BRUME_SHARED_TEMPORAL_H
#define BRUME_SHARED_TEMPORAL_H

#include "froxel.h"

BRUME_NAMESPACE_BEGIN

// Reprojection distance [froxels] at which the history weight reaches 0.
BRUME_CONST float TEMPORAL_MOTION_FROXELS = 4.0f;
// Largest finite float; |x| <= it is false for NaN and +-Inf.
BRUME_CONST float BRUME_FLOAT_MAX = 3.402823466e38f;
// The jitter sequence repeats after this many frames (a power of 2: depth stays stratified).
BRUME_CONST int TEMPORAL_SEQUENCE_LENGTH = 1024;

BRUME_FUNC bool allFinite4(vec4 v) { return all(lessThanEqual(abs(v), vec4(BRUME_FLOAT_MAX))); }

// Van der Corput radical inverse of n in `base`: the digits of n mirrored about the point.
BRUME_FUNC float radicalInverse(int n, int base) {
    float inv = 1.0f / float(base);
    float f = inv;
    float r = 0.0f;
    for (int k = n; k > 0; k /= base) {
        r += f * float(k % base);
        f *= inv;
    }
    return r;
}

// Sample position inside each froxel for a frame, in [0,1)^3. Frame 0 samples the centre, as a
// render without temporal does. Along depth, frames 2k-1 and 2k sample a_k and 1 - a_k, mirrored
// about the centre, so that every odd number of frames averages positions centred on the slice (a
// plain van der Corput sequence from the centre leaves its 2^m-frame means 1/2^(m+1) of a slice in
// front of it: a quarter slice after 2 frames); a_k = fract(ri2(k - 1) + 15/32) / 2 runs through
// the front half from near its middle (the first pair near the quarter points), and 8 pairs put one
// sample in each 1/16 of the slice.
// Across the tile every frame samples the column's centre: the composite reconstructs each pixel
// bilinearly between column centres, which interpolates point samples well, but the tile's average
// read that way is blurred twice (a box and a tent: 1.5x the blur), and on lit scenes that costs more
// than averaging gains (docs/temporal.md, "Why not across the tile": default scene, medium, 16
// frames, 3.43% with the tile covered, 2.82% without, 2.89% for one frame).
BRUME_FUNC vec3 temporalJitter(int frameIndex) {
    int n = frameIndex % TEMPORAL_SEQUENCE_LENGTH;
    if (n == 0) return vec3(0.5f);
    float a = 0.5f * fract(radicalInverse((n - 1) / 2, 2) + 15.0f / 32.0f);
    return vec3(0.5f, 0.5f, (n % 2) == 1 ? a : fract(1.0f - a));
}

// History weight of a frame whose view rests: the history holds the mean of restFrames samples
// (>= 1), and mix(current, history, n / (n + 1)) makes it the mean of n + 1. The progressive mean
// runs until its variance equals the exponential blend's steady state, (1 - w) / (1 + w) of one
// frame's, i.e. (1 + w) / (1 - w) frames (19 at w = 0.9); then the weight stays w, which keeps that
// variance, so the switch makes no visible step.
BRUME_FUNC float temporalRestWeight(int restFrames, float historyWeight) {
    float n = float(max(restFrames, 1));
    float cap = (1.0f + historyWeight) / max(1.0f - historyWeight, 1e-6f);
    return n + 1.0f <= cap + 1.0e-3f ? n / (n + 1.0f) : historyWeight;
}

// Where froxel `froxel` of frame `cur` reads last frame's history, and with what weight (steps 1-4
// and 6 of the rule above). Trilinear between the corners lo and hi with fractions `fractions`.
struct HistoryTaps {
    ivec3 lo;
    ivec3 hi;
    vec3 fractions;  // toward hi
    float weight;    // history weight in the blend; 0 = rejected
};

BRUME_FUNC HistoryTaps historyTaps(ivec3 froxel, FrameUniforms cur, FrameUniforms prev, float historyWeight) {
    vec3 centre = vec3(froxel) + vec3(0.5f);
    vec4 c = froxelCoordFromWorld(worldFromFroxelCoord(centre, cur), prev);
    vec3 maxCentre = vec3(ivec3(prev.froxelDims)) - vec3(0.5f);
    vec3 t = clamp(vec3(c), vec3(0.5f), maxCentre) - vec3(0.5f);
    HistoryTaps r;
    r.lo = ivec3(floor(t));
    r.hi = min(r.lo + ivec3(1), ivec3(prev.froxelDims) - ivec3(1));
    r.fractions = t - floor(t);
    float motion = length(vec3(c) - centre);
    r.weight = c.w * historyWeight * clamp(1.0f - motion / TEMPORAL_MOTION_FROXELS, 0.0f, 1.0f);
    return r;
}

// Trilinear read of the history that skips non-finite taps (renormalising the weights of the
// others), so that one poisoned froxel cannot spread into the froxels that read next to it.
struct HistorySample {
    vec4 sum;
    float weight;  // sum of the finite taps' weights; the value is sum / weight
};

BRUME_FUNC HistorySample emptyHistorySample() {
    HistorySample h;
    h.sum = vec4(0.0f);
    h.weight = 0.0f;
    return h;
}

// Adds the tap at corner (cx, cy, cz) in {0, 1}^3 (0 = lo, 1 = hi) with its trilinear weight.
BRUME_FUNC HistorySample addHistoryTap(HistorySample h, vec4 value, ivec3 corner, vec3 fractions) {
    vec3 w3 = mix(vec3(1.0f) - fractions, fractions, vec3(corner));
    float w = w3.x * w3.y * w3.z;
    if (w > 0.0f && allFinite4(value)) {
        h.sum += value * w;
        h.weight += w;
    }
    return h;
}

// Neighbourhood bounds of the current frame (step 5); start from emptyBounds, grow with each
// finite neighbour.
struct Bounds {
    vec4 lo;
    vec4 hi;
};

BRUME_FUNC Bounds emptyBounds() {
    Bounds b;
    b.lo = vec4(BRUME_HUGE);
    b.hi = vec4(-BRUME_HUGE);
    return b;
}

BRUME_FUNC Bounds growBounds(Bounds b, vec4 v) {
    if (!allFinite4(v)) return b;
    b.lo = min(b.lo, v);
    b.hi = max(b.hi, v);
    return b;
}

// Step 7 for one quantity. `current` is this frame's value, `history` the history read (its finite
// taps), `bounds` the neighbourhood of `current`, `weight` from historyTaps; `clampHistory` false
// while the view rests (the bounds then only guard a non-finite current value). Always finite.
BRUME_FUNC vec4 resolveTemporal(vec4 current, HistorySample history, Bounds bounds, float weight, bool clampHistory) {
    bool haveBounds = all(lessThanEqual(bounds.lo, bounds.hi));
    bool historyOk = weight > 0.0f && haveBounds && history.weight > 0.0f;
    vec4 h = historyOk ? history.sum / history.weight : vec4(0.0f);
    vec4 clamped = historyOk ? (clampHistory ? clamp(h, bounds.lo, bounds.hi) : h) : vec4(0.0f);
    if (!allFinite4(current)) return clamped;
    return historyOk ? mix(current, clamped, weight) : current;
}

// Step 7 while the view rests, or without history (weight 0): `history` is the froxel's own
// history value (no reprojection, no clamp). A non-finite current value is replaced by the history
// (or 0), a non-finite history is rejected. Always finite.
BRUME_FUNC vec4 resolveTemporalAtRest(vec4 current, vec4 history, float weight) {
    bool historyOk = weight > 0.0f && allFinite4(history);
    vec4 held = historyOk ? history : vec4(0.0f);
    if (!allFinite4(current)) return held;
    return historyOk ? mix(current, history, weight) : current;
}

// Whether a frame resolves with resolveTemporalAtRest (frame.temporal: x weight, y view rests).
BRUME_FUNC bool temporalAtRest(vec4 temporal) { return temporal.y != 0.0f || temporal.x <= 0.0f; }

// Whether a frame lights and resolves only the froxels some lookup reads (frame.temporal.z, GPU only:
// GpuOptions::skipHiddenFroxels; shaders/column_entries.glsl).
BRUME_FUNC bool temporalSkipsHidden(vec4 temporal) { return temporal.z != 0.0f; }

BRUME_NAMESPACE_END

#endif
