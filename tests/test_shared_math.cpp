// Closed forms of the formulas in shaders/shared/ that both the CPU and the GPU evaluate:
// phase normalisation and mean cosine, the stable slab integral at extreme sigma_t and d,
// energy conservation, the light falloffs and the density profiles.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "core/compile.h"
#include "core/quality.h"
#include "shaders/shared/brume.h"
#include "shaders/shared/distant_table.h"

using namespace brume;

namespace {

// Integral of f over [a, b] with panels geometrically graded toward a (a peak at a stays resolved).
double integrateGraded(const std::function<double(double)>& f, double a, double b, int panels = 4000) {
    const double len = b - a, first = 1e-10;
    double sum = f(a) * first;  // the piece [a, a + first], where f is ~constant
    double x0 = first;
    const double ratio = std::pow(len / first, 1.0 / panels);
    for (int i = 0; i < panels; ++i) {
        const double x1 = x0 * ratio, xm = 0.5 * (x0 + x1);
        sum += (x1 - x0) / 6.0 * (f(a + x0) + 4.0 * f(a + xm) + f(a + x1));  // Simpson
        x0 = x1;
    }
    return sum;
}

// Integral over the sphere of h(cos) * p(cos), with dOmega = 2 pi dcos; split at 0 so both
// poles are resolved whatever the sign of g.
double sphereIntegral(float g, const std::function<double(double)>& h) {
    auto p = [&](double c) { return 2.0 * M_PI * h(c) * shd::hgPhase(g, static_cast<float>(c)); };
    const double fwd = integrateGraded([&](double x) { return p(1.0 - x); }, 0.0, 1.0);
    const double back = integrateGraded([&](double x) { return p(-1.0 + x); }, 0.0, 1.0);
    return fwd + back;
}

}  // namespace

TEST(Phase, IntegratesToOneOverTheSphere) {
    for (float g : {-1.0f, -0.99f, -0.7f, -0.3f, 0.0f, 0.3f, 0.7f, 0.9f, 0.99f, 1.0f}) {
        const double integral = sphereIntegral(g, [](double) { return 1.0; });
        EXPECT_NEAR(integral, 1.0, 2e-3) << "g = " << g;
    }
}

TEST(Phase, MeanCosineIsG) {
    for (float g : {-0.95f, -0.5f, 0.0f, 0.25f, 0.6f, 0.95f}) {
        const double mean = sphereIntegral(g, [](double c) { return c; });
        EXPECT_NEAR(mean, g, 2e-3) << "g = " << g;
    }
}

TEST(Phase, FiniteAndPositiveAtExtremes) {
    for (float g : {-1.0f, -0.999f, 0.999f, 1.0f, 5.0f, -5.0f}) {
        for (float c : {-1.0f, -0.5f, 0.0f, 0.5f, 1.0f}) {
            const float p = shd::hgPhase(g, c);
            EXPECT_TRUE(std::isfinite(p)) << g << " " << c;
            EXPECT_GT(p, 0.0f);
        }
    }
    EXPECT_NEAR(shd::hgPhase(0.0f, 0.3f), 1.0 / (4.0 * M_PI), 1e-7);
}

TEST(Slab, ExtremesStayFiniteAndBounded) {
    const glm::vec3 source(2.0f, 1.0f, 0.5f);
    for (double sigma : {0.0, 1e-12, 1e-6, 1.0, 1e6, 1e12}) {
        for (double d : {0.0, 1e-6, 1.0, 1e6}) {
            const glm::vec3 st(static_cast<float>(sigma));
            const float df = static_cast<float>(d);
            const glm::vec3 t = shd::slabTransmittance(st, df);
            const glm::vec3 s = shd::slabScattering(source, st, df);
            for (int c = 0; c < 3; ++c) {
                ASSERT_TRUE(std::isfinite(t[c]) && std::isfinite(s[c])) << sigma << " " << d;
                EXPECT_GE(t[c], 0.0f);
                EXPECT_LE(t[c], 1.0f);
                // Closed form in double: S (1 - e^{-sigma d}) / sigma, and S d at sigma = 0.
                const double x = sigma * d;
                const double exact = sigma > 0.0 ? source[c] * -std::expm1(-x) / sigma : source[c] * d;
                EXPECT_NEAR(s[c], exact, 2e-6 * std::abs(exact) + 1e-30) << "sigma " << sigma << " d " << d;
                EXPECT_NEAR(t[c], std::exp(-x), 1e-6);
            }
        }
    }
}

TEST(Slab, TendsToSourceTimesLengthAsSigmaVanishes) {
    const glm::vec3 source(3.0f);
    for (float d : {1e-6f, 1.0f, 1e6f}) {
        const glm::vec3 s = shd::slabScattering(source, glm::vec3(1e-12f), d);
        EXPECT_NEAR(s.x / (3.0 * d), 1.0, 1e-5) << d;
    }
}

TEST(Slab, PhiIsContinuousAcrossItsSeriesThreshold) {
    // Both branches agree at the switch to float precision; phi is decreasing everywhere.
    const float below = shd::slabPhi(0.01f - 1e-7f), above = shd::slabPhi(0.01f + 1e-7f);
    EXPECT_NEAR(below, above, 2e-6f);
    float prev = shd::slabPhi(0.0f);
    EXPECT_EQ(prev, 1.0f);
    for (float x = 1e-4f; x < 100.0f; x *= 1.3f) {
        const float phi = shd::slabPhi(x);
        EXPECT_LE(phi, prev + 1e-6f) << x;
        EXPECT_NEAR(phi, -std::expm1(-static_cast<double>(x)) / x, 2e-6) << x;
        prev = phi;
    }
}

TEST(Slab, AccumulationOfSlicesEqualsOneSlab) {
    // Homogeneous medium cut into n slabs integrates to the single-slab closed form.
    const glm::vec3 sigmaT(0.3f, 0.7f, 1.1f), source(0.5f, 0.2f, 0.9f);
    shd::Accumulated acc = shd::emptyAccumulated();
    for (int i = 0; i < 64; ++i) acc = shd::accumulateSlab(acc, source, sigmaT, 10.0f / 64.0f);
    const glm::vec3 t = shd::slabTransmittance(sigmaT, 10.0f), s = shd::slabScattering(source, sigmaT, 10.0f);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(acc.transmittance[c], t[c], 1e-5f * t[c] + 1e-7f);
        EXPECT_NEAR(acc.scattering[c], s[c], 1e-5f * s[c]);
    }
}

TEST(Energy, AlbedoAtMostOneNeverCreatesLight) {
    // A medium lit only by ambient radiance A, seen against a sky of radiance A: single scattering
    // gives A T + albedo A (1 - T), which equals A at albedo 1 and is below A otherwise.
    const float A = 2.5f;
    for (float sigmaS : {0.0f, 1e-6f, 0.1f, 1.0f, 50.0f, 1e9f}) {
        for (float albedo : {0.0f, 0.3f, 0.9f, 1.0f}) {
            const float sigmaT = albedo > 0.0f ? sigmaS / albedo : sigmaS + 1.0f;
            for (float d : {1e-3f, 1.0f, 100.0f, 1e6f}) {
                shd::Accumulated acc = shd::emptyAccumulated();
                acc = shd::accumulateSlab(acc, glm::vec3(sigmaS * A), glm::vec3(sigmaT), d);
                const float out = shd::compositeFog(glm::vec3(A), acc).x;
                EXPECT_LE(out, A * (1.0f + 1e-5f)) << sigmaS << " " << albedo << " " << d;
                if (albedo == 1.0f) {
                    EXPECT_NEAR(out, A, A * 1e-5f);
                }
            }
        }
    }
}

TEST(Lights, InverseSquareRangeWindowAndCone) {
    Light point = makeLight(LightType::Point);
    point.position = glm::vec3(0.0f);
    point.intensity = 8.0f;
    point.color = glm::vec3(1.0f);
    const shd::LightData pd = compileLight(point);
    EXPECT_NEAR(shd::evalLight(pd, glm::vec3(2, 0, 0)).irradiance.x, 8.0f / 4.0f, 1e-6f);
    EXPECT_NEAR(shd::evalLight(pd, glm::vec3(0, 0, 4)).irradiance.x, 8.0f / 16.0f, 1e-6f);
    const shd::LightSample at = shd::evalLight(pd, glm::vec3(0.0f));
    EXPECT_TRUE(std::isfinite(at.irradiance.x));
    EXPECT_NEAR(at.irradiance.x, 8.0f / (shd::LIGHT_MIN_DISTANCE * shd::LIGHT_MIN_DISTANCE), 1.0f);

    EXPECT_EQ(shd::rangeWindow(0.0f, 5.0f), 1.0f);
    EXPECT_EQ(shd::rangeWindow(5.0f, 5.0f), 0.0f);
    EXPECT_EQ(shd::rangeWindow(7.0f, 5.0f), 0.0f);
    EXPECT_EQ(shd::rangeWindow(1e6f, 0.0f), 1.0f);
    float prev = 1.0f;
    for (float r = 0.0f; r <= 5.0f; r += 0.25f) {
        EXPECT_LE(shd::rangeWindow(r, 5.0f), prev);
        prev = shd::rangeWindow(r, 5.0f);
    }

    Light spot = makeLight(LightType::Spot);
    spot.position = glm::vec3(0, 10, 0);
    spot.direction = glm::vec3(0, -1, 0);
    spot.inner_deg = 20.0f;
    spot.outer_deg = 30.0f;
    spot.intensity = 100.0f;
    const shd::LightData sd = compileLight(spot);
    auto at_angle = [&](float deg) {
        const float r = std::tan(glm::radians(deg)) * 10.0f;
        return shd::evalLight(sd, glm::vec3(r, 0, 0)).irradiance.x * (100.0f + r * r) / 100.0f;  // undo 1/d^2
    };
    EXPECT_NEAR(at_angle(0.0f), 1.0f, 1e-5f);
    EXPECT_NEAR(at_angle(19.0f), 1.0f, 1e-5f);
    EXPECT_NEAR(at_angle(31.0f), 0.0f, 1e-6f);
    EXPECT_GT(at_angle(25.0f), 0.05f);
    EXPECT_LT(at_angle(25.0f), 0.95f);

    Light sun = makeLight(LightType::Directional);
    sun.direction = glm::vec3(0, -2, 0);  // normalized by compileLight
    sun.intensity = 3.0f;
    const shd::LightSample s = shd::evalLight(compileLight(sun), glm::vec3(1e5f, 0, 0));
    EXPECT_NEAR(s.toLight.y, 1.0f, 1e-6f);
    EXPECT_NEAR(s.irradiance.x, 3.0f, 1e-6f);
    // A Lambert surface facing the sun reflects albedo/pi of the irradiance.
    EXPECT_NEAR(shd::lambert(glm::vec3(0.5f), glm::vec3(0, 1, 0), s).x, 0.5f / M_PI * 3.0f, 1e-6f);
}

TEST(Density, ProfilesOfEveryVolumeType) {
    Volume box;
    box.type = VolumeType::Box;
    box.edge_fade = 0.2f;
    box.transform.scale = glm::vec3(4.0f, 2.0f, 2.0f);
    box.transform.translation = glm::vec3(10.0f, 0.0f, 0.0f);
    const shd::VolumeData b = compileVolume(box);
    EXPECT_NEAR(shd::boxDensity(b, glm::vec3(10, 0, 0)), 1.0f, 1e-6f);
    EXPECT_NEAR(shd::boxDensity(b, glm::vec3(11.5f, 0, 0)), 1.0f, 1e-6f);  // d = 0.75 < 0.8
    EXPECT_EQ(shd::boxDensity(b, glm::vec3(12.01f, 0, 0)), 0.0f);
    const float mid = shd::boxDensity(b, glm::vec3(11.8f, 0, 0));  // d = 0.9: smoothstep(0.8, 1, 0.9) = 0.5
    EXPECT_NEAR(mid, 0.5f, 1e-4f);
    box.edge_fade = 0.0f;
    EXPECT_EQ(shd::boxDensity(compileVolume(box), glm::vec3(11.99f, 0, 0)), 1.0f);

    Volume h;
    h.type = VolumeType::Height;
    h.base_height = 1.0f;
    h.falloff = 0.5f;
    const shd::VolumeData he = compileVolume(h);
    EXPECT_EQ(shd::analyticDensity(he, glm::vec3(0, -50, 0), glm::vec3(0)), 1.0f);
    EXPECT_NEAR(shd::analyticDensity(he, glm::vec3(0, 3, 0), glm::vec3(0)), std::exp(-1.0f), 1e-6f);
    h.profile = HeightProfile::Linear;
    h.transition_height = 4.0f;
    const shd::VolumeData hl = compileVolume(h);
    EXPECT_NEAR(shd::analyticDensity(hl, glm::vec3(0, 2, 0), glm::vec3(0)), 0.75f, 1e-6f);
    EXPECT_EQ(shd::analyticDensity(hl, glm::vec3(0, 6, 0), glm::vec3(0)), 0.0f);

    Volume dv;
    dv.type = VolumeType::Depth;
    dv.start_distance = 5.0f;
    dv.visibility_distance = 30.0f;
    const shd::VolumeData dd = compileVolume(dv);
    const glm::vec3 cam(1, 2, 3);
    EXPECT_EQ(shd::analyticDensity(dd, cam + glm::vec3(4.9f, 0, 0), cam), 0.0f);
    EXPECT_NEAR(shd::analyticDensity(dd, cam + glm::vec3(0, 0, 35.0f), cam), 1.0f - std::exp(-3.0f), 1e-5f);
}

TEST(Media, OverlapsAddAndPhaseIsScatteringWeighted) {
    Volume a, b;
    a.type = b.type = VolumeType::Height;
    a.falloff = b.falloff = 0.0f;  // density 1 everywhere
    a.medium.scattering = glm::vec3(1.0f);
    a.medium.absorption = glm::vec3(0.5f);
    a.medium.emission = glm::vec3(0.25f);
    a.medium.phase_g = 0.8f;
    b.medium.scattering = glm::vec3(3.0f);
    b.medium.absorption = glm::vec3(0.0f);
    b.medium.emission = glm::vec3(0.0f);
    b.medium.phase_g = -0.4f;
    Scene scene;
    scene.volumes = {a, b};
    const shd::MediaSample m = mediaAt(compileScene(scene), glm::vec3(0.0f));
    EXPECT_NEAR(m.sigmaS.x, 4.0f, 1e-6f);
    EXPECT_NEAR(m.sigmaT.x, 4.5f, 1e-6f);
    EXPECT_NEAR(m.emission.x, 0.25f, 1e-6f);
    EXPECT_NEAR(shd::mediaPhaseG(m), (1.0f * 0.8f + 3.0f * -0.4f) / 4.0f, 1e-6f);
    EXPECT_EQ(shd::mediaPhaseG(shd::emptyMedia()), 0.0f);
}

namespace {

// Brute-force midpoint integral of a volume's density along a camera ray.
double numericDensityLength(const shd::VolumeData& v, glm::vec3 origin, glm::vec3 dir, double s0, double s1) {
    const int n = 200000;
    const double h = (s1 - s0) / n;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        const double s = s0 + (i + 0.5) * h;
        const glm::vec3 p = origin + dir * static_cast<float>(s);
        sum += shd::analyticDensity(v, p, origin) * h;
    }
    return sum;
}

}  // namespace

TEST(Distant, DensityLengthsMatchNumericIntegrals) {
    Volume he;
    he.type = VolumeType::Height;
    he.base_height = 2.0f;
    he.falloff = 0.3f;
    Volume hl = he;
    hl.profile = HeightProfile::Linear;
    hl.transition_height = 5.0f;
    Volume dv;
    dv.type = VolumeType::Depth;
    dv.start_distance = 10.0f;
    dv.visibility_distance = 40.0f;
    const glm::vec3 origin(3.0f, 1.0f, -2.0f);
    for (const Volume& vol : {he, hl, dv}) {
        const shd::VolumeData v = compileVolume(vol);
        for (glm::vec3 dir : {glm::vec3(1, 0, 0), glm::vec3(1, 0.3f, 0), glm::vec3(1, -0.2f, 0.5f),
                              glm::vec3(0, 1, 0), glm::vec3(0.2f, -1, 0), glm::vec3(1, 1e-7f, 0)}) {
            dir = glm::normalize(dir);
            for (auto [s0, s1] : {std::pair{0.0f, 5.0f}, std::pair{4.0f, 60.0f}, std::pair{30.0f, 200.0f}}) {
                const double exact = numericDensityLength(v, origin, dir, s0, s1);
                const float closed = shd::distantDensityLength(v, origin, dir, s0, s1);
                EXPECT_NEAR(closed, exact, 1e-4 * (s1 - s0) + 1e-4 * exact)
                    << toString(vol.type) << " dir " << dir.x << "," << dir.y << "," << dir.z << " [" << s0 << ","
                    << s1 << "]";
            }
        }
    }
}

TEST(Distant, OneMediumSegmentEqualsFineSlabMarch) {
    // Exponential height fog lit by a sun and ambient: the closed-form segment agrees with marching
    // 100k thin slabs with the medium at each slab's midpoint.
    Scene scene;
    Volume h;
    h.type = VolumeType::Height;
    h.falloff = 0.2f;
    h.medium.scattering = glm::vec3(0.05f, 0.08f, 0.1f);
    h.medium.absorption = glm::vec3(0.01f);
    h.medium.emission = glm::vec3(0.002f);
    h.medium.phase_g = 0.6f;
    scene.volumes = {h};
    Light sun = makeLight(LightType::Directional);
    sun.direction = glm::vec3(0.3f, -0.5f, 0.8f);
    sun.intensity = 4.0f;
    scene.lights = {sun};
    scene.ambient = glm::vec3(0.2f, 0.3f, 0.4f);
    const CompiledScene cs = compileScene(scene);
    const glm::vec3 origin(0, 1.5f, 0), dir = glm::normalize(glm::vec3(0.9f, 0.05f, 0.3f));
    const float s0 = 60.0f, s1 = 400.0f;

    const shd::VolumeData& v = cs.volumes[0];
    const glm::vec3 light = shd::distantLightPerSigmaS(cs.lights[0], dir, v.sigmaS_g.w) + cs.ambient;
    shd::DistantSegment seg = shd::emptyDistantSegment();
    seg = shd::addDistantVolume(seg, v, shd::distantDensityLength(v, origin, dir, s0, s1), light);
    const shd::Accumulated closed = shd::accumulateDistant(shd::emptyAccumulated(), seg);

    shd::Accumulated march = shd::emptyAccumulated();
    const int n = 100000;
    const float ds = (s1 - s0) / n;
    for (int i = 0; i < n; ++i) {
        const glm::vec3 p = origin + dir * (s0 + (static_cast<float>(i) + 0.5f) * ds);
        const shd::MediaSample m = mediaAt(cs, p);
        const shd::LightSample ls = shd::evalLight(cs.lights[0], p);
        const glm::vec3 src =
            m.sigmaS * (shd::inScatterPerSigmaS(cs.lights[0], ls, dir, shd::mediaPhaseG(m)) + cs.ambient) + m.emission;
        march = shd::accumulateSlab(march, src, m.sigmaT, ds);
    }
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(closed.transmittance[c], march.transmittance[c], 1e-3 * march.transmittance[c] + 1e-6);
        EXPECT_NEAR(closed.scattering[c], march.scattering[c], 1e-3 * march.scattering[c]);
    }
}

// The distant fog table's step blend (shared/distant_table.h): between two accumulation states of one
// homogeneous medium it gives exactly the state at the intermediate distance.
TEST(DistantTable, BlendWithinAHomogeneousStepIsExact) {
    const glm::vec3 source(0.02f, 0.05f, 0.1f), sigmaT(0.01f, 0.08f, 0.5f);
    const shd::Accumulated front = shd::accumulateSlab(shd::emptyAccumulated(), glm::vec3(0.3f), glm::vec3(0.2f), 1.0f);
    const float d = 12.0f;
    const shd::Accumulated a1 = shd::accumulateSlab(front, source, sigmaT, d);
    for (float b : {0.0f, 0.1f, 0.5f, 0.9f, 1.0f}) {
        const shd::Accumulated exact = shd::accumulateSlab(front, source, sigmaT, b * d);
        const shd::Accumulated blended = shd::distantTableBlend(front, a1, b);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(blended.transmittance[c], exact.transmittance[c], 1e-5f) << b;
            EXPECT_NEAR(blended.scattering[c], exact.scattering[c], 1e-5f * (1.0f + exact.scattering[c])) << b;
        }
    }
    // No medium: nothing changes, nothing divides by zero.
    const shd::Accumulated same = shd::distantTableBlend(front, front, 0.5f);
    EXPECT_EQ(same.transmittance, front.transmittance);
    EXPECT_EQ(same.scattering, front.scattering);
}

// Entries from the froxel far to the camera far: the sky (camera far) reads the last entry exactly,
// every pixel's corners exist, and the steps never exceed the table's ratio unless capped.
TEST(DistantTable, EntriesCoverTheFroxelFarToTheCameraFar) {
    shd::FrameUniforms f{};
    f.counts = glm::ivec4(1281, 719, 0, 0);
    f.projection = glm::vec4(1.0f, 1.0f, 0.1f, 100.0f);
    f.froxelRange = glm::vec4(0.1f, 48.0f, 2.0f, 0.0f);
    const int n = shd::distantTableEntries(f);
    ASSERT_GE(n, 1);
    ASSERT_LE(n, shd::DISTANT_TABLE_DEPTHS);
    for (int j = 1; j <= n; ++j) {
        EXPECT_GT(shd::distantTableDepth(f, j, n), shd::distantTableDepth(f, j - 1, n));
        EXPECT_LE(shd::distantTableDepth(f, j, n) / shd::distantTableDepth(f, j - 1, n), shd::DISTANT_TABLE_RATIO * 1.0001f);
    }
    EXPECT_EQ(shd::distantTableDepth(f, n, n), 100.0f);
    const shd::DistantTableLookup sky = shd::distantTableLookup(glm::vec2(640.5f, 300.5f), 100.0f, f, n);
    EXPECT_EQ(sky.entry, n);
    EXPECT_FLOAT_EQ(sky.blend, 1.0f);
    const shd::DistantTableLookup near = shd::distantTableLookup(glm::vec2(0.5f, 0.5f), 48.001f, f, n);
    EXPECT_EQ(near.entry, 1);
    EXPECT_LT(near.blend, 1e-3f);
    const glm::ivec2 corners = shd::distantTableCorners(glm::ivec2(f.counts));
    const shd::DistantTableLookup last = shd::distantTableLookup(glm::vec2(1280.5f, 718.5f), 60.0f, f, n);
    EXPECT_LT(last.corners.z, corners.x);
    EXPECT_LT(last.corners.w, corners.y);
    f.froxelRange.y = 100.0f;  // the froxels reach the camera far: no table
    EXPECT_EQ(shd::distantTableEntries(f), 0);
}

TEST(Distant, ExtremesStayFinite) {
    Volume h;
    h.type = VolumeType::Height;
    h.falloff = 1000.0f;
    h.base_height = -1e5f;
    Volume d;
    d.type = VolumeType::Depth;
    d.visibility_distance = 1e-3f;
    d.start_distance = 0.0f;
    for (const Volume& vol : {h, d}) {
        const shd::VolumeData v = compileVolume(vol);
        for (float s1 : {1e-6f, 1.0f, 1e6f}) {
            const float len = shd::distantDensityLength(v, glm::vec3(1e5f, 0, 0), glm::vec3(0, 0, 1), 0.0f, s1);
            EXPECT_TRUE(std::isfinite(len));
            EXPECT_GE(len, 0.0f);
            EXPECT_LE(len, s1 * 1.0001f);
        }
    }
}

TEST(Lights, FroxelScaleClampBoundsTheInverseSquare) {
    Light point = makeLight(LightType::Point);
    point.position = glm::vec3(0.0f);
    point.intensity = 2.0f;
    const shd::LightData l = compileLight(point);
    // Closer than the clamp: the clamp's inverse square; farther: unchanged.
    EXPECT_NEAR(shd::evalLightNear(l, glm::vec3(0.01f, 0, 0), 0.5f).irradiance.x, 2.0f / 0.25f, 1e-5f);
    EXPECT_NEAR(shd::evalLightNear(l, glm::vec3(3.0f, 0, 0), 0.5f).irradiance.x, 2.0f / 9.0f, 1e-6f);
    EXPECT_EQ(shd::evalLightNear(l, glm::vec3(0.3f, 0, 0), 0.0f).irradiance.x,
              shd::evalLight(l, glm::vec3(0.3f, 0, 0)).irradiance.x);

    // Froxel radii grow with depth and are of the size of a tile footprint and a slice.
    Scene scene;
    const FroxelSettings fs = resolveFroxelSettings(scene, Quality::Medium);
    const shd::FrameUniforms f = makeFrameUniforms(scene, compileScene(scene), 640, 360, fs);
    float prev = 0.0f;
    for (int s = 0; s < fs.slices; ++s) {
        const float r = shd::froxelRadius(s, f);
        EXPECT_GT(r, prev) << s;
        prev = r;
    }
    const float zFar = fs.far, zPrev = shd::viewDepthFromSliceT(float(fs.slices - 1) / float(fs.slices), fs.near, fs.far, fs.distribution);
    const float width = 2.0f * f.projection.x * 0.5f * (zFar + zPrev) * float(fs.tile_px) / 640.0f;
    EXPECT_GT(prev, 0.5f * std::max(width, zFar - zPrev));
    EXPECT_LT(prev, 0.5f * std::sqrt(2.0f * width * width + (zFar - zPrev) * (zFar - zPrev)) * 1.001f);
}

// The glow split (shared/glow.h): along any camera ray, the froxel part (1 - h) / r^2 integrated
// finely plus the pixel part's 6-point quadrature equal the whole inverse square's integral, from a
// ray grazing the light (b = 3% of R, 1.7 cm) to one at the ball's edge; in an absorbing medium the
// pixel part matches its own integral; an opaque medium gives a finite 0, and the froxel part stays
// finite. The rule's error is largest on grazing rays, where the window h falls to 0 in a thin layer
// at both ends of the phi interval: 1.7% of the pixel part at b = 0.03 R with g = 0.3 (1.1-1.3% for
// the isotropic part at b = 0.02-0.05 R against its closed form), 0.4% at 0.1 R, under 0.3% beyond.
TEST(Lights, GlowSplitKeepsTheWholeInverseSquare) {
    Scene scene;  // the default camera: at (0, 2, 8) looking at (0, 1, 0)
    const FroxelSettings fs = resolveFroxelSettings(scene, Quality::High);
    const shd::FrameUniforms f = makeFrameUniforms(scene, compileScene(scene), 320, 180, fs);
    Light point = makeLight(LightType::Point);
    point.position = glm::vec3(0.4f, 1.2f, 1.0f);
    point.intensity = 3.0f;
    const shd::LightData l = compileLight(point);
    const float radius = shd::lightGlowRadius(l, f);
    const glm::vec4 coord = shd::froxelCoordFromWorld(point.position, f);
    ASSERT_EQ(coord.w, 1.0f);
    EXPECT_NEAR(radius, shd::LIGHT_GLOW_FROXELS * shd::froxelRadius(int(coord.z), f), 0.1f * radius);
    // Bounded at the light: (2 - u^2) / R^2 <= 2 / R^2.
    EXPECT_LE(shd::evalLightFroxel(l, point.position, 0.0f, f).irradiance.x, 2.0f * 3.0f / (radius * radius) * 1.0001f);
    // Beyond the ball the froxel part is the inverse square.
    const glm::vec3 far = point.position + glm::vec3(0.0f, 0.0f, 1.5f * radius);
    EXPECT_FLOAT_EQ(shd::evalLightFroxel(l, far, 0.0f, f).irradiance.x, shd::evalLight(l, far).irradiance.x);

    const glm::vec3 origin = glm::vec3(f.cameraPosition);
    const float g = 0.3f;
    const glm::vec3 toLight = point.position - origin;
    const glm::vec3 side = glm::normalize(glm::cross(toLight, glm::vec3(0, 1, 0)));
    for (float bFrac : {0.03f, 0.1f, 0.4f, 0.9f}) {
        // A ray passing at b from the light, ending 20 m out.
        const glm::vec3 dir = glm::normalize(toLight + side * (bFrac * radius));
        const double tc = glm::dot(toLight, dir);
        const double b = glm::length(toLight - dir * float(tc));
        const shd::LightGlowRay r = shd::lightGlowRay(l, f, origin, dir, 20.0f);
        ASSERT_GT(r.radius, 0.0f) << bFrac;
        EXPECT_NEAR(r.b, b, 1e-3 * radius);
        auto perSigmaS = [&](double t, bool froxelPart) {
            const glm::vec3 p = origin + dir * float(t);
            const shd::LightSample ls = froxelPart ? shd::evalLightFroxel(l, p, 0.0f, f) : shd::evalLight(l, p);
            return double(shd::inScatterPerSigmaS(l, ls, dir, g).x);
        };
        // Graded toward the closest point on both sides, where 1/r^2 peaks.
        auto alongRay = [&](bool froxelPart) {
            auto fn = [&](double t) { return perSigmaS(t, froxelPart); };
            return integrateGraded([&](double x) { return fn(tc - x); }, 0.0, tc) +
                   integrateGraded([&](double x) { return fn(tc + x); }, 0.0, 20.0 - tc);
        };
        const double whole = alongRay(false);
        const double split = alongRay(true) + shd::lightGlowPerSigmaS(l, r, origin, dir, glm::vec3(0.0f), g).x;
        EXPECT_NEAR(split, whole, (bFrac < 0.1f ? 2.5e-2 : 5e-3) * whole) << "b = " << bFrac << " R";

        // Absorbing (sigma_t 0.8/m): the pixel part against its integral from where the ray enters.
        const float sigmaT = 0.8f;
        auto pixelPart = [&](double t) {
            const glm::vec3 p = origin + dir * float(t);
            const shd::LightSample ls = shd::evalLight(l, p);
            const double u2 = double(ls.distance) * ls.distance / (double(radius) * radius);
            const double h = u2 < 1.0 ? (1.0 - u2) * (1.0 - u2) : 0.0;
            return double(shd::inScatterPerSigmaS(l, ls, dir, g).x) * h *
                   std::exp(-sigmaT * ((t - r.enter) + ls.distance));
        };
        const double absorbing = integrateGraded([&](double x) { return pixelPart(tc - x); }, 0.0, tc - r.enter) +
                                 integrateGraded([&](double x) { return pixelPart(tc + x); }, 0.0, tc - r.enter);
        EXPECT_NEAR(shd::lightGlowPerSigmaS(l, r, origin, dir, glm::vec3(sigmaT), g).x, absorbing,
                    (bFrac < 0.1f ? 2.5e-2 : 5e-3) * absorbing)
            << "b = " << bFrac << " R";
        const glm::vec3 opaque = shd::lightGlowPerSigmaS(l, r, origin, dir, glm::vec3(2e9f), g);
        EXPECT_TRUE(std::isfinite(opaque.x) && opaque.x >= 0.0f && opaque.x < 1e-6f);
    }
    // A ray that ends before the ball (a surface in front of the light), or passes outside it: nothing.
    EXPECT_EQ(shd::lightGlowRay(l, f, origin, glm::normalize(toLight), glm::length(toLight) - 1.01f * radius).radius, 0.0f);
    EXPECT_EQ(shd::lightGlowRay(l, f, origin, glm::normalize(toLight + side * (1.1f * radius)), 20.0f).radius, 0.0f);
}

// The glow radius at the ends of the froxel mapping (issue 17): near 1e-4 m, far 1e4 m, every
// distribution exponent in range, lights from the camera itself to the far plane. R is the slice
// thickness (far - near) k t^(k-1) / slices with t = u^(1/k): dividing by t underflowed near the
// froxel near plane (k = 0.1: t = u^10 = 0 for a light at 1 mm), giving an infinite R. R, the froxel
// part and the pixel part must stay finite and non-negative, and R no larger than a whole-grid
// froxel.
TEST(Lights, GlowRadiusStaysFiniteAtTheFroxelNearPlane) {
    Scene scene;
    scene.camera.position = {0.0f, 1.0f, 0.0f};
    scene.camera.target = {0.0f, 1.0f, -1.0f};
    scene.camera.near = 1e-4f;
    scene.camera.far = 1e4f;
    scene.froxels.far = 1e4f;
    const glm::vec3 forward(0.0f, 0.0f, -1.0f);
    for (float k : {0.1f, 0.5f, 1.0f, 2.0f, 8.0f}) {
        scene.froxels.distribution = k;
        const FroxelSettings fs = resolveFroxelSettings(scene, Quality::High);
        const shd::FrameUniforms f = makeFrameUniforms(scene, compileScene(scene), 160, 90, fs);
        ASSERT_FLOAT_EQ(f.froxelRange.x, 1e-4f);
        ASSERT_FLOAT_EQ(f.froxelRange.y, 1e4f);
        // The largest footprint of one froxel anywhere in the grid: a tile at the far plane, the
        // whole depth range thick.
        const float tileW = 2.0f * f.projection.x * 1e4f * float(f.froxelDims.w) / float(f.counts.x);
        const float tileH = 2.0f * f.projection.y * 1e4f * float(f.froxelDims.w) / float(f.counts.y);
        const float bound = shd::LIGHT_GLOW_FROXELS * 0.5f * std::sqrt(tileW * tileW + tileH * tileH + 1e8f);
        for (float depth : {0.0f, 1e-4f, 1.00001e-4f, 1.1e-4f, 1e-3f, 1e-2f, 1.0f, 100.0f, 9999.0f}) {
            Light point = makeLight(LightType::Point);
            point.position = glm::vec3(0.0f, 1.0f, 0.0f) + forward * depth;
            point.intensity = 1e6f;
            const shd::LightData l = compileLight(point);
            const float radius = shd::lightGlowRadius(l, f);
            ASSERT_TRUE(std::isfinite(radius)) << "k " << k << ", light at " << depth << " m";
            ASSERT_GE(radius, 0.0f) << "k " << k << ", light at " << depth << " m";
            EXPECT_LE(radius, bound * 1.0001f) << "k " << k << ", light at " << depth << " m";
            const glm::vec3 origin = glm::vec3(f.cameraPosition);
            for (float along : {2e-4f, 1e-3f, 0.5f, 50.0f}) {
                for (const glm::vec3 dir : {forward, glm::normalize(forward + glm::vec3(0.01f, 0.0f, 0.0f))}) {
                    const glm::vec3 p = origin + dir * along;
                    const float froxel = shd::evalLightFroxel(l, p, 0.0f, f).irradiance.x;
                    EXPECT_TRUE(std::isfinite(froxel) && froxel >= 0.0f) << "k " << k << ", light at " << depth;
                    const shd::LightGlowRay r = shd::lightGlowRay(l, f, origin, dir, along);
                    const glm::vec3 pixel = shd::lightGlowPerSigmaS(l, r, origin, dir, glm::vec3(0.1f), 0.3f);
                    EXPECT_TRUE(std::isfinite(pixel.x) && pixel.x >= 0.0f) << "k " << k << ", light at " << depth;
                }
            }
        }
    }
}

// Scenes built in code skip the file's range checks: the divisors of the density profiles are held
// to their settings' minimum when compiled, so a zero never reaches the shared formulas.
TEST(Density, ZeroDivisorsFromCodeStayFinite) {
    Volume linear;
    linear.type = VolumeType::Height;
    linear.profile = HeightProfile::Linear;
    linear.transition_height = 0.0f;
    Volume depth;
    depth.type = VolumeType::Depth;
    depth.visibility_distance = 0.0f;
    depth.start_distance = 0.0f;
    const glm::vec3 cam(0.0f, 1.0f, 0.0f);
    for (const Volume& v : {linear, depth}) {
        const shd::VolumeData d = compileVolume(v);
        for (glm::vec3 p : {glm::vec3(0.0f), glm::vec3(0, 1e-4f, 0), glm::vec3(0, 1, 0), glm::vec3(3, 2, 1)}) {
            const float density = shd::analyticDensity(d, p, cam);
            EXPECT_TRUE(std::isfinite(density)) << toString(v.type);
            EXPECT_GE(density, 0.0f);
            EXPECT_LE(density, 1.0f);
        }
        const float len = shd::distantDensityLength(d, cam, glm::vec3(1, 0, 0), 0.0f, 50.0f);
        EXPECT_TRUE(std::isfinite(len)) << toString(v.type);
    }
}

// The glow pass runs over each light's screen rectangle only (shared/glow.h lightGlowScreenRect): every
// pixel whose ray meets the ball, as the composite's ray from the pixel centre, lies inside it; a
// light in view gets a rectangle around its ball, not the image; lights near the camera, at the
// image's edge and behind the camera are covered too.
TEST(Lights, GlowScreenRectHoldsEveryPixelWhoseRayMeetsTheBall) {
    Scene scene;
    const FroxelSettings fs = resolveFroxelSettings(scene, Quality::Low);
    const int w = 160, h = 90;
    const shd::FrameUniforms f = makeFrameUniforms(scene, compileScene(scene), w, h, fs);
    const glm::vec3 origin = glm::vec3(f.cameraPosition);
    const float farDepth = f.projection.w;
    int tight = 0;
    for (const glm::vec3 position : {glm::vec3(0.4f, 1.2f, 1.0f), glm::vec3(-3.0f, 0.3f, 2.0f), glm::vec3(0.0f, 2.0f, 7.6f),
                                     glm::vec3(6.5f, 1.0f, 0.0f), glm::vec3(2.0f, 5.0f, -30.0f), glm::vec3(0.0f, 2.0f, 9.5f)}) {
        Light point = makeLight(LightType::Point);
        point.position = position;
        const shd::LightData l = compileLight(point);
        const glm::ivec4 rect = shd::lightGlowScreenRect(l, f);
        int inside = 0;
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                const glm::vec3 viewRay = shd::viewRayFromPixel(glm::vec2(x, y) + glm::vec2(0.5f), f);
                const glm::vec3 dir = glm::normalize(glm::vec3(f.worldFromView * glm::vec4(viewRay, 0.0f)));
                if (shd::lightGlowRay(l, f, origin, dir, farDepth * glm::length(viewRay)).radius <= 0.0f) continue;
                ++inside;
                EXPECT_TRUE(x >= rect.x && x <= rect.z && y >= rect.y && y <= rect.w)
                    << "light at " << position.x << ", " << position.y << ", " << position.z << ": pixel " << x << ", " << y;
            }
        }
        const int area = rect.z < rect.x ? 0 : (rect.z - rect.x + 1) * (rect.w - rect.y + 1);
        if (inside > 0 && area < w * h / 4) ++tight;
    }
    EXPECT_GE(tight, 2);  // the lights well in view: a rectangle around the ball, not the image
}

// The same at the far end of the settings' ranges: camera and froxel far at 10^7 m, where the glow
// radius grows to the light's own depth d. Lights on and beside the view axis at the depths where the
// ball's near side d - R is 0.6, 2 and 50 times the camera near (found by bisection: R / d rises
// toward the camera), so the rectangle's tangent slopes divide by d^2 - R^2 with d near 10^5 m.
TEST(Lights, GlowScreenRectHoldsTheBallAtTheFarEndOfTheRanges) {
    Scene scene;
    scene.camera.far = 1e7f;
    scene.froxels.far = 1e7f;
    const FroxelSettings fs = resolveFroxelSettings(scene, Quality::Low);
    const int w = 160, h = 90;
    const shd::FrameUniforms f = makeFrameUniforms(scene, compileScene(scene), w, h, fs);
    const glm::vec3 origin = glm::vec3(f.cameraPosition);
    const glm::vec3 forward = glm::normalize(glm::vec3(f.worldFromView * glm::vec4(0.0f, 0.0f, -1.0f, 0.0f)));
    const glm::vec3 right = glm::normalize(glm::vec3(f.worldFromView * glm::vec4(1.0f, 0.0f, 0.0f, 0.0f)));
    const float zNear = f.projection.z;
    Light point = makeLight(LightType::Point);
    auto at = [&](float depth, float side) {
        point.position = origin + forward * depth + right * (side * depth);
        return compileLight(point);
    };
    for (const float gap : {0.6f, 2.0f, 50.0f})
        for (const float side : {0.0f, 0.3f}) {
            // d - R(d) is negative near the froxel near plane's far side of R = d and grows with d.
            float lo = f.froxelRange.x * 1.01f, hi = 0.5f * f.froxelRange.y;
            const auto gapAt = [&](float d) {
                const shd::LightData l = at(d, side);
                const float depth = -(f.viewFromWorld * glm::vec4(glm::vec3(l.positionRange), 1.0f)).z;
                return depth - shd::lightGlowRadius(l, f);
            };
            ASSERT_LT(gapAt(lo), gap * zNear);
            ASSERT_GT(gapAt(hi), gap * zNear);
            for (int i = 0; i < 200; ++i) {
                const float mid = 0.5f * (lo + hi);
                (gapAt(mid) < gap * zNear ? lo : hi) = mid;
            }
            const shd::LightData l = at(hi, side);
            ASSERT_GT(shd::lightGlowRadius(l, f), 1e3f) << "a ball of kilometres: the range's far end";
            const glm::ivec4 rect = shd::lightGlowScreenRect(l, f);
            int inside = 0;
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    const glm::vec3 viewRay = shd::viewRayFromPixel(glm::vec2(x, y) + glm::vec2(0.5f), f);
                    const glm::vec3 dir = glm::normalize(glm::vec3(f.worldFromView * glm::vec4(viewRay, 0.0f)));
                    if (shd::lightGlowRay(l, f, origin, dir, f.projection.w * glm::length(viewRay)).radius <= 0.0f) continue;
                    ++inside;
                    EXPECT_TRUE(x >= rect.x && x <= rect.z && y >= rect.y && y <= rect.w)
                        << "gap " << gap << " side " << side << ": pixel " << x << ", " << y << " outside " << rect.x
                        << " " << rect.y << " " << rect.z << " " << rect.w;
                }
            EXPECT_GT(inside, 0) << "gap " << gap << " side " << side << ": no pixel meets the ball";
        }
}
