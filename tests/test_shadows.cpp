// Volumetric shadows of the froxel renderers (shaders/shared/shadows.h, core/shadows.cpp): the
// closed forms against the reference's independent double-precision ones, and rendered scenes
// against the reference: the fog's shadow on the ground, and a dense block that must not leak light.
#include <gtest/gtest.h>

#include "ground_shadow.h"
#include "test_support.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "core/compile.h"
#include "core/geometry.h"
#include "core/reference_detail.h"
#include "core/render.h"
#include "core/shadows.h"

using namespace brume;

namespace {

using test::boxFog;

Light sunFrom(glm::vec3 direction) {
    Light l = makeLight(LightType::Directional);
    l.direction = glm::normalize(direction);
    l.intensity = 2.0f;
    return l;
}

Geometry groundPlane(float albedo) { return test::groundPlane(glm::vec3(albedo)); }

RenderRequest request(int w, int h, Quality q) {
    RenderRequest r;
    r.width = w;
    r.height = h;
    r.quality = q;
    r.threads = 2;
    return r;
}

// Every kind of volume that shadows: faded and hard rotated boxes, both height profiles, and a
// depth fog that must not count.
CompiledScene mixedVolumes() {
    Scene s;
    Volume faded = boxFog({0.3f, 1.2f, -0.4f}, {3.0f, 2.0f, 2.5f}, 0.4f, 0.3f, 0.05f);
    faded.transform.rotation_deg = {10.0f, 35.0f, -5.0f};
    Volume hard = boxFog({-1.0f, 0.5f, 1.0f}, {1.0f, 1.5f, 2.0f}, 0.0f, 0.5f, 0.1f);
    hard.transform.rotation_deg = {0.0f, -20.0f, 0.0f};
    Volume expo;
    expo.type = VolumeType::Height;
    expo.base_height = 0.3f;
    expo.falloff = 0.7f;
    Volume linear = expo;
    linear.profile = HeightProfile::Linear;
    linear.transition_height = 2.0f;
    Volume depth;
    depth.type = VolumeType::Depth;
    depth.visibility_distance = 5.0f;
    s.volumes = {faded, hard, expo, linear, depth};
    s.lights = {sunFrom({0.3f, -1.0f, 0.2f})};
    return compileScene(s);
}

}  // namespace

// The shared float closed forms equal the reference's double ones (written independently) on random
// segments and half-lines through every volume kind: both the sun's case (to infinity) and a point
// light's (a finite segment). Breaking any closed form (a wrong fade integral, a missing volume,
// depth fog counted) moves the transmittance by far more than the bound.
TEST(FogShadowClosedForm, MatchesTheReferenceOnRandomRays) {
    const CompiledScene cs = mixedVolumes();
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    double worst = 0.0;
    for (int i = 0; i < 2000; ++i) {
        const glm::vec3 p(2.5f * u(rng), 1.2f + 1.5f * u(rng), 2.5f * u(rng));
        glm::vec3 dir(u(rng), u(rng), u(rng));
        if (glm::length(dir) < 0.1f) continue;
        dir = glm::normalize(dir);
        // The sun is above the horizon; point lights are anywhere, 0.5..6 m away.
        const bool sun = i % 2 == 0;
        if (sun) dir.y = std::abs(dir.y) + 0.05f, dir = glm::normalize(dir);
        const float dist = sun ? shd::BRUME_HUGE : 3.25f + 2.75f * u(rng);
        shd::LightData l = cs.lights[0];
        l.kind.x = sun ? shd::LIGHT_DIRECTIONAL : shd::LIGHT_POINT;
        const glm::vec3 got = lightFogTransmittance(cs, l, p, dir, dist, 1);
        const glm::vec3 want = reference::fogTransmittance(cs, p, dir, dist);
        for (int c = 0; c < 3; ++c) worst = std::max(worst, static_cast<double>(std::abs(got[c] - want[c])));
    }
    std::printf("worst |T_shared - T_reference| over 2000 rays: %.2e\n", worst);
    EXPECT_LT(worst, 2e-5);
}

// Point and spot lights are fog-shadowed only when the frame asks; the sun always. Every quality asks
// (low once did not, and a point light lit an opaque fog bank as clear air: tests/test_extremes.cpp).
TEST(FogShadowClosedForm, LocalLightsOnlyWhenAsked) {
    const CompiledScene cs = mixedVolumes();
    shd::LightData point = cs.lights[0];
    point.kind.x = shd::LIGHT_POINT;
    const glm::vec3 p(0.3f, 1.2f, -0.4f), up(0.0f, 1.0f, 0.0f);
    EXPECT_EQ(lightFogTransmittance(cs, point, p, up, 2.0f, 0), glm::vec3(1.0f));
    EXPECT_LT(lightFogTransmittance(cs, point, p, up, 2.0f, 1).x, 0.9f);
    EXPECT_LT(lightFogTransmittance(cs, cs.lights[0], p, up, shd::BRUME_HUGE, 0).x, 0.9f);
    for (Quality q : {Quality::Low, Quality::Medium, Quality::High, Quality::Ultra}) EXPECT_TRUE(localLightFogShadows(q));
}

namespace {

// A 6 x 2 x 6 m fog box (sigma_t 0.55/m) floating 2-4 m above a bright ground under a slanted sun;
// the camera stands below the box's bottom, so it sees the box's shadow on the ground (partly
// under the box, partly beside it) with little fog in front.
Scene boxOverGround() {
    Scene s;
    s.camera.position = {6.0f, 1.6f, 10.0f};
    s.camera.target = {2.0f, 0.0f, 0.0f};
    s.camera.far = 60.0f;
    s.ambient = glm::vec3(0.02f);
    s.lights = {sunFrom({0.8f, -1.0f, 0.1f})};
    s.volumes = {boxFog({0.0f, 3.0f, 0.0f}, {6.0f, 2.0f, 6.0f}, 0.1f, 0.5f, 0.05f)};
    s.geometry = {groundPlane(0.6f)};
    return s;
}

}  // namespace

// "The ground's shadowed area within 5% of the reference": the pixels of ground that the fog
// darkens by more than 10% in the reference (its shadow); their mean radiance must match within 5%.
// Without fog shadows on surfaces the shadowed ground comes out as bright as the sunlit ground, which
// the second check shows is far more than 5% off.
TEST(FogShadowOnGround, ShadowedAreaWithinFivePercentOfTheReference) {
    const Scene scene = boxOverGround();
    const RenderRequest req = request(160, 90, Quality::High);
    const Image ref = renderReference(scene, req);
    const Image froxel = renderFroxelCpu(scene, req).image;
    Scene noFog = scene;
    noFog.volumes.clear();
    const Image bare = renderReference(noFog, req);  // the ground without any fog: shadow-free
    double refSum = 0.0, froxelSum = 0.0, bareSum = 0.0;
    int count = 0;
    for (size_t i = 0; i < ref.pixels.size(); ++i) {
        if (!(ref.pixels[i].x < 0.9f * bare.pixels[i].x)) continue;
        refSum += ref.pixels[i].x;
        froxelSum += froxel.pixels[i].x;
        bareSum += bare.pixels[i].x;
        ++count;
    }
    ASSERT_GT(count, 300);  // the shadow covers a good part of the image
    const double err = std::abs(froxelSum - refSum) / refSum;
    std::printf("shadowed ground: %d px, froxel vs reference %.4f, unshadowed ground %.3f brighter; whole image %.4f\n",
                count, err, bareSum / refSum - 1.0, relativeMeanAbsError(froxel, ref));
    EXPECT_LT(err, 0.05);
    EXPECT_GT(bareSum / refSum, 1.2);  // what a renderer without fog shadows would be off by, at least
}

// A dense block (sigma_t = 40/m, 1 m thick: optical depth 40) over height fog and the ground: every
// froxel whose path to the sun crosses the block's core gets no sun (source = sigma_s x ambient
// alone), and neither does the ground beneath it. Without volumetric shadows both get full sun.
TEST(FogShadowDenseBlock, NoLightLeaksThrough) {
    Scene s;
    s.camera.position = {0.0f, 2.0f, 9.0f};
    s.camera.target = {0.0f, 0.5f, 0.0f};
    s.camera.far = 40.0f;
    s.ambient = glm::vec3(0.0f);
    const glm::vec3 sunDir = glm::normalize(glm::vec3(0.0f, -1.0f, 0.0f));
    s.lights = {sunFrom(sunDir)};
    Volume block = boxFog({0.0f, 3.0f, 0.0f}, {3.0f, 1.0f, 3.0f}, 0.0f, 20.0f, 20.0f);
    Volume haze;
    haze.type = VolumeType::Height;
    haze.base_height = 1.0f;
    haze.falloff = 2.0f;
    haze.medium.scattering = glm::vec3(0.2f);
    s.volumes = {block, haze};
    s.geometry = {groundPlane(0.5f)};
    const FroxelResult r = renderFroxelCpu(s, request(96, 54, Quality::High));
    const FroxelVolumes& v = r.volumes;
    int under = 0, lit = 0;
    for (int z = 0; z < v.dims.z; ++z)
        for (int y = 0; y < v.dims.y; ++y)
            for (int x = 0; x < v.dims.x; ++x) {
                const glm::vec3 p = shd::worldFromFroxelCoord(glm::vec3(x, y, z) + glm::vec3(0.5f), v.frame);
                const size_t i = (static_cast<size_t>(z) * static_cast<size_t>(v.dims.y) + static_cast<size_t>(y)) *
                                     static_cast<size_t>(v.dims.x) + static_cast<size_t>(x);
                if (p.y > 2.4f || v.mediaExtinction[i].x <= 0.0f) continue;
                // Beneath the block's core (10 cm inside its sides): the sun crosses 1 m of it.
                if (std::abs(p.x) < 1.4f && std::abs(p.z) < 1.4f) {
                    ++under;
                    EXPECT_LT(v.source[i].x, 1e-12f) << "light leaked into froxel " << x << "," << y << "," << z;
                } else if (std::abs(p.x) > 1.6f || std::abs(p.z) > 1.6f) {
                    ++lit;
                    EXPECT_GT(v.source[i].x, 0.0f);
                }
            }
    EXPECT_GT(under, 50);
    EXPECT_GT(lit, 200);
    // The ground beneath the block is black (no ambient, no haze in the way); beside it, sunlit.
    s.volumes = {block};
    const Image img = renderFroxelCpu(s, request(96, 54, Quality::High)).image;
    test::expectNoSunBeneathTheBlock(img, s, v.frame);
}

// With fog shadows the froxel renderer approaches the reference: on the box-over-ground scene the
// whole image at high is within 3% of it.
TEST(FogShadowOnGround, HighIsWithinThreePercentOfTheReference) {
    const Scene scene = boxOverGround();
    const RenderRequest req = request(160, 90, Quality::High);
    const double err = relativeMeanAbsError(renderFroxelCpu(scene, req).image, renderReference(scene, req));
    std::printf("box over ground, high: relative mean abs error %.4f\n", err);
    EXPECT_LT(err, 0.03);
}

namespace {

// Largest |T_blend - T_exact| over every froxel of a grid and every light, with the volume's raw
// trilinear blend (the exact fallback off): the interpolation error itself.
float worstBlendError(const CompiledScene& cs, shd::FrameUniforms frame, int reduction) {
    frame.shadowReduction = reduction;
    const ShadowVolume sv = computeShadowVolume(cs, frame, reduction, 2);
    const glm::ivec3 dims(frame.froxelDims);
    float worst = 0.0f;
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) {
                const glm::vec3 p = shd::worldFromFroxelCoord(glm::vec3(x, y, z) + glm::vec3(frame.jitter), frame);
                const shd::ShadowLookup k = shd::shadowLookup(glm::ivec3(x, y, z), dims, reduction);
                const glm::ivec3 hi = k.upper;
                for (size_t li = 0; li < cs.lights.size(); ++li) {
                    auto at = [&](int cx, int cy, int cz) {
                        const size_t zz = li * static_cast<size_t>(sv.dims.z) + static_cast<size_t>(cz ? hi.z : k.cell.z);
                        return glm::vec3(sv.transmittance[(zz * static_cast<size_t>(sv.dims.y) +
                                                           static_cast<size_t>(cy ? hi.y : k.cell.y)) *
                                                              static_cast<size_t>(sv.dims.x) +
                                                          static_cast<size_t>(cx ? hi.x : k.cell.x)]);
                    };
                    const glm::vec3 blend = shd::shadowBlend(at(0, 0, 0), at(1, 0, 0), at(0, 1, 0), at(1, 1, 0),
                                                             at(0, 0, 1), at(1, 0, 1), at(0, 1, 1), at(1, 1, 1),
                                                             k.weights).transmittance;
                    const shd::LightSample ls = shd::evalLight(cs.lights[li], p);
                    const glm::vec3 exact = lightFogTransmittance(cs, cs.lights[li], p, ls.toLight, ls.distance, 1);
                    worst = std::max(worst, glm::length(blend - exact) / std::sqrt(3.0f));
                }
            }
    return worst;
}

// boxOverGround with a point light inside the box: its transmittance varies everywhere, and shadow
// volume cells disagree around many froxels.
Scene boxOverGroundLitInside() {
    Scene scene = boxOverGround();
    Light point = makeLight(LightType::Point);
    point.position = {1.0f, 3.2f, 0.5f};
    point.intensity = 6.0f;
    point.range = 8.0f;
    scene.lights.push_back(point);
    return scene;
}

// The scene's frame at 96x54 `high`, with the point lights' fog shadows on.
shd::FrameUniforms highFrame(const Scene& scene, const CompiledScene& cs) {
    shd::FrameUniforms frame = makeFrameUniforms(scene, cs, 96, 54, resolveFroxelSettings(scene, Quality::High));
    frame.localFogShadows = 1;
    return frame;
}

}  // namespace

// The reduced-resolution transmittance volume converges to the exact transmittance as the reduction
// goes to 1: its raw trilinear blend (no exact fallback) is exact at r = 1 and its worst error over
// every froxel shrinks with r; and the rendered image (with the fallback at shadow edges) moves
// less and less from the all-exact one. A volume sampled at the wrong froxel, a wrong weight or a
// swapped corner breaks r = 1 or the ordering.
TEST(FogShadowVolume, ConvergesToTheExactTransmittanceAsTheReductionGoesToOne) {
    const Scene scene = boxOverGroundLitInside();
    const CompiledScene cs = compileScene(scene);
    shd::FrameUniforms frame = highFrame(scene, cs);
    const float e4 = worstBlendError(cs, frame, 4), e2 = worstBlendError(cs, frame, 2),
                e1 = worstBlendError(cs, frame, 1);
    std::printf("worst |T_volume - T_exact| (raw blend): r=4 %.4f, r=2 %.4f, r=1 %.2e\n", e4, e2, e1);
    EXPECT_EQ(e1, 0.0f);
    EXPECT_GT(e4, e2);
    EXPECT_GT(e2, 1e-3f);  // the blend does differ: the test can see an error

    RenderRequest req = request(96, 54, Quality::High);
    req.shadowReduction = 1;
    const Image exact = renderFroxelCpu(scene, req).image;
    double prev = 1.0;
    for (int r : {4, 2}) {
        req.shadowReduction = r;
        const double err = relativeMeanAbsError(renderFroxelCpu(scene, req).image, exact);
        std::printf("image vs all-exact transmittance, r=%d: relative mean abs error %.2e\n", r, err);
        EXPECT_LT(err, prev);
        EXPECT_LT(err, 0.01);
        prev = err;
    }
}

// A froxel on a cell (every r-th froxel along each axis: weights 0, 0, 0) reads that cell's value, the
// exact transmittance at its own sample point, so shadowBlend trusts it even where the 8 cells
// disagree (shadow_volume.h shadowOnCell): the exact fallback would compute the same value bit for
// bit. The froxels next to it (weight 1/r along one axis) are still judged by their 8 cells. The
// box-over-ground scene with a point light inside the box has disagreeing cells around froxels on
// cells (counted, so the test sees the case); trusting them without the value being the exact one,
// or leaving them untrusted, fails it.
TEST(FogShadowVolume, AFroxelOnACellIsTrustedAndExact) {
    const Scene scene = boxOverGroundLitInside();
    const CompiledScene cs = compileScene(scene);
    shd::FrameUniforms frame = highFrame(scene, cs);
    for (int r : {2, 4}) {
        frame.shadowReduction = r;
        const ShadowVolume sv = computeShadowVolume(cs, frame, r, 2);
        const glm::ivec3 dims(frame.froxelDims);
        int onCellDisagreeing = 0, nextToCellUntrusted = 0;
        for (int z = 0; z < dims.z; ++z)
            for (int y = 0; y < dims.y; y += r)
                for (int x = 0; x < dims.x; x += r) {
                    const shd::ShadowLookup k = shd::shadowLookup(glm::ivec3(x, y, z), dims, r);
                    const glm::vec3 p = shd::worldFromFroxelCoord(glm::vec3(x, y, z) + glm::vec3(frame.jitter), frame);
                    for (size_t li = 0; li < cs.lights.size(); ++li) {
                        auto at = [&](int cx, int cy, int cz) {
                            const glm::ivec3 c(cx ? k.upper.x : k.cell.x, cy ? k.upper.y : k.cell.y,
                                               cz ? k.upper.z : k.cell.z);
                            return glm::vec3(sv.transmittance[static_cast<size_t>(
                                shd::shadowVolumeIndex(sv.dims, static_cast<int>(li), c))]);
                        };
                        const shd::ShadowBlend b = shd::shadowBlend(at(0, 0, 0), at(1, 0, 0), at(0, 1, 0), at(1, 1, 0),
                                                                    at(0, 0, 1), at(1, 0, 1), at(0, 1, 1), at(1, 1, 1),
                                                                    k.weights);
                        glm::vec3 lo = at(0, 0, 0), hi = lo;
                        for (int c = 1; c < 8; ++c) {
                            lo = glm::min(lo, at(c & 1, (c >> 1) & 1, c >> 2));
                            hi = glm::max(hi, at(c & 1, (c >> 1) & 1, c >> 2));
                        }
                        const glm::vec3 spread = hi - lo;
                        const bool agree = std::max(spread.x, std::max(spread.y, spread.z)) <= shd::SHADOW_VOLUME_SPREAD;
                        if (z % r != 0) {  // next to a cell along z: the 8 cells decide
                            EXPECT_EQ(b.trusted, agree);
                            nextToCellUntrusted += agree ? 0 : 1;
                            continue;
                        }
                        onCellDisagreeing += agree ? 0 : 1;
                        EXPECT_TRUE(b.trusted);
                        const shd::LightSample ls = shd::evalLight(cs.lights[li], p);
                        const glm::vec3 exact = lightFogTransmittance(cs, cs.lights[li], p, ls.toLight, ls.distance, 1);
                        EXPECT_EQ(b.transmittance.x, exact.x);
                        EXPECT_EQ(b.transmittance.y, exact.y);
                        EXPECT_EQ(b.transmittance.z, exact.z);
                    }
                }
        std::printf("r=%d: %d (froxel on a cell, light) pairs with disagreeing cells, %d untrusted next to a cell\n", r,
                    onCellDisagreeing, nextToCellUntrusted);
        EXPECT_GT(onCellDisagreeing, 0);
        EXPECT_GT(nextToCellUntrusted, 0);
    }
}

namespace {

// Dense midpoint integral, in double, of a box volume's density along o + s d over s in [0, maxDist]:
// the chord through the unit cube found in double (so the integrand is continuous: the faded density
// is 0 at the cube's surface), then 200000 midpoint samples of 1 - smoothstep(1 - fade, 1, u),
// u = 2 max|q_a|, on it. The midpoint rule's error is below 1e-8 here (the density's second
// derivative along the ray is at most 6 / fade^2 x |ld|^2 per m^2).
double denseBoxDensityLength(const shd::VolumeData& v, glm::vec3 o, glm::vec3 d, double maxDist) {
    const glm::dmat4 m(v.localFromWorld);
    const glm::dvec3 lo = glm::dvec3(m * glm::dvec4(glm::dvec3(o), 1.0));
    const glm::dvec3 ld = glm::dvec3(m * glm::dvec4(glm::dvec3(d), 0.0));
    double t0 = 0.0, t1 = maxDist;
    for (int a = 0; a < 3; ++a) {
        if (ld[a] == 0.0) {
            if (std::abs(lo[a]) > 0.5) return 0.0;
            continue;
        }
        const double ta = (-0.5 - lo[a]) / ld[a], tb = (0.5 - lo[a]) / ld[a];
        t0 = std::max(t0, std::min(ta, tb));
        t1 = std::min(t1, std::max(ta, tb));
    }
    if (!(t1 > t0)) return 0.0;
    const double fade = v.params.x, e0 = 1.0 - fade;
    const int n = 200000;
    const double h = (t1 - t0) / n;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        const glm::dvec3 q = glm::abs(lo + ld * (t0 + (i + 0.5) * h));
        const double u = 2.0 * std::max(q.x, std::max(q.y, q.z));
        double density = 1.0;
        if (fade > 0.0) {
            const double x = std::clamp((u - e0) / fade, 0.0, 1.0);
            density = 1.0 - x * x * (3.0 - 2.0 * x);
        }
        sum += density;
    }
    return sum * h;
}

}  // namespace

// The faded box's closed form (shared/shadows.h boxDensityLength) against a dense numerical integral
// on the rays where its pieces degenerate: a ray along a face inside the fade (u constant on its
// middle pieces), on a face, grazing an edge (|q_x| = |q_y| all along: every x-y cut has a zero
// denominator), through the cube's diagonal (all three |q_a| equal), nearly face-parallel pieces
// (u changes by less than 1e-3 over a piece, where the old midpoint fallback erred by up to
// ~1e-4 m at fade 0.05), a maxDist ending inside the box, an origin inside it, and random rays
// through a rotated box; fades 0, 0.05, 0.35 and 1. Tolerance 2e-6 m + 2e-6 x the integral (float
// rounding of a chord of a few metres).
TEST(FogShadowClosedForm, BoxMatchesADenseIntegralOnDegenerateRays) {
    struct Ray {
        glm::vec3 o, d;
        float maxDist;
        const char* what;
    };
    // The axis-aligned box: centre 0, size 2 (local = world / 2, so world rays map onto exact local ones).
    const std::vector<Ray> rays = {
        {{0.9f, 0.2f, -3.0f}, {0, 0, 1}, shd::BRUME_HUGE, "along a face inside the fade"},
        {{0.97f, -0.3f, -3.0f}, {0, 0, 1}, shd::BRUME_HUGE, "along a face near the surface"},
        {{1.0f, 0.2f, -3.0f}, {0, 0, 1}, shd::BRUME_HUGE, "on a face"},
        {{0.98f, 0.98f, -3.0f}, {0, 0, 1}, shd::BRUME_HUGE, "grazing an edge"},
        {{0.6f, 0.6f, -3.0f}, {0, 0, 1}, shd::BRUME_HUGE, "|q_x| = |q_y| all along"},
        {{-3.0f, -3.0f, -3.0f}, glm::normalize(glm::vec3(1, 1, 1)), shd::BRUME_HUGE, "the diagonal"},
        {{0.951f, 0.1f, -3.0f}, glm::normalize(glm::vec3(-4e-4f, 0, 1)), shd::BRUME_HUGE, "nearly face-parallel"},
        {{0.99f, 0.2f, -3.0f}, glm::normalize(glm::vec3(-3e-4f, 1e-4f, 1)), shd::BRUME_HUGE, "nearly parallel, fade edge"},
        {{0.975f, 0.975f, -3.0f}, glm::normalize(glm::vec3(1e-4f, -2e-4f, 1)), shd::BRUME_HUGE, "grazing, tilted"},
        {{-3.0f, 0.3f, 0.2f}, {1, 0, 0}, 2.5f, "maxDist inside the box"},
        {{-3.0f, 0.93f, 0.2f}, glm::normalize(glm::vec3(1, 1e-4f, 0)), 3.3f, "maxDist inside, nearly parallel"},
        {{0.2f, -0.3f, 0.5f}, glm::normalize(glm::vec3(0.3f, 0.8f, -0.5f)), shd::BRUME_HUGE, "origin inside"},
        {{0.2f, -0.3f, 0.5f}, glm::normalize(glm::vec3(0.3f, 0.8f, -0.5f)), 0.4f, "origin and maxDist inside"},
        {{2.0f, 1.5f, 0.0f}, {0, 0, 1}, shd::BRUME_HUGE, "a miss"},
    };
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    double worst = 0.0;
    for (float fade : {0.0f, 0.05f, 0.35f, 1.0f}) {
        const shd::VolumeData aligned = compileVolume(boxFog({0, 0, 0}, {2, 2, 2}, fade, 0.5f, 0.1f));
        for (const Ray& r : rays) {
            // On a face, a hard box's chord counts the face as inside (a set of no thickness).
            if (fade == 0.0f && std::string(r.what) == "on a face") continue;
            const double want = denseBoxDensityLength(aligned, r.o, r.d, r.maxDist);
            const float got = shd::boxDensityLength(aligned, r.o, r.d, r.maxDist);
            const double err = std::abs(got - want);
            worst = std::max(worst, err);
            EXPECT_LE(err, 2e-6 + 2e-6 * want) << r.what << ", fade " << fade << ": " << got << " vs " << want;
        }
        Volume rotated = boxFog({0.3f, 1.2f, -0.4f}, {3.0f, 2.0f, 2.5f}, fade, 0.5f, 0.1f);
        rotated.transform.rotation_deg = {10.0f, 35.0f, -5.0f};
        const shd::VolumeData v = compileVolume(rotated);
        for (int i = 0; i < 200; ++i) {
            const glm::vec3 o(0.3f + 2.5f * u(rng), 1.2f + 2.0f * u(rng), -0.4f + 2.5f * u(rng));
            glm::vec3 d(u(rng), u(rng), u(rng));
            if (glm::length(d) < 0.1f) continue;
            d = glm::normalize(d);
            const float maxDist = i % 3 == 0 ? 1.0f + 2.0f * std::abs(u(rng)) : shd::BRUME_HUGE;
            const double want = denseBoxDensityLength(v, o, d, maxDist);
            const float got = shd::boxDensityLength(v, o, d, maxDist);
            const double err = std::abs(got - want);
            worst = std::max(worst, err);
            EXPECT_LE(err, 2e-6 + 2e-6 * want) << "random ray " << i << ", fade " << fade;
        }
    }
    std::printf("worst |closed form - dense integral| of the box: %.2e m\n", worst);
}

// Fades at the bottom of edge_fade's range [0, 1]: a fade under float's resolution at 1 is a hard
// edge, and a denormal one (1 / fade overflows) must not turn the chord into NaN.
TEST(FogShadowClosedForm, BoxWithAVanishingFadeIsTheHardChord) {
    for (float fade : {1.0e-7f, 1.0e-30f, 1.0e-40f, std::numeric_limits<float>::denorm_min()}) {
        const shd::VolumeData v = compileVolume(boxFog({0, 0, 0}, {2, 2, 2}, fade, 0.5f, 0.1f));
        const shd::VolumeData hard = compileVolume(boxFog({0, 0, 0}, {2, 2, 2}, 0.0f, 0.5f, 0.1f));
        const glm::vec3 o(-3.0f, 0.3f, 0.2f), d = glm::normalize(glm::vec3(1.0f, 0.1f, -0.05f));
        for (float maxDist : {shd::BRUME_HUGE, 2.5f}) {
            const float got = shd::boxDensityLength(v, o, d, maxDist);
            ASSERT_TRUE(std::isfinite(got)) << "fade " << fade;
            EXPECT_NEAR(got, shd::boxDensityLength(hard, o, d, maxDist), 1e-5f) << "fade " << fade;
        }
    }
}

// The exponential height fog's density length (shared/distant.h heightExponentialLength) where the
// ray's pieces degenerate: starting exactly at base, level rays above and below base, rays that
// never reach base, and half-lines to infinity (a sun), against the integral in closed form in
// double: below base the density is 1, above it exp(-f (y - base)). Tolerance 1e-5 relative.
TEST(FogShadowClosedForm, HeightExponentialLengthOnDegenerateRays) {
    const double base = 2.0, f = 0.7;
    // Integral over s in [0, len] of the density along y0 + dy s, split at the crossing.
    auto exact = [&](double y0, double dy, double len) {
        auto above = [&](double ya, double d, double l) {  // from height ya >= base, rising at d >= 0
            if (d == 0.0) return std::exp(-f * (ya - base)) * l;
            return std::exp(-f * (ya - base)) * -std::expm1(-f * d * l) / (f * d);
        };
        if (dy == 0.0) return y0 <= base ? len : above(y0, 0.0, len);
        const double c = std::clamp((base - y0) / dy, 0.0, len);
        if (y0 > base) return dy < 0.0 ? above(y0 + dy * c, -dy, c) + (len - c) : above(y0, dy, len);
        return dy > 0.0 ? c + above(base, dy, len - c) : len;
    };
    struct Case {
        float y0, dy, len;
    };
    const float huge = shd::BRUME_HUGE;
    for (Case k : {Case{2.0f, 0.5f, 10.0f}, Case{2.0f, -0.5f, 10.0f}, Case{2.0f, 0.0f, 10.0f}, Case{3.0f, 0.0f, 10.0f},
                   Case{1.0f, 0.0f, 10.0f}, Case{1.0f, -0.3f, 10.0f}, Case{3.0f, 0.3f, 10.0f}, Case{3.0f, -0.3f, 10.0f},
                   Case{3.0f, -0.3f, 2.0f}, Case{1.0f, 0.3f, 2.0f}, Case{1.0f, 0.3f, 5.0f}, Case{3.0f, -1e-6f, 10.0f},
                   Case{1.0f, 1e-6f, 10.0f}, Case{1.0f, 0.3f, huge}, Case{3.0f, 0.3f, huge}, Case{2.0f, 0.8f, huge},
                   Case{2.5f, 0.0f, huge}}) {
        const double want = exact(k.y0, k.dy, k.len);
        const float got = shd::heightExponentialLength(k.y0, k.dy, k.len, static_cast<float>(base), static_cast<float>(f));
        EXPECT_NEAR(got, want, 1e-5 * want) << "y0 " << k.y0 << " dy " << k.dy << " len " << k.len;
    }
}

// The shadow volume's cell counts and its pass's layer index divide through a float (shadow_volume.h
// smallQuotient, cheaper than an integer division on lavapipe): exact against the integer division
// over its range, at its top end and around every multiple of the divisor.
TEST(ShadowVolume, SmallQuotientIsTheIntegerQuotientUpToItsLimit) {
    const int top = shd::SMALL_QUOTIENT_LIMIT - 1;
    for (int b = 1; b <= 300; ++b) {
        for (int a = 0; a < 5000; ++a) ASSERT_EQ(shd::smallQuotient(a, b), a / b) << a << " / " << b;
        for (int a = top - 5000; a <= top; ++a) ASSERT_EQ(shd::smallQuotient(a, b), a / b) << a << " / " << b;
    }
    for (int b : {301, 1000, 4095, 65536, top})
        for (int k = 0; k * b <= top; k += std::max(1, top / b / 2000))
            for (int a = std::max(0, k * b - 1); a <= std::min(top, k * b + 1); ++a)
                ASSERT_EQ(shd::smallQuotient(a, b), a / b) << a << " / " << b;
    for (int r = 1; r <= 8; ++r)
        for (int d = 1; d <= 1024; ++d) {
            const glm::ivec3 dims(d, d + 1, d + 7);
            EXPECT_EQ(shd::shadowVolumeDims(dims, r), (dims - 1 + (r - 1)) / r + 1) << d << ", r " << r;
        }
}
