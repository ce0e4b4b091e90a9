// Temporal integration of the CPU froxel renderer (the GPU's oracle): convergence toward the
// reference with a static camera, banding along depth, flicker, edits that must not leave ghosts,
// history that cannot be poisoned, camera motion, and the shared reprojection rule's round trip.
#include <gtest/gtest.h>

#include "shaft_scenes.h"
#include "test_support.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "core/froxel_frame.h"
#include "core/render.h"
#include "shaders/shared/brume.h"

using namespace brume;

namespace {

// A spot light cone and a point light in thin box fog over a dark ground: lighting that varies
// fast along depth, where 64 slices band. Thin and dark so the reference's shadows (the froxel
// renderer has none yet) cost little (see FroxelVsReference in test_froxel_renderer.cpp).
Scene conesScene() {
    Scene s = test::sceneWithTestView();
    Light spot = makeLight(LightType::Spot);
    spot.position = {1.5f, 4.0f, -1.0f};
    spot.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, 0.1f));
    spot.intensity = 120.0f;
    spot.inner_deg = 12.0f;
    spot.outer_deg = 18.0f;
    Light point = makeLight(LightType::Point);
    point.position = {-2.0f, 4.5f, 1.0f};  // above the fog: see TemporalFlicker
    point.intensity = 8.0f;
    point.color = {1.0f, 0.7f, 0.4f};
    s.lights = {spot, point};
    Volume box;
    box.type = VolumeType::Box;
    box.transform.translation = {0.0f, 1.5f, -2.0f};
    box.transform.scale = {10.0f, 3.0f, 12.0f};
    box.edge_fade = 0.3f;
    box.medium.scattering = glm::vec3(0.03f);
    box.medium.absorption = glm::vec3(0.003f);
    box.medium.phase_g = 0.3f;
    s.volumes = {box};
    Geometry g;
    g.type = GeometryType::Plane;
    g.albedo = glm::vec3(0.05f);
    s.geometry = {g};
    s.froxels.tile_px = 4;  // 32 x 18 columns at 128 x 72: the cones span several
    return s;
}

// Three hard-edged slabs of emissive, absorbing fog across the view at 2, -2 and -6 m, nothing else:
// the source needs no lights (so the reference is exact, without the shadows the froxel renderers
// lack yet) and the error is the slices' depth sampling alone: a slab face falls inside a slice,
// which the centre sample sees as all or nothing.
Scene slabsScene() {
    Scene s;
    s.camera.position = {0.0f, 3.0f, 6.0f};
    s.camera.target = {0.0f, 0.0f, -4.0f};
    s.camera.far = 60.0f;
    s.ambient = glm::vec3(0.0f);
    Geometry black;  // a black ground: each image row ends the fog at a different depth
    black.type = GeometryType::Plane;
    black.albedo = glm::vec3(0.0f);
    s.geometry = {black};
    for (int i = 0; i < 3; ++i) {
        Volume box;
        box.type = VolumeType::Box;
        box.transform.translation = {0.0f, 1.0f, 2.0f - 4.0f * static_cast<float>(i)};
        box.transform.scale = {30.0f, 10.0f, 1.3f};
        box.edge_fade = 0.0f;
        box.medium.scattering = glm::vec3(0.0f);
        box.medium.absorption = glm::vec3(0.5f);
        box.medium.emission = glm::vec3(0.3f, 0.25f, 0.2f);
        s.volumes.push_back(box);
    }
    return s;
}

RenderRequest request(Quality q, HistoryMode mode = HistoryMode::Continue) {
    RenderRequest r;
    r.width = 128;
    r.height = 72;
    r.quality = q;
    r.threads = 2;
    r.history = mode;
    return r;
}

// Length of the ray o + t d, t in [0, tMax], inside the axis-aligned box [lo, hi].
float lengthInside(glm::vec3 o, glm::vec3 d, float tMax, glm::vec3 lo, glm::vec3 hi) {
    const glm::vec3 inv = 1.0f / d;
    const glm::vec3 t0 = (lo - o) * inv, t1 = (hi - o) * inv;
    const glm::vec3 tn = glm::min(t0, t1), tf = glm::max(t0, t1);
    const float enter = std::max(std::max(tn.x, tn.y), std::max(tn.z, 0.0f));
    const float leave = std::min(std::min(tf.x, tf.y), std::min(tf.z, tMax));
    return std::max(leave - enter, 0.0f);
}

// Optical depth of the slabs along o + t d, t in [0, tMax] (axis-aligned boxes with hard edges).
double slabOpticalDepth(const Scene& scene, glm::vec3 o, glm::vec3 d, float tMax) {
    double tau = 0.0;
    for (const Volume& b : scene.volumes) {
        const glm::vec3 half = 0.5f * b.transform.scale;
        const glm::vec3 c = b.transform.translation;
        const float sigmaT = b.medium.scattering.x + b.medium.absorption.x;
        tau += sigmaT * lengthInside(o, d, tMax, c - half, c + half);
    }
    return tau;
}

// Banding along depth: each slice's own optical depth, -ln(T(s) / T(s - 1)) from the integrated
// transmittance along every column's centre ray, against the slabs' exact one; sum of |difference|
// over sum of exact. A slab face inside a slice makes a centre sample all or nothing: the staircase
// that shows as bands.
double bandingAlongDepth(const FroxelVolumes& v, const Scene& scene) {
    const shd::FrameUniforms& f = v.frame;
    double diff = 0.0, total = 0.0;
    for (int y = 0; y < v.dims.y; ++y) {
        for (int x = 0; x < v.dims.x; ++x) {
            const glm::vec2 pixel = (glm::vec2(x, y) + 0.5f) * static_cast<float>(f.froxelDims.w);
            const glm::vec3 dir = glm::vec3(f.worldFromView * glm::vec4(shd::viewRayFromPixel(pixel, f), 0.0f));
            double tauBefore = 0.0, transmittanceBefore = 1.0;
            for (int s = 0; s < v.dims.z; ++s) {
                const float z = shd::viewDepthFromSliceT(static_cast<float>(s + 1) / static_cast<float>(v.dims.z),
                                                         f.froxelRange.x, f.froxelRange.y, f.froxelRange.z);
                const double tau = slabOpticalDepth(scene, glm::vec3(f.cameraPosition), dir, z);
                const size_t i = (static_cast<size_t>(s) * static_cast<size_t>(v.dims.y) + static_cast<size_t>(y)) *
                                     static_cast<size_t>(v.dims.x) + static_cast<size_t>(x);
                const double transmittance = v.integratedTransmittance[i].x;
                diff += std::abs(-std::log(transmittance / transmittanceBefore) - (tau - tauBefore));
                total += tau - tauBefore;
                tauBefore = tau;
                transmittanceBefore = transmittance;
            }
        }
    }
    return diff / total;
}

bool allFinite(const std::vector<glm::vec4>& v) {
    for (const glm::vec4& p : v)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || !std::isfinite(p.w)) return false;
    return true;
}

// Mean of |a - b| / mean of |reference - off|: the share of a light's contribution still present.
double staleShare(const Image& img, const Image& off, const Image& on) {
    double stale = 0.0, light = 0.0;
    for (size_t i = 0; i < img.pixels.size(); ++i) {
        const glm::vec3 s = glm::abs(img.pixels[i] - off.pixels[i]);
        const glm::vec3 l = glm::abs(on.pixels[i] - off.pixels[i]);
        stale += s.x + s.y + s.z;
        light += l.x + l.y + l.z;
    }
    return stale / light;
}

}  // namespace

TEST(TemporalJitter, FrameZeroIsTheCentreAndTheSequenceStratifiesDepth) {
    EXPECT_EQ(shd::temporalJitter(0), glm::vec3(0.5f));
    // Every odd number of frames averages positions centred on the slice, and 17 frames put one
    // sample in each 1/16 of it (plus the centre); across the tile every frame samples the column's
    // centre (docs/temporal.md).
    double sum = 0.0;
    std::vector<int> bins(16, 0);
    for (int n = 0; n < 17; ++n) {
        const glm::vec3 j = shd::temporalJitter(n);
        EXPECT_EQ(glm::vec2(j), glm::vec2(0.5f));
        ASSERT_GE(j.z, 0.0f);
        ASSERT_LT(j.z, 1.0f);
        sum += j.z;
        if (n % 2 == 0) {
            EXPECT_NEAR(sum / (n + 1), 0.5, 1e-6) << n + 1 << " frames";
        }
        if (n > 0) ++bins[static_cast<size_t>(j.z * 16.0f)];
    }
    for (int b : bins) EXPECT_EQ(b, 1);
}

TEST(TemporalRest, ProgressiveMeanUpToTheCapThenTheExponentialBlend) {
    // The weights make the history the plain mean of every frame while the view rests...
    double mean = 0.0;
    for (int n = 1; n <= 18; ++n) {
        const double sample = std::sin(3.0 * n);  // any sequence
        const float w = n == 1 ? 0.0f : shd::temporalRestWeight(n - 1, 0.9f);
        mean = (1.0 - w) * sample + w * mean;
        double exact = 0.0;
        for (int k = 1; k <= n; ++k) exact += std::sin(3.0 * k);
        EXPECT_NEAR(mean, exact / n, 1e-6) << n;
    }
    // ... up to (1 + w) / (1 - w) frames (19 at w = 0.9), then the blend's own weight.
    EXPECT_NEAR(shd::temporalRestWeight(18, 0.9f), 18.0f / 19.0f, 1e-6f);
    EXPECT_EQ(shd::temporalRestWeight(19, 0.9f), 0.9f);
    EXPECT_EQ(shd::temporalRestWeight(1000, 0.9f), 0.9f);
    EXPECT_EQ(shd::temporalRestWeight(5, 0.0f), 0.0f);
}

TEST(TemporalReprojection, StaticCameraMapsEachFroxelOntoItself) {
    const Scene scene = conesScene();
    const CompiledScene cs = compileScene(scene);
    const shd::FrameUniforms f =
        makeFrameUniforms(scene, cs, 128, 72, resolveFroxelSettings(scene, Quality::Medium), shd::temporalJitter(3));
    for (glm::ivec3 c : {glm::ivec3(0, 0, 0), glm::ivec3(5, 3, 20), glm::ivec3(10, 5, 63)}) {
        const shd::HistoryTaps k = shd::historyTaps(c, f, f, 0.9f);
        EXPECT_NEAR(k.weight, 0.9f, 1e-4f);
        const glm::vec3 at = glm::vec3(k.lo) + k.fractions;
        EXPECT_NEAR(glm::length(at - glm::vec3(c)), 0.0f, 1e-3f);
    }
    // Behind the camera and past the froxel far: outside last frame's grid.
    EXPECT_EQ(shd::froxelCoordFromWorld(glm::vec3(scene.camera.position) + glm::vec3(0, 0, 5), f).w, 0.0f);
    EXPECT_EQ(shd::froxelCoordFromWorld(glm::vec3(0.0f, 1.0f, -80.0f), f).w, 0.0f);
}

TEST(TemporalResolve, NonFiniteValuesNeverLeaveTheResolve) {
    shd::Bounds b = shd::emptyBounds();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    for (glm::vec4 n : {glm::vec4(1.0f), glm::vec4(2.0f), glm::vec4(nan), glm::vec4(inf, 1, 1, 1)})
        b = shd::growBounds(b, n);
    EXPECT_EQ(b.lo, glm::vec4(1.0f));
    EXPECT_EQ(b.hi, glm::vec4(2.0f));
    auto history = [](glm::vec4 v) {
        shd::HistorySample h = shd::emptyHistorySample();
        for (int c = 0; c < 8; ++c)
            h = shd::addHistoryTap(h, v, glm::ivec3(c & 1, (c >> 1) & 1, c >> 2), glm::vec3(0.25f));
        return h;
    };
    // A non-finite tap is skipped, the others renormalised.
    shd::HistorySample mixed = shd::emptyHistorySample();
    mixed = shd::addHistoryTap(mixed, glm::vec4(nan), glm::ivec3(0), glm::vec3(0.5f));
    mixed = shd::addHistoryTap(mixed, glm::vec4(1.75f), glm::ivec3(1), glm::vec3(0.5f));
    EXPECT_EQ(mixed.sum / mixed.weight, glm::vec4(1.75f));
    // NaN current: the clamped history; NaN history: the current; both: 0; no bounds: the current.
    for (bool clampHistory : {true, false}) {
        const glm::vec4 held(clampHistory ? 2.0f : 5.0f);  // the history, clamped or not
        EXPECT_EQ(shd::resolveTemporal(glm::vec4(nan), history(glm::vec4(5.0f)), b, 0.9f, clampHistory), held);
        EXPECT_EQ(shd::resolveTemporal(glm::vec4(1.5f), history(glm::vec4(inf)), b, 0.9f, clampHistory),
                  glm::vec4(1.5f));
        EXPECT_EQ(shd::resolveTemporal(glm::vec4(nan), history(glm::vec4(nan)), b, 0.9f, clampHistory),
                  glm::vec4(0.0f));
        EXPECT_EQ(shd::resolveTemporal(glm::vec4(-inf), history(glm::vec4(1.0f)), shd::emptyBounds(), 0.9f, clampHistory),
                  glm::vec4(0.0f));
    }
    // The blend itself: mix(current, clamp(history), weight); at rest the history unclamped.
    const glm::vec4 r = shd::resolveTemporal(glm::vec4(1.0f), history(glm::vec4(1.5f)), b, 0.5f, true);
    EXPECT_NEAR(r.x, 1.25f, 1e-6f);
    const glm::vec4 rest = shd::resolveTemporal(glm::vec4(1.0f), history(glm::vec4(3.0f)), b, 0.5f, false);
    EXPECT_NEAR(rest.x, 2.0f, 1e-6f);
    // At rest, and without history (weight 0, the history unread whatever it holds): the froxel's own
    // history, unclamped; non-finite values as above.
    EXPECT_NEAR(shd::resolveTemporalAtRest(glm::vec4(1.0f), glm::vec4(3.0f), 0.5f).x, 2.0f, 1e-6f);
    EXPECT_EQ(shd::resolveTemporalAtRest(glm::vec4(nan), glm::vec4(5.0f), 0.9f), glm::vec4(5.0f));
    EXPECT_EQ(shd::resolveTemporalAtRest(glm::vec4(1.5f), glm::vec4(inf), 0.9f), glm::vec4(1.5f));
    EXPECT_EQ(shd::resolveTemporalAtRest(glm::vec4(nan), glm::vec4(nan), 0.9f), glm::vec4(0.0f));
    EXPECT_EQ(shd::resolveTemporalAtRest(glm::vec4(1.5f), glm::vec4(nan), 0.0f), glm::vec4(1.5f));
    EXPECT_EQ(shd::resolveTemporalAtRest(glm::vec4(-inf), glm::vec4(2.0f), 0.0f), glm::vec4(0.0f));
    EXPECT_TRUE(shd::temporalAtRest(glm::vec4(0.9f, 1.0f, 0.0f, 0.0f)));
    EXPECT_TRUE(shd::temporalAtRest(glm::vec4(0.0f)));
    EXPECT_FALSE(shd::temporalAtRest(glm::vec4(0.9f, 0.0f, 0.0f, 0.0f)));
}

// The convergence curve: with a static camera, the error against the reference falls as frames
// accumulate (jittered samples average S and sigma_t over each froxel instead of taking its
// centre), and the slice banding along depth drops with it.
TEST(TemporalConvergence, StaticViewErrorAndBandingFallAndMediumApproachesUltra) {
    const Scene scene = slabsScene();
    RenderRequest refRequest = request(Quality::Medium);
    refRequest.threads = 0;
    const Image ref = renderReference(scene, refRequest);
    ASSERT_TRUE(brume::allFinite(ref));

    FroxelCpuRenderer medium;
    std::vector<double> error, banding;
    for (int frame = 1; frame <= 16; ++frame) {
        const FroxelResult r = medium.render(scene, request(Quality::Medium));
        ASSERT_TRUE(brume::allFinite(r.image));
        error.push_back(relativeMeanAbsError(r.image, ref));
        banding.push_back(bandingAlongDepth(r.volumes, scene));
        std::printf("[convergence] medium frame %2d: error %.4f banding %.5f\n", frame, error.back(), banding.back());
    }
    Scene still = scene;
    still.temporal.enabled = false;
    const FroxelResult ultra = renderFroxelCpu(still, request(Quality::Ultra));
    const double ultraError = relativeMeanAbsError(ultra.image, ref);
    const double ultraBanding = bandingAlongDepth(ultra.volumes, scene);
    std::printf("[convergence] ultra without temporal: error %.4f banding %.5f\n", ultraError, ultraBanding);

    EXPECT_LT(error[3], error[0]);
    EXPECT_LT(error[15], error[3]);
    EXPECT_LT(error[15], 0.8 * error[0]);
    EXPECT_LT(banding[15], 0.6 * banding[0]);
    EXPECT_LT(error[15], 1.25 * ultraError);
}

// The same promise on a lit scene: the sun through a 1.5 m roof gap over height fog, one shaft seen
// from the side. Its error is mostly the shaft's width on 12 px tiles, which no number of frames
// removes, so the gain is small; what must hold is that 16 frames beat one and that more frames never
// make it worse beyond a band of 0.05 points: the error wanders by up to 0.03 points from one frame
// count to the next as the depth samples fill the slices unevenly (4.575% at 4 frames, 4.605% at 8,
// 4.592% at 16, 4.597% at 32; docs/temporal.md, "Convergence").
TEST(TemporalConvergence, LitShaftErrorFallsFromOneToFourToSixteenFrames) {
    const Scene scene = test::sunShaftScene(1.5f);
    RenderRequest req = request(Quality::Medium, HistoryMode::Continue);
    req.width = 160;
    req.height = 90;
    req.threads = 0;
    const Image ref = renderReference(scene, req);
    FroxelCpuRenderer renderer;
    std::vector<double> error;
    for (int frame = 1; frame <= 16; ++frame) {
        const FroxelResult r = renderer.render(scene, req);
        if (frame == 1 || frame == 4 || frame == 16) {
            error.push_back(relativeMeanAbsError(r.image, ref));
            std::printf("[convergence] sun shaft, medium, frame %2d: error %.5f\n", frame, error.back());
        }
    }
    const double band = 5e-4;
    EXPECT_LT(error[2], error[0]);
    EXPECT_LE(error[1], error[0] + band);
    EXPECT_LE(error[2], error[1] + band);
}

namespace {

// The CPU renderer's history after `frames` frames of `scene` from a fresh start.
CpuHistory historyAfter(const Scene& scene, const RenderRequest& req, int frames) {
    CpuHistory h;
    for (int n = 0; n < frames; ++n) renderFroxelFrameCpu(scene, req, h);
    return h;
}

// One frame with the jitter of frame `frameIndex` but no history: what the temporal pass must
// leave untouched where it rejects the history.
FroxelResult freshFrame(const Scene& scene, const RenderRequest& req, int frameIndex) {
    CpuHistory h;
    const CompiledScene cs = compileScene(scene);
    const FroxelSettings fs = resolveFroxelSettings(scene, req.quality);
    h.state.sceneKey = temporalSceneKey(cs, scene, froxelGridDims(req.width, req.height, fs));
    h.state.frameIndex = frameIndex;
    return renderFroxelFrameCpu(scene, req, h);
}

}  // namespace

TEST(TemporalHistory, SceneKeyIgnoresTheCameraAndSeesEveryEdit) {
    const Scene scene = conesScene();
    auto key = [](const Scene& s) { return temporalSceneKey(compileScene(s), s, glm::ivec3(11, 6, 64)); };
    Scene moved = scene;
    moved.camera = orbitCamera(scene.camera, 5.0f);
    EXPECT_EQ(key(scene), key(moved));
    Scene dimmer = scene;
    dimmer.lights[0].intensity *= 0.99f;
    Scene shifted = scene;
    shifted.volumes[0].transform.translation.x += 0.01f;
    Scene sky = scene;
    sky.ambient.x += 0.01f;
    Scene lowered = scene;  // geometry shadows the froxels
    lowered.geometry[0].height -= 0.01f;
    for (const Scene* s : {&dimmer, &shifted, &sky, &lowered}) EXPECT_NE(key(scene), key(*s));
    Scene recoloured = scene;  // surface colours never reach the froxels
    recoloured.geometry[0].albedo = glm::vec3(0.9f);
    EXPECT_EQ(key(scene), key(recoloured));
}

// Editing must never leave a ghost: the spot light switched off after 8 frames is gone from the
// very next frame (the scene key changed, so the history was dropped): frame k after the switch
// equals frame k of a sequence that never had the light.
TEST(TemporalHistory, LightSwitchedOffLeavesNoStaleLight) {
    const Scene on = conesScene();
    Scene off = on;
    off.lights[0].intensity = 0.0f;
    FroxelCpuRenderer renderer, neverOn;
    Image lastOn;
    for (int n = 0; n < 8; ++n) lastOn = renderer.render(on, request(Quality::Medium)).image;
    for (int k = 1; k <= 4; ++k) {
        const Image img = renderer.render(off, request(Quality::Medium)).image;
        const Image truth = neverOn.render(off, request(Quality::Medium)).image;
        if (k == 1) {
            ASSERT_GT(relativeMeanAbsError(lastOn, truth), 0.05);  // the spot is a visible part of the image
        }
        const double stale = staleShare(img, truth, lastOn);
        std::printf("[ghost] frame %d after the switch: stale light %.4f%%\n", k, 100.0 * stale);
        EXPECT_LT(stale, 1e-6);  // exactly the never-on sequence (the clamp alone leaves ~1%, below)
    }
}

// Second line of defence, for an edit the key would miss while the view moves: with the history
// kept (the key forced equal), the neighbourhood clamp alone removes the switched-off light within a
// frame. Compared with a sequence that never had the light, at the same jitter indices and views.
// (While the view rests there is no clamp, docs/temporal.md: the key is then the only defence.)
TEST(TemporalHistory, ClampingAloneRemovesStaleLightWhenTheHistoryIsKept) {
    const Scene on = conesScene();
    Scene off = on;
    off.lights[0].intensity = 0.0f;
    const RenderRequest req = request(Quality::Medium);
    CpuHistory h = historyAfter(on, req, 8);
    const Image lastOn = renderFroxelFrameCpu(on, req, h).image;  // frame index 8
    CpuHistory neverOn = historyAfter(off, req, 9);
    const uint64_t offKey = neverOn.state.sceneKey;
    for (int k = 1; k <= 3; ++k) {
        h.state.sceneKey = offKey;  // as if the edit had not been noticed
        Scene moving = off;         // a slow orbit: 0.1 degree per frame
        moving.camera = orbitCamera(off.camera, 0.1f * static_cast<float>(k));
        const Image img = renderFroxelFrameCpu(moving, req, h).image;
        const Image truth = renderFroxelFrameCpu(moving, req, neverOn).image;
        const double stale = staleShare(img, truth, lastOn);
        std::printf("[ghost] history kept, frame %d after the switch: stale light %.2f%%\n", k, 100.0 * stale);
        EXPECT_LT(stale, 0.05);
    }
}

// Godot's fog history is poisoned by NaN: black froxels that spread. Here a NaN and an Inf written
// into the history are rejected where they are read, and touch nothing else.
TEST(TemporalHistory, NanInTheHistoryDoesNotSpread) {
    const Scene scene = conesScene();
    const RenderRequest req = request(Quality::Medium);
    CpuHistory clean = historyAfter(scene, req, 4);
    CpuHistory poisoned = clean;
    HistoryVolume& h = poisoned.pair[static_cast<size_t>(poisoned.state.lastWritten)];
    const glm::ivec3 dims(poisoned.state.frame.froxelDims);
    const size_t i = (static_cast<size_t>(20) * static_cast<size_t>(dims.y) + 3) * static_cast<size_t>(dims.x) + 5;
    h.source[i] = glm::vec4(std::numeric_limits<float>::quiet_NaN());
    h.extinction[i + 1] = glm::vec4(std::numeric_limits<float>::infinity());
    FroxelResult a, b;
    for (int n = 0; n < 4; ++n) {
        a = renderFroxelFrameCpu(scene, req, clean);
        b = renderFroxelFrameCpu(scene, req, poisoned);
        ASSERT_TRUE(brume::allFinite(b.image));
        const HistoryVolume& hb = poisoned.pair[static_cast<size_t>(poisoned.state.lastWritten)];
        ASSERT_TRUE(allFinite(hb.source) && allFinite(hb.extinction));
        const HistoryVolume& ha = clean.pair[static_cast<size_t>(clean.state.lastWritten)];
        size_t changed = 0;
        for (size_t k = 0; k < ha.source.size(); ++k) {
            const float d = glm::length(ha.source[k] - hb.source[k]) + glm::length(ha.extinction[k] - hb.extinction[k]);
            const float m = glm::length(ha.source[k]) + glm::length(ha.extinction[k]);
            if (d > 1e-3f * m + 1e-9f) ++changed;
        }
        EXPECT_LE(changed, 2u) << "frame " << n;  // at most the two poisoned froxels differ
    }
    EXPECT_LT(relativeMeanAbsError(b.image, a.image), 1e-3);
}

namespace {

// Worst relative mean abs change between consecutive frames 9..16 of a static view.
double worstFlicker(const Scene& scene) {
    FroxelCpuRenderer renderer;
    Image previous;
    double worst = 0.0;
    for (int n = 1; n <= 16; ++n) {
        const Image img = renderer.render(scene, request(Quality::Medium)).image;
        if (n > 8) worst = std::max(worst, relativeMeanAbsError(img, previous));
        previous = img;
    }
    return worst;
}

}  // namespace

// A static view must not shimmer: after the history has filled, consecutive frames differ by less
// than 1% (relative mean abs), although each samples other points in every froxel; without the
// history (weight 0) the jittered frames alone differ by over ten times that.
// A point light inside the fog is the hard case: its 1/r^2 peak is sampled by whichever froxel
// sample comes closest. The light pass evaluates it no closer than half a froxel radius
// (FROXEL_LIGHT_CLAMP), which took the blended flicker from 2.6% to 1.3% (13% unblended); the
// 1% bound is not met there (measured, not hidden: docs/temporal.md).
TEST(TemporalFlicker, StaticViewChangesLessThanOnePercentPerFrame) {
    Scene scene = conesScene();
    const double flicker = worstFlicker(scene);
    scene.temporal.history_weight = 0.0f;
    const double raw = worstFlicker(scene);
    std::printf("[flicker] frames 9..16, worst change: %.3f%% with history, %.3f%% jitter alone\n",
                100.0 * flicker, 100.0 * raw);
    EXPECT_LT(flicker, 0.01);
    EXPECT_GT(flicker, 0.0);  // the jitter does move the samples
    EXPECT_LT(flicker, 0.2 * raw);

    Scene inFog = conesScene();
    inFog.lights[1].position = {-2.0f, 2.0f, 1.0f};
    const double hard = worstFlicker(inFog);
    inFog.temporal.history_weight = 0.0f;
    const double hardRaw = worstFlicker(inFog);
    std::printf("[flicker] point light inside the fog: %.3f%% with history, %.3f%% jitter alone\n", 100.0 * hard,
                100.0 * hardRaw);
    EXPECT_LT(hard, 0.15 * hardRaw);
    EXPECT_LT(hard, 0.02);  // 0.026 without the froxel-scale clamp
}

// A camera panning left by 1.5 degrees per frame (about half a froxel column at the edges): froxels
// that come into view have no history (rejected: equal to a fresh frame with the same jitter), the
// rest keep it; the pan lags a converged still of the final view by little.
TEST(TemporalMotion, NewlyVisibleFroxelsRejectHistoryAndTheRestKeepIt) {
    const Scene scene = conesScene();
    const RenderRequest req = request(Quality::Medium);
    CpuHistory h;
    Scene s = scene;
    FroxelResult r;
    for (int n = 0; n < 8; ++n) {
        const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), glm::radians(1.5f * static_cast<float>(n)), glm::vec3(0, 1, 0));
        s.camera.target = scene.camera.position + glm::vec3(turn * glm::vec4(scene.camera.target - scene.camera.position, 0.0f));
        r = renderFroxelFrameCpu(s, req, h);
    }
    const FroxelResult fresh = freshFrame(s, req, 7);
    size_t fog = 0, kept = 0;
    size_t edgeFog[2] = {0, 0}, edgeKept[2] = {0, 0};  // columns x = 0 and x = last
    const glm::ivec3 d = r.volumes.dims;
    for (size_t k = 0; k < r.volumes.source.size(); ++k) {
        if (fresh.volumes.mediaExtinction[k] == glm::vec4(0.0f)) continue;  // no fog: nothing to keep
        const int x = static_cast<int>(k % static_cast<size_t>(d.x));
        const bool keeps = r.volumes.source[k] != fresh.volumes.source[k];
        ++fog;
        kept += keeps ? 1 : 0;
        for (int e = 0; e < 2; ++e) {
            if (x != (e == 0 ? 0 : d.x - 1)) continue;
            ++edgeFog[e];
            edgeKept[e] += keeps ? 1 : 0;
        }
    }
    const double share = static_cast<double>(kept) / static_cast<double>(fog);
    std::printf("[motion] pan 1.5 deg/frame: %.1f%% of %zu fog froxels kept history; left column %zu of %zu, right %zu of %zu\n",
                100.0 * share, fog, edgeKept[0], edgeFog[0], edgeKept[1], edgeFog[1]);
    EXPECT_GT(share, 0.75);
    // The column entering the view (the left one) has none; the one leaving keeps it.
    EXPECT_GT(edgeFog[0], 0u);
    EXPECT_EQ(edgeKept[0], 0u);
    EXPECT_GT(edgeKept[1], edgeFog[1] / 2);

    FroxelCpuRenderer converged;
    Image still;
    for (int n = 0; n < 16; ++n) still = converged.render(s, req).image;
    const double lag = relativeMeanAbsError(r.image, still);
    std::printf("[motion] pan 1.5 deg/frame: final frame vs a converged still of the same view %.4f\n", lag);
    EXPECT_LT(lag, 0.03);
}

// The history weight falls with the reprojection distance: a camera moved sideways by more froxels
// trusts the history less, and not at all from TEMPORAL_MOTION_FROXELS on.
TEST(TemporalMotion, HistoryWeightFallsWithReprojectionDistance) {
    const Scene scene = conesScene();
    const CompiledScene cs = compileScene(scene);
    const FroxelSettings fs = resolveFroxelSettings(scene, Quality::Medium);
    const shd::FrameUniforms prev = makeFrameUniforms(scene, cs, 128, 72, fs);
    float previousWeight = 1.0f;
    for (float shift : {0.0f, 0.5f, 1.0f, 2.0f, 4.0f}) {
        Scene moved = scene;
        moved.camera.position.x += shift;
        moved.camera.target.x += shift;
        const shd::FrameUniforms cur = makeFrameUniforms(moved, cs, 128, 72, fs);
        const shd::HistoryTaps k = shd::historyTaps(glm::ivec3(16, 9, 30), cur, prev, 0.9f);
        std::printf("[motion] camera moved %.2f m sideways: history weight %.3f\n", shift, k.weight);
        if (shift == 0.0f) {
            EXPECT_NEAR(k.weight, 0.9f, 1e-4f);
        } else {
            EXPECT_LT(k.weight, previousWeight);
        }
        previousWeight = k.weight;
    }
    EXPECT_EQ(previousWeight, 0.0f);
}

// A sequence reports progress over all its frames, not only the last: values never fall, the first
// frame's end is reported near 1/frames, and the last call is 1.
TEST(TemporalProgress, SpansEveryFrameOfTheSequence) {
    Scene scene = conesScene();
    RenderRequest req = request(Quality::Low);
    req.width = 64;
    req.height = 36;
    req.frames = 4;
    std::vector<float> calls;
    req.progress = [&calls](float f) { calls.push_back(f); };
    renderFroxelCpu(scene, req);
    ASSERT_FALSE(calls.empty());
    for (size_t i = 1; i < calls.size(); ++i) EXPECT_GE(calls[i], calls[i - 1]) << i;
    EXPECT_LT(calls.front(), 0.26f);
    EXPECT_TRUE(std::find(calls.begin(), calls.end(), 0.25f) != calls.end()) << "end of frame 1";
    EXPECT_EQ(calls.back(), 1.0f);
}
