// Volumetric shadows: the fog's transmittance from a point toward a light, written once for the
// CPU froxel renderer and the GPU passes (docs/shadows.md).
//
// Method: analytic optical depth. Every analytic volume's density has a closed-form integral along
// a line, so the optical depth from a froxel (or a surface point) to the light is evaluated exactly,
// per volume, with no light-space grid and hence no grid resolution error:
//   box, hard edge   chord length of the ray through the oriented unit cube;
//   box, edge fade   the chord split where two |q_a| cross (u = 2 max|q| is linear on each piece)
//                    and the smoothstep integrated in closed form;
//   ellipsoid, cylinder, and a box with height_falloff: the chord through the shape in closed
//                    form, cut where the density has a kink (the inner shape where the fade
//                    begins; a cylinder's side/cap seam), and 4-point Gauss-Legendre on each of the
//                    five pieces (a fixed count: no data-dependent loop). Exact for hard edges
//                    without falloff; tests/test_shapes.cpp measures the error (docs/shadows.md);
//   height fog       distant.h's closed forms (exponential and linear profiles), to infinity for a sun;
//   depth fog        not counted: it is aerial perspective measured from the camera (docs/reference.md).
// VDB volumes contribute nothing until they have a sampler (their shadow will need a grid march).
// The cost per froxel is O(volumes) per shadowing light; the error is the froxel's sampling alone.
#ifndef BRUME_SHARED_SHADOWS_H
#define BRUME_SHARED_SHADOWS_H

#include "distant.h"

BRUME_NAMESPACE_BEGIN

// Parameter interval [x, y] of o + s * d inside the cube [-h, h]^3; empty when x > y.
// Branch-free (lavapipe runs both sides of a branch): an axis the ray parallels (|d| < 1e-20, past
// which the slab's own interval would be longer than 1e19 and another axis bounds the chord) admits
// every s when |o| <= h (a ray along a face is inside) and none otherwise; one reciprocal per axis.
BRUME_FUNC vec2 cubeInterval(vec3 o, vec3 d, float h) {
    vec2 r = vec2(-BRUME_HUGE, BRUME_HUGE);
    for (int a = 0; a < 3; ++a) {
        bool parallel = abs(d[a]) < 1.0e-20f;
        float inv = 1.0f / (parallel ? 1.0f : d[a]);
        float ta = (-h - o[a]) * inv;
        float tb = (h - o[a]) * inv;
        bool outside = abs(o[a]) > h;
        r.x = max(r.x, parallel ? (outside ? BRUME_HUGE : -BRUME_HUGE) : min(ta, tb));
        r.y = min(r.y, parallel ? (outside ? -BRUME_HUGE : BRUME_HUGE) : max(ta, tb));
    }
    return r;
}

// The faded box's density 1 - smoothstep(e0, 1, u), e0 = 1 - fade, seen at one end of a piece:
// u = 2 max|q_a| (continuous along the ray: at a cut the two |q_a| are equal), u clamped into the
// fade [e0, 1], the fade's coordinate x = (u - e0) / fade in [0, 1], and u clamped below at 1.
struct FadeEnd {
    float u;
    float fadeU;
    float x;
    float topU;
};

BRUME_FUNC FadeEnd fadeEnd(vec3 lo, vec3 ld, float s, float e0, float invFade) {
    vec3 q = abs(lo + ld * s);
    FadeEnd f;
    f.u = 2.0f * max(q.x, max(q.y, q.z));
    f.fadeU = clamp(f.u, e0, 1.0f);
    f.x = min((f.fadeU - e0) * invFade, 1.0f);
    f.topU = max(f.u, 1.0f);
    return f;
}

// Integral of the faded density over a piece of length len between ends a and b, on which u is
// linear (one axis dominates). The mean of smoothstep(e0, 1, u) over [u_a, u_b] splits where u
// crosses e0 and 1: 0 below, 1 past 1 (the part topU_b - topU_a of u_b - u_a), and across the fade
// (the part fadeU_b - fadeU_a) the mean of 3x^2 - 2x^3 over [x_a, x_b], the divided difference of
// its antiderivative x^3 - x^4 / 2 written without cancellation:
// x_a^2 + x_a x_b + x_b^2 - (x_a + x_b)(x_a^2 + x_b^2) / 2. So a nearly face-parallel piece (u_b
// close to u_a) needs no fallback; at u_b = u_a that mean is the smoothstep at u_a, the limit.
BRUME_FUNC float fadedPieceLength(FadeEnd a, FadeEnd b, float len) {
    float du = b.u - a.u;
    float squares = a.x * a.x + b.x * b.x;
    float fadeMean = squares + a.x * b.x - 0.5f * (a.x + b.x) * squares;
    float inv = 1.0f / (du != 0.0f ? du : 1.0f);
    float mean = du != 0.0f ? ((b.fadeU - a.fadeU) * fadeMean + (b.topU - a.topU)) * inv : fadeMean;
    return len * (1.0f - mean);
}

// Orders a pair of cuts (a compare-exchange of the sorting network below).
BRUME_FUNC vec2 sortedPair(float a, float b) { return vec2(min(a, b), max(a, b)); }

// Integral of a box volume's density along o + s * d (d unit), s in [0, maxDist].
// Branch-free in the data (lavapipe runs 8 lanes in lockstep and pays for every loop trip any lane
// takes): the six cuts where |q_a| = |q_b| for an axis pair are clamped into the chord (a cut that
// misses it becomes a piece of length 0, which adds exactly 0), ordered by a fixed 12-exchange
// sorting network, and the seven pieces between chord ends and cuts are summed in order. The same
// pieces as a sorted list of only the cuts inside the chord, so the same sum. u and its clamps are
// evaluated once at each of the 8 piece ends (fadeEnd), shared by the two pieces that meet there.
BRUME_FUNC float boxDensityLength(VolumeData v, vec3 o, vec3 d, float maxDist) {
    vec3 lo = vec3(v.localFromWorld * vec4(o, 1.0f));
    vec3 ld = vec3(v.localFromWorld * vec4(d, 0.0f));
    vec2 chord = cubeInterval(lo, ld, 0.5f);
    chord = vec2(max(chord.x, 0.0f), min(chord.y, maxDist));
    if (!(chord.y > chord.x)) return 0.0f;
    float fade = v.params.x;
    if (fade <= 0.0f) return chord.y - chord.x;
    // Cut where |q_a| = |q_b| for each axis pair (q_a = -q_b, then q_a = q_b): between cuts one
    // axis dominates.
    float c[6];
    for (int p = 0; p < 3; ++p) {
        int a = p == 2 ? 1 : 0;
        int b = p == 0 ? 1 : 2;
        for (int k = 0; k < 2; ++k) {
            float sgn = k == 0 ? -1.0f : 1.0f;
            float denom = ld[a] - sgn * ld[b];
            float s = denom != 0.0f ? (sgn * lo[b] - lo[a]) / denom : chord.x;
            // NaN-free: a cut outside (chord.x, chord.y) lands on an end.
            c[2 * p + k] = s > chord.x ? min(s, chord.y) : chord.x;
        }
    }
    // Optimal sorting network for 6 keys (12 compare-exchanges, depth 5).
    vec2 t;
    t = sortedPair(c[1], c[2]); c[1] = t.x; c[2] = t.y;
    t = sortedPair(c[4], c[5]); c[4] = t.x; c[5] = t.y;
    t = sortedPair(c[0], c[2]); c[0] = t.x; c[2] = t.y;
    t = sortedPair(c[3], c[5]); c[3] = t.x; c[5] = t.y;
    t = sortedPair(c[0], c[1]); c[0] = t.x; c[1] = t.y;
    t = sortedPair(c[3], c[4]); c[3] = t.x; c[4] = t.y;
    t = sortedPair(c[2], c[5]); c[2] = t.x; c[5] = t.y;
    t = sortedPair(c[0], c[3]); c[0] = t.x; c[3] = t.y;
    t = sortedPair(c[1], c[4]); c[1] = t.x; c[4] = t.y;
    t = sortedPair(c[2], c[4]); c[2] = t.x; c[4] = t.y;
    t = sortedPair(c[1], c[3]); c[1] = t.x; c[3] = t.y;
    t = sortedPair(c[2], c[3]); c[2] = t.x; c[3] = t.y;
    float e0 = 1.0f - fade;
    // A fade below float's resolution at 1 (e0 rounds to 1) leaves fadeU - e0 = 0 at every end: any
    // finite 1 / fade then gives x = 0. The floor keeps a denormal fade (the range allows it) from
    // making 1 / fade infinite and x = 0 x inf = NaN.
    float invFade = 1.0f / max(fade, 1.0e-30f);
    FadeEnd prev = fadeEnd(lo, ld, chord.x, e0, invFade);
    FadeEnd next = fadeEnd(lo, ld, c[0], e0, invFade);
    float total = fadedPieceLength(prev, next, c[0] - chord.x);
    for (int i = 0; i < 5; ++i) {
        prev = next;
        next = fadeEnd(lo, ld, c[i + 1], e0, invFade);
        total += fadedPieceLength(prev, next, c[i + 1] - c[i]);
    }
    FadeEnd last = fadeEnd(lo, ld, chord.y, e0, invFade);
    total += fadedPieceLength(next, last, chord.y - c[5]);
    return total;
}

// Parameter interval of o + s * d inside the ball of radius h; empty when x > y. The roots in the
// form that does not cancel (q = -(b + sign(b) sqrt(disc))).
BRUME_FUNC vec2 ballInterval(vec3 o, vec3 d, float h) {
    float a = dot(d, d);
    float b = dot(o, d);
    float c = dot(o, o) - h * h;
    float disc = b * b - a * c;
    if (!(disc >= 0.0f) || !(a > 0.0f)) return vec2(1.0f, 0.0f);
    float q = -(b + (b >= 0.0f ? sqrt(disc) : -sqrt(disc)));
    if (q == 0.0f) return vec2(0.0f, 0.0f);  // o at the centre of a ball of radius 0
    return sortedPair(q / a, c / q);
}

// Parameter interval inside the cylinder of radius h, |y| <= h (axis local Y).
BRUME_FUNC vec2 cylinderInterval(vec3 o, vec3 d, float h) {
    vec2 all = vec2(-BRUME_HUGE, BRUME_HUGE);
    vec2 none = vec2(1.0f, 0.0f);
    bool alongAxis = d.x * d.x + d.z * d.z <= 0.0f;
    vec2 r = alongAxis ? (o.x * o.x + o.z * o.z <= h * h ? all : none)
                       : ballInterval(vec3(o.x, 0.0f, o.z), vec3(d.x, 0.0f, d.z), h);
    vec2 y = d.y != 0.0f ? sortedPair((-h - o.y) / d.y, (h - o.y) / d.y) : (abs(o.y) <= h ? all : none);
    return vec2(max(r.x, y.x), min(r.y, y.y));
}

// Parameter interval of o + s * d inside a box-kind shape of half-size h (local coordinates).
BRUME_FUNC vec2 shapeInterval(int shape, vec3 o, vec3 d, float h) {
    if (shape == SHAPE_ELLIPSOID) return ballInterval(o, d, h);
    if (shape == SHAPE_CYLINDER) return cylinderInterval(o, d, h);
    return cubeInterval(o, d, h);
}

// One node of shapeFadedPiece's quadrature: x in [-1, 1] on the piece, weight its weight.
// shape: the volume's SHAPE_*; falloff false: its height factor is 1 (height_falloff 0, where the
// exp would give exactly 1), left out.
BRUME_FUNC float shapeFadedNode(int shape, bool falloff, VolumeData v, vec3 lo, vec3 ld, float y0, float dy, float mid,
                                float halfLen, float x, float weight) {
    float s = mid + halfLen * x;
    float u = shapeDistance(shape, (lo + ld * s) * 2.0f);
    float density = u < 1.0f ? edgeFade(u, v.params.x) : 0.0f;
    if (!falloff) return weight * density;
    return weight * density * exp(-v.params.z * max(y0 + dy * s - v.params.w, 0.0f));
}

// Gauss-Legendre, 4 nodes, of the density over a piece [s0, s1] (lo, ld local; y0, dy world
// height of o and its rate along the ray). The nodes written out, not a loop over constant arrays:
// the compiler kept such a loop and its arrays, which lavapipe ran lane by lane (docs/performance.md,
// "pixel, round seven": the glow's quadrature).
BRUME_FUNC float shapeFadedPiece(int shape, bool falloff, VolumeData v, vec3 lo, vec3 ld, float y0, float dy, float s0,
                                 float s1) {
    float halfLen = 0.5f * (s1 - s0);
    float mid = 0.5f * (s0 + s1);
    float sum = 0.0f;
    sum += shapeFadedNode(shape, falloff, v, lo, ld, y0, dy, mid, halfLen, -0.8611363115940526f, 0.3478548451374538f);
    sum += shapeFadedNode(shape, falloff, v, lo, ld, y0, dy, mid, halfLen, -0.3399810435848563f, 0.6521451548625461f);
    sum += shapeFadedNode(shape, falloff, v, lo, ld, y0, dy, mid, halfLen, 0.3399810435848563f, 0.6521451548625461f);
    sum += shapeFadedNode(shape, falloff, v, lo, ld, y0, dy, mid, halfLen, 0.8611363115940526f, 0.3478548451374538f);
    return sum * halfLen;
}

// Whether volume v's fog shadow needs the sampled integral below (an ellipsoid, a cylinder, a box
// with height_falloff) rather than the box's closed form.
BRUME_FUNC bool needsShapeShadows(VolumeData v) {
    return v.kind.x == VOLUME_BOX && (boxShape(v) != SHAPE_BOX || v.params.z > 0.0f);
}

// A cut on the chord: s clamped into [lo, hi]; NaN (no such point) lands on lo, making an empty piece.
BRUME_FUNC float chordCut(float s, vec2 chord) { return s > chord.x ? min(s, chord.y) : chord.x; }

// Integral of an ellipsoid's, a cylinder's or a height-falling box's density along o + s * d (d
// unit), s in [0, maxDist] (the method: the header comment). The chord is cut where the density has
// a kink: the inner shape's boundary (the fade begins) and, for a cylinder, where |q.xz| = |q.y|
// (the side's fade meets the cap's); the five pieces between the sorted cuts are integrated by
// Gauss-Legendre. A box's own kinks (six axis pairs) are not cut: its faded pieces err more.
// shape, falloff: the volume's (boxKindDensityLength's caller reads them from it, or a specialized
// pipeline passes them as constants).
BRUME_FUNC float shapeDensityLengthOf(int shape, bool falloff, VolumeData v, vec3 o, vec3 d, float maxDist) {
    vec3 lo = vec3(v.localFromWorld * vec4(o, 1.0f));
    vec3 ld = vec3(v.localFromWorld * vec4(d, 0.0f));
    vec2 raw = shapeInterval(shape, lo, ld, 0.5f);
    vec2 chord = vec2(max(raw.x, 0.0f), min(raw.y, maxDist));
    if (!(chord.y > chord.x)) return 0.0f;
    vec2 inner = shapeInterval(shape, lo, ld, 0.5f * (1.0f - v.params.x));
    // A chord that misses the inner shape: both cuts at the chord's middle (where an ellipsoid's
    // density peaks).
    float m = 0.5f * (raw.x + raw.y);
    bool hit = inner.y > inner.x;
    float c[4];
    c[0] = chordCut(hit ? inner.x : m, chord);
    c[1] = chordCut(hit ? inner.y : m, chord);
    // Cylinder: |q.xz|^2 = q.y^2 is a quadratic a s^2 + 2 b s + c = 0 along the ray.
    float qa = ld.x * ld.x + ld.z * ld.z - ld.y * ld.y;
    float qb = lo.x * ld.x + lo.z * ld.z - lo.y * ld.y;
    float qc = lo.x * lo.x + lo.z * lo.z - lo.y * lo.y;
    float root = sqrt(max(qb * qb - qa * qc, 0.0f));
    bool kinked = shape == SHAPE_CYLINDER && qb * qb - qa * qc >= 0.0f && qa != 0.0f;
    c[2] = chordCut(kinked ? (-qb - root) / qa : chord.x, chord);
    c[3] = chordCut(kinked ? (-qb + root) / qa : chord.x, chord);
    // Sorting network for 4 keys (5 compare-exchanges).
    vec2 t;
    t = sortedPair(c[0], c[1]); c[0] = t.x; c[1] = t.y;
    t = sortedPair(c[2], c[3]); c[2] = t.x; c[3] = t.y;
    t = sortedPair(c[0], c[2]); c[0] = t.x; c[2] = t.y;
    t = sortedPair(c[1], c[3]); c[1] = t.x; c[3] = t.y;
    t = sortedPair(c[1], c[2]); c[1] = t.x; c[2] = t.y;
    float total = shapeFadedPiece(shape, falloff, v, lo, ld, o.y, d.y, chord.x, c[0]);
    for (int i = 0; i < 3; ++i) total += shapeFadedPiece(shape, falloff, v, lo, ld, o.y, d.y, c[i], c[i + 1]);
    return total + shapeFadedPiece(shape, falloff, v, lo, ld, o.y, d.y, c[3], chord.y);
}

// A box-kind volume's integral, its shape and whether it has a height falloff given (the volume's,
// or a specialized pipeline's constants: shadowDensityLengthListed): the box's closed form, exact
// without a height factor, or else the sampled integral of its own shape (needsShapeShadows is the
// same choice). GLSL has the sampled one only in the _shapes variants (gpu: VariantKey::shapes).
BRUME_FUNC float boxKindDensityLength(int shape, bool falloff, VolumeData v, vec3 p, vec3 dir, float maxDist) {
#if defined(__cplusplus) || defined(BRUME_LOCAL_SHAPES)
    if (shape != SHAPE_BOX || falloff) return shapeDensityLengthOf(shape, falloff, v, p, dir, maxDist);
#endif
    return boxDensityLength(v, p, dir, maxDist);
}

// Integral of one volume's density from p along unit dir over [0, maxDist] (BRUME_HUGE: to
// infinity, a directional light). Depth and VDB volumes: 0 (see the header comment).
// k: v's kind (a constant where the caller knows it: fog_shadow.glsl).
BRUME_FUNC float shadowDensityLengthOfKind(int k, VolumeData v, vec3 p, vec3 dir, float maxDist) {
    // BRUME_VOLUME_KIND_USED: a kind the scene lacks is compiled out of specialized pipelines.
    if (BRUME_VOLUME_KIND_USED(VOLUME_BOX) && k == VOLUME_BOX)
        return boxKindDensityLength(boxShape(v), v.params.z > 0.0f, v, p, dir, maxDist);
    if (BRUME_VOLUME_KIND_USED(VOLUME_HEIGHT_EXPONENTIAL) && k == VOLUME_HEIGHT_EXPONENTIAL)
        return heightExponentialLength(p.y, dir.y, maxDist, v.params.x, v.params.y);
    if (BRUME_VOLUME_KIND_USED(VOLUME_HEIGHT_LINEAR) && k == VOLUME_HEIGHT_LINEAR)
        return heightLinearLength(p.y, dir.y, maxDist, v.params.x, v.params.y);
    return 0.0f;
}

// shadowDensityLengthOfKind for a listed volume whose SPEC_SHAPE_LIST entry is `entry` (shape | 4 with a
// falloff; -1: not specialized). With constants a box-kind volume builds its own shape's integral
// only, and either the box's closed form or the sampled integral: read from the volume at run time,
// lavapipe builds both (it runs both sides of a branch). The same function of the same values.
BRUME_FUNC float shadowDensityLengthListed(int k, int entry, VolumeData v, vec3 p, vec3 dir, float maxDist) {
    if (entry >= 0 && BRUME_VOLUME_KIND_USED(VOLUME_BOX) && k == VOLUME_BOX)
        return boxKindDensityLength(entry & 3, (entry & 4) != 0, v, p, dir, maxDist);
    return shadowDensityLengthOfKind(k, v, p, dir, maxDist);
}

// sigma_t x a density length (0 for a length <= 0).
BRUME_FUNC vec3 opticalDepthOfLength(VolumeData v, float len) {
    if (len <= 0.0f) return vec3(0.0f);
    return (vec3(v.sigmaS_g) + vec3(v.sigmaA)) * len;
}

BRUME_FUNC vec3 shadowOpticalDepthListed(int k, int entry, VolumeData v, vec3 p, vec3 dir, float maxDist) {
    return opticalDepthOfLength(v, shadowDensityLengthListed(k, entry, v, p, dir, maxDist));
}

// Optical depth of one volume toward a light (sigma_t x density length); sum over volumes, then
// exp(-sum) is the transmittance. Finite or +inf, never NaN.
BRUME_FUNC float shadowDensityLength(VolumeData v, vec3 p, vec3 dir, float maxDist) {
    return shadowDensityLengthOfKind(v.kind.x, v, p, dir, maxDist);
}

BRUME_FUNC vec3 shadowOpticalDepthOfKind(int k, VolumeData v, vec3 p, vec3 dir, float maxDist) {
    return opticalDepthOfLength(v, shadowDensityLengthOfKind(k, v, p, dir, maxDist));
}

BRUME_FUNC vec3 shadowOpticalDepth(VolumeData v, vec3 p, vec3 dir, float maxDist) {
    return shadowOpticalDepthOfKind(v.kind.x, v, p, dir, maxDist);
}

// Whether the fog's transmittance toward light l is evaluated: directional lights always (the sun's
// volumetric shadow); point and spot lights when the quality asks for it (frame flag).
BRUME_FUNC bool fogShadowsLight(LightData l, int localLightsToo) {
    return l.kind.x == LIGHT_DIRECTIONAL || localLightsToo != 0;
}

// Past the froxel far (distant.h) the camera ray is cut into pieces, geometric in ray distance,
// each lit by the directional lights times the fog transmittance toward them at the piece's
// (geometric) middle: the closed form needs a source that is constant along a piece. A piece spans
// a distance ratio of at most DISTANT_SHADOW_PIECE_RATIO, and there are at most
// DISTANT_SHADOW_PIECES: a sky pixel just past the froxel far (96 -> 100 m) needs one piece, not 8,
// which was most of the composite's cost (docs/shadows.md, "Cost").
BRUME_CONST int DISTANT_SHADOW_PIECES = 8;
BRUME_CONST float DISTANT_SHADOW_PIECE_RATIO = 1.5f;

// How many pieces [s0, s1] (0 < s0 < s1) is cut into: 1..DISTANT_SHADOW_PIECES.
BRUME_FUNC int distantShadowPieceCount(float s0, float s1) {
    float n = ceil(log(s1 / s0) / log(DISTANT_SHADOW_PIECE_RATIO));
    return int(clamp(n, 1.0f, float(DISTANT_SHADOW_PIECES)));
}

// Ray-distance bounds [x, y] of piece i of n of [s0, s1]; the last piece ends at s1 exactly.
BRUME_FUNC vec2 distantShadowPiece(float s0, float s1, int i, int n) {
    float ratio = s1 / s0;
    float fn = float(n);
    float a = i == 0 ? s0 : s0 * pow(ratio, float(i) / fn);
    float b = i + 1 == n ? s1 : s0 * pow(ratio, float(i + 1) / fn);
    return vec2(a, b);
}

BRUME_NAMESPACE_END

#endif
