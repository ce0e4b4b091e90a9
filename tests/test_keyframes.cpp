// Keyframes (core/keyframes.h, core/animate.h): values at and between keys, both interpolations,
// extrapolation holding the end values, and the renderers seeing the keyed values at the scene time.
#include <gtest/gtest.h>

#include <cmath>

#include "core/animate.h"
#include "core/compile.h"
#include "core/render.h"

namespace brume {
namespace {

KeyTrack track(Interpolation interp, std::vector<std::pair<float, float>> keys) {
    KeyTrack t;
    t.target = "medium.phase_g";
    t.interpolation = interp;
    for (auto [time, value] : keys) t.keys.push_back({time, glm::vec3(value, 2.0f * value, -value)});
    return t;
}

TEST(Keyframes, LinearAtAndBetweenKeys) {
    const KeyTrack t = track(Interpolation::Linear, {{0.0f, 1.0f}, {2.0f, 3.0f}, {3.0f, -1.0f}});
    EXPECT_EQ(evaluateTrack(t, 0.0f), glm::vec3(1, 2, -1));
    EXPECT_EQ(evaluateTrack(t, 2.0f), glm::vec3(3, 6, -3));
    EXPECT_EQ(evaluateTrack(t, 3.0f), glm::vec3(-1, -2, 1));
    EXPECT_FLOAT_EQ(evaluateTrack(t, 0.5f).x, 1.5f);
    EXPECT_FLOAT_EQ(evaluateTrack(t, 2.25f).x, 2.0f);
    EXPECT_FLOAT_EQ(evaluateTrack(t, 2.25f).y, 4.0f);
}

TEST(Keyframes, ExtrapolationHoldsTheEndValues) {
    for (Interpolation i : {Interpolation::Linear, Interpolation::Smooth}) {
        const KeyTrack t = track(i, {{1.0f, 5.0f}, {2.0f, 7.0f}, {4.0f, 6.0f}});
        EXPECT_EQ(evaluateTrack(t, -1.0e6f).x, 5.0f);
        EXPECT_EQ(evaluateTrack(t, 0.999f).x, 5.0f);
        EXPECT_EQ(evaluateTrack(t, 4.001f).x, 6.0f);
        EXPECT_EQ(evaluateTrack(t, 1.0e6f).x, 6.0f);
        EXPECT_EQ(evaluateTrack(t, NAN).x, 5.0f);
    }
    const KeyTrack one = track(Interpolation::Smooth, {{3.0f, 0.25f}});
    EXPECT_EQ(evaluateTrack(one, -5.0f).x, 0.25f);
    EXPECT_EQ(evaluateTrack(one, 3.0f).x, 0.25f);
    EXPECT_EQ(evaluateTrack(one, 50.0f).x, 0.25f);
}

TEST(Keyframes, SmoothPassesThroughKeysAndHasNoKinks) {
    const KeyTrack t = track(Interpolation::Smooth, {{0.0f, 0.0f}, {1.0f, 2.0f}, {3.0f, 1.0f}, {3.5f, 4.0f}});
    for (const Keyframe& k : t.keys) EXPECT_NEAR(evaluateTrack(t, k.time).x, k.value.x, 1e-6f);
    // The slope on both sides of an inner key agrees (C1), where linear has a kink.
    const float h = 1.0e-3f;
    for (float at : {1.0f, 3.0f}) {
        const float left = (evaluateTrack(t, at).x - evaluateTrack(t, at - h).x) / h;
        const float right = (evaluateTrack(t, at + h).x - evaluateTrack(t, at).x) / h;
        EXPECT_NEAR(left, right, 0.05f * (std::abs(left) + 1.0f)) << "at " << at;
    }
    // Between keys it is a curve, not the chord.
    KeyTrack linear = t;
    linear.interpolation = Interpolation::Linear;
    EXPECT_GT(std::abs(evaluateTrack(t, 2.0f).x - evaluateTrack(linear, 2.0f).x), 0.05f);
}

// Catmull-Rom with finite-difference tangents reproduces a straight line exactly, unevenly spaced keys
// included.
TEST(Keyframes, SmoothReproducesALine) {
    const KeyTrack t = track(Interpolation::Smooth, {{0.0f, 1.0f}, {0.5f, 2.0f}, {2.0f, 5.0f}, {2.25f, 5.5f}});
    for (float x = 0.0f; x <= 2.25f; x += 0.125f) EXPECT_NEAR(evaluateTrack(t, x).x, 1.0f + 2.0f * x, 1e-5f) << x;
}

Scene keyedScene() {
    Scene s;
    s.render = {32, 18, Quality::Low};
    s.camera.position = {0, 1, 4};
    s.camera.target = {0, 1, 0};
    Volume v;
    v.type = VolumeType::Box;
    v.transform.scale = {3, 2, 3};
    v.transform.translation = {0, 1, 0};
    KeyTrack scat;
    scat.target = "medium.scattering";
    scat.keys = {{0.0f, glm::vec3(0.0f)}, {2.0f, glm::vec3(0.4f, 0.2f, 0.1f)}};
    KeyTrack move;
    move.target = "transform.translation";
    move.interpolation = Interpolation::Smooth;
    move.keys = {{0.0f, {0, 1, 0}}, {1.0f, {1, 1, 0}}, {2.0f, {0, 1, 0}}};
    v.keys = {scat, move};
    s.volumes.push_back(v);
    Light l = makeLight(LightType::Point);
    l.position = {0, 2, 0};
    KeyTrack intensity;
    intensity.target = "intensity";
    intensity.keys = {{0.0f, glm::vec3(10.0f, 0, 0)}, {1.0f, glm::vec3(30.0f, 0, 0)}};
    l.keys = {intensity};
    s.lights.push_back(l);
    return s;
}

TEST(Keyframes, BakeWritesTheValuesAtTheTime) {
    const Scene s = keyedScene();
    const Scene at1 = bakeKeys(s, 1.0f);
    EXPECT_EQ(at1.time_s, 1.0f);
    EXPECT_TRUE(at1.volumes[0].keys.empty());
    EXPECT_FLOAT_EQ(at1.volumes[0].medium.scattering.x, 0.2f);
    EXPECT_FLOAT_EQ(at1.volumes[0].medium.scattering.y, 0.1f);
    EXPECT_NEAR(at1.volumes[0].transform.translation.x, 1.0f, 1e-6f);
    EXPECT_FLOAT_EQ(at1.lights[0].intensity, 30.0f);
    EXPECT_FLOAT_EQ(bakeKeys(s, 0.5f).lights[0].intensity, 20.0f);
    EXPECT_FLOAT_EQ(bakeKeys(s, 9.0f).lights[0].intensity, 30.0f);
    EXPECT_EQ(bakeKeys(at1, 5.0f).volumes, at1.volumes);  // nothing left to bake
}

// A smooth curve may overshoot; the value stays in the setting's range (scattering >= 0) and a keyed
// direction stays a unit vector.
TEST(Keyframes, BakedValuesStayValid) {
    Scene s = keyedScene();
    KeyTrack dip;
    dip.target = "medium.absorption";
    dip.interpolation = Interpolation::Smooth;
    dip.keys = {{0.0f, glm::vec3(0.0f)}, {1.0f, glm::vec3(0.0f)}, {2.0f, glm::vec3(1.0f)}};
    ASSERT_LT(evaluateTrack(dip, 0.5f).x, 0.0f);  // the curve itself dips below zero
    s.volumes[0].keys.push_back(dip);
    EXPECT_EQ(bakeKeys(s, 0.5f).volumes[0].medium.absorption, glm::vec3(0.0f));
    Light sun = makeLight(LightType::Directional);
    KeyTrack turn;
    turn.target = "direction";
    turn.keys = {{0.0f, {0, -1, 0}}, {1.0f, {1, 0, 0}}};
    sun.keys = {turn};
    s.lights.push_back(sun);
    EXPECT_NEAR(glm::length(bakeKeys(s, 0.5f).lights[1].direction), 1.0f, 1e-6f);
}

// compileScene bakes at the scene time, so every renderer that compiles sees the keyed values:
// rendering the keyed scene at t equals rendering the scene baked at t, and differs from t = 0.
TEST(Keyframes, RenderersSeeTheKeyedValues) {
    Scene s = keyedScene();
    s.time_s = 1.5f;
    const Scene baked = bakeKeys(s, 1.5f);
    RenderRequest r = requestFromScene(s);
    const Image keyed = renderFroxelCpu(s, r).image;
    EXPECT_EQ(keyed.pixels, renderFroxelCpu(baked, r).image.pixels);
    EXPECT_EQ(renderReference(s, r).pixels, renderReference(baked, r).pixels);
    Scene start = s;
    start.time_s = 0.0f;
    EXPECT_NE(keyed.pixels, renderFroxelCpu(start, r).image.pixels);  // no fog at t = 0
}

}  // namespace
}  // namespace brume
