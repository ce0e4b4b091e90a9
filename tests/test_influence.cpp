// Influencers (core/influence.h, shaders/shared/influence.h): the thinning at the centre and its
// falloff, the wake's decay against its closed form, the image recovering after 10 half-lives, the
// froxel renderer against the reference with an influencer, and the scene format's bad input.
#include <gtest/gtest.h>

#include "test_support.h"

#include <cmath>
#include <cstdio>

#include "core/compile.h"
#include "core/influence.h"
#include "core/render.h"
#include "io/scene_json.h"

using namespace brume;

namespace {

const glm::vec3 kCentre(0.0f, 1.0f, -1.0f);

Influencer sphereAt(std::vector<std::pair<float, glm::vec3>> path, float radius, float strength, float halfLife) {
    Influencer f;
    f.type = InfluencerType::Sphere;
    f.radius = radius;
    f.strength = strength;
    f.wake_half_life_s = halfLife;
    f.path.target = "position";
    for (const auto& [t, p] : path) f.path.keys.push_back(Keyframe{t, p});
    return f;
}

// Uniform box fog around the influencers, seen by the shared test view (camera at z = 7; the box
// spans z from -5 to 3, so an influencer near z = 1.5 is seen through little fog).
Scene fogScene() {
    Scene s = test::sceneWithTestView();
    s.volumes = {test::boxFog({0.0f, 1.0f, -1.0f}, {8.0f, 3.0f, 8.0f}, 0.0f, 0.3f, 0.02f)};
    Light sun = makeLight(LightType::Directional);
    sun.direction = glm::normalize(glm::vec3(0.2f, -0.9f, 0.45f));
    sun.intensity = 2.0f;
    s.lights = {sun};
    return s;
}

// The froxel-vs-reference scene of test_froxel_renderer.cpp (FroxelVsReference: high within 3%): a
// box of thin fog over a dark ground, lit by the sun and a point light.
Scene boxFogScene() {
    Scene s = test::sceneWithTestView();
    Light sun = makeLight(LightType::Directional);
    sun.direction = glm::normalize(glm::vec3(0.2f, -0.9f, 0.45f));
    sun.intensity = 2.0f;
    Light point = makeLight(LightType::Point);
    point.position = {-3.0f, 4.5f, 0.0f};
    point.intensity = 20.0f;
    point.color = {1.0f, 0.7f, 0.4f};
    s.lights = {sun, point};
    Volume box = test::boxFog({0.0f, 1.5f, -3.0f}, {10.0f, 3.0f, 10.0f}, 0.3f, glm::vec3(0.02f), glm::vec3(0.003f));
    box.medium.phase_g = 0.5f;
    s.volumes = {box};
    s.geometry = {test::groundPlane(glm::vec3(0.05f))};
    return s;
}

float extinctionAt(const Scene& s, float t, glm::vec3 p) {
    Scene at = s;
    at.time_s = t;
    return mediaAt(compileScene(at), p).sigmaT.x;
}

RenderRequest request(int w, int h, Quality q) {
    RenderRequest r;
    r.width = w;
    r.height = h;
    r.threads = 0;
    r.quality = q;
    return r;
}

}  // namespace

// density x (1 - strength x falloff(d / r)), falloff(u) = 1 - smoothstep(0, 1, u); nothing at the radius.
TEST(Influence, DensityAtTheCentreIsReducedByTheStrength) {
    Scene s = fogScene();
    const float plain = extinctionAt(s, 0.0f, kCentre);
    ASSERT_GT(plain, 0.0f);
    s.influencers = {sphereAt({{0.0f, kCentre}, {1.0f, kCentre}}, 1.5f, 0.7f, 1.0f)};
    EXPECT_NEAR(extinctionAt(s, 0.5f, kCentre), plain * 0.3f, 1e-6f * plain);
    const glm::vec3 half = kCentre + glm::vec3(0.75f, 0.0f, 0.0f);  // u = 0.5: falloff 0.5
    EXPECT_NEAR(extinctionAt(s, 0.5f, half), plain * (1.0f - 0.7f * 0.5f), 1e-5f * plain);
    EXPECT_NEAR(extinctionAt(s, 0.5f, kCentre + glm::vec3(0.0f, 0.0f, 1.5f)), plain, 1e-6f * plain);
    // A capsule thins its whole upright axis alike.
    s.influencers[0].type = InfluencerType::Capsule;
    s.influencers[0].length = 1.0f;
    EXPECT_NEAR(extinctionAt(s, 0.5f, kCentre + glm::vec3(0.0f, 0.45f, 0.0f)), plain * 0.3f, 1e-6f * plain);
    EXPECT_NEAR(extinctionAt(s, 0.5f, kCentre + glm::vec3(1.5f, 0.45f, 0.0f)), plain, 1e-6f * plain);
}

// The influencer rests at P until t = 1 s, then leaves; at P the reduction is then
// strength x 2^(-(t - 1) / h): the wake copy of tau = 1 s (a multiple of the step) is the newest there.
TEST(Influence, WakeDecaysAsTheClosedForm) {
    Scene s = fogScene();
    const float plain = extinctionAt(s, 0.0f, kCentre);
    const float strength = 0.9f, h = 0.5f;
    Influencer f = sphereAt({{0.0f, kCentre}, {1.0f, kCentre}, {1.125f, glm::vec3(30.0f, 1.0f, 0.0f)}}, 1.0f, strength, h);
    f.wake_step_s = 0.125f;
    f.wake_samples = 64;  // h log2(0.9 / 0.001) / 64 = 0.077 s < the step: the step stays 0.125 s
    ASSERT_EQ(influenceWakeStep(f), 0.125);
    s.influencers = {f};
    for (float t : {1.25f, 1.5f, 2.0f, 2.75f, 4.0f}) {
        const float expected = plain * (1.0f - strength * std::exp2(-(t - 1.0f) / h));
        EXPECT_NEAR(extinctionAt(s, t, kCentre), expected, 2e-6f * plain) << "t = " << t;
    }
    // Past the live wake (strength x 2^(-age/h) < 0.001) nothing is left.
    EXPECT_EQ(extinctionAt(s, 1.0f + 10.0f, kCentre), plain);
    // The samples follow the scene time alone: compiled twice, or after other times, they are equal.
    const InfluenceSet a = compileInfluence(s.influencers, 2.3f);
    compileInfluence(s.influencers, 7.0f);
    const InfluenceSet b = compileInfluence(s.influencers, 2.3f);
    ASSERT_EQ(a.samples.size(), b.samples.size());
    for (size_t i = 0; i < a.samples.size(); ++i) EXPECT_TRUE(a.samples[i].a == b.samples[i].a && a.samples[i].b == b.samples[i].b);
}

// A wake longer than wake_samples steps takes a longer step, so the samples reach its end.
TEST(Influence, WakeSamplesAreCappedAndReachTheEndOfTheLiveWake) {
    Influencer f = sphereAt({{0.0f, glm::vec3(-20.0f, 0.0f, 0.0f)}, {40.0f, glm::vec3(20.0f, 0.0f, 0.0f)}}, 0.5f, 1.0f, 2.0f);
    f.wake_step_s = 0.01f;
    f.wake_samples = 16;
    const double step = influenceWakeStep(f);
    EXPECT_NEAR(step, 2.0 * std::log2(1.0 / 0.001) / 16.0, 1e-6);
    // Moving all along (no copy is left out as equal to a newer one): the shape now and 16 copies,
    // the oldest within one step of the end of the live wake (strength 0.001 x 2^(step / h) at most).
    const InfluenceSet set = compileInfluence({f}, 35.0f);
    EXPECT_EQ(set.samples.size(), 1u + 16u);
    EXPECT_LT(set.samples.back().b.w, 2.0f * shd::INFLUENCE_MIN_STRENGTH);
    // The box holds every sample.
    for (const shd::InfluenceSample& s : set.samples) {
        EXPECT_TRUE(shd::insideInfluenceBounds(set.header, glm::vec3(s.a)));
    }
}

// The influencer crosses the fog and leaves it at t = 1 s; 10 half-lives later the image is the one
// without it (the wake's last copies weigh 2^-10), while just after it left it is not.
TEST(Influence, AfterTenHalfLivesTheImageEqualsTheImageWithoutTheInfluencer) {
    Scene s = fogScene();
    const float h = 0.4f;
    s.influencers = {sphereAt({{0.0f, glm::vec3(-3.0f, 1.0f, 1.5f)}, {1.0f, glm::vec3(3.0f, 1.0f, 1.5f)},
                               {1.05f, glm::vec3(3.0f, 1.0f, -40.0f)}},
                              1.5f, 1.0f, h)};
    s.influencers[0].type = InfluencerType::Capsule;  // a trench through the box's whole height
    s.influencers[0].length = 2.0f;
    Scene without = s;
    without.influencers.clear();
    const RenderRequest req = request(96, 54, Quality::Medium);
    s.time_s = without.time_s = 1.0f + 10.0f * h;
    const Image plain = renderFroxelCpu(without, req).image;
    const double late = relativeMeanAbsError(renderFroxelCpu(s, req).image, plain);
    s.time_s = 1.0f;
    const double early = relativeMeanAbsError(renderFroxelCpu(s, req).image, plain);
    std::printf("image error against no influencer: just after %.4f, after 10 half-lives %.6f\n", early, late);
    EXPECT_LT(late, 0.005);
    EXPECT_GT(early, 0.02);
}

// The froxel renderer against the reference with an influencer and its wake in the fog, within the
// bound the other scenes hold at high (test_froxel_renderer.cpp: 3%).
TEST(Influence, FroxelRendererMatchesTheReference) {
    Scene s = boxFogScene();
    Influencer f = sphereAt({{0.0f, glm::vec3(-4.0f, 1.5f, 0.5f)}, {2.0f, glm::vec3(3.0f, 1.5f, -1.0f)}}, 1.4f, 1.0f, 1.0f);
    f.type = InfluencerType::Capsule;
    f.length = 1.0f;
    s.influencers = {f};
    s.time_s = 1.5f;
    const RenderRequest req = request(160, 90, Quality::High);
    const Image ref = renderReference(s, req);
    Scene without = s;
    without.influencers.clear();
    const double influence = relativeMeanAbsError(renderReference(without, req), ref);
    const double err = relativeMeanAbsError(renderFroxelCpu(s, req).image, ref);
    std::printf("influencer: its effect on the reference %.4f, froxel high vs reference %.4f\n", influence, err);
    EXPECT_GT(influence, 0.01) << "the influencer must matter for the bound to mean something";
    EXPECT_LT(err, 0.03);
}

TEST(InfluenceJson, RoundTripsAndBadInputNamesThePath) {
    const std::string good = R"({"brume_scene": 1,
      "influencers": [{"type": "capsule", "name": "walker", "radius": 0.4, "length": 1.2, "strength": 0.8,
                       "wake_half_life_s": 1.5, "path_interpolation": "smooth",
                       "path": [{"time": 0, "position": [0, 1, 0]}, {"time": 2, "position": [3, 1, 0]}]}]})";
    const Result<Scene> parsed = parseScene(good, "scene.json");
    ASSERT_TRUE(parsed.ok()) << parsed.error().message;
    const Scene& s = parsed.value();
    ASSERT_EQ(s.influencers.size(), 1u);
    EXPECT_EQ(s.influencers[0].type, InfluencerType::Capsule);
    EXPECT_EQ(s.influencers[0].path.keys.size(), 2u);
    EXPECT_EQ(s.influencers[0].path.interpolation, Interpolation::Smooth);
    const Result<Scene> again = parseScene(sceneToJson(s), "scene.json");
    ASSERT_TRUE(again.ok()) << again.error().message;
    EXPECT_TRUE(again.value() == s);

    const std::pair<const char*, const char*> cases[] = {
        {R"({"brume_scene": 1, "influencers": [{"type": "sphere", "path": [{"time": 0, "position": [0, 1, 0]}]}]})",
         "scene.json: influencers[0].path: expected an array of at least 2 points {\"time\": s, \"position\": [x, y, z]}, got an array of 1 value"},
        {R"({"brume_scene": 1, "influencers": [{"type": "sphere", "wake_half_life_s": -1,
             "path": [{"time": 0, "position": [0, 1, 0]}, {"time": 1, "position": [1, 1, 0]}]}]})",
         "scene.json: influencers[0].wake_half_life_s: -1 s is out of range [0, 10000] s"},
        {R"({"brume_scene": 1, "influencers": [{"type": "sphere",
             "path": [{"time": 1, "position": [0, 1, 0]}, {"time": 0.5, "position": [1, 1, 0]}]}]})",
         "scene.json: influencers[0].path[1].time: 0.5 s is not after the previous point's time (1 s); a path's points must be in increasing time"},
        {R"({"brume_scene": 1, "influencers": [{"type": "cube",
             "path": [{"time": 0, "position": [0, 1, 0]}, {"time": 1, "position": [1, 1, 0]}]}]})",
         "scene.json: influencers[0].type: unknown choice \"cube\"; choices: sphere, capsule"},
        {R"({"brume_scene": 1, "influencers": [{"type": "sphere", "length": 2,
             "path": [{"time": 0, "position": [0, 1, 0]}, {"time": 1, "position": [1, 1, 0]}]}]})",
         "scene.json: influencers[0].length: unknown key; allowed in a sphere influencer: type, name, radius, strength, "
         "wake_half_life_s, wake_step_s, wake_samples, path_interpolation, path"},
        {R"({"brume_scene": 1, "influencers": [{"type": "sphere"}]})",
         "scene.json: influencers[0].path: missing required key (at least 2 points {\"time\": s, \"position\": [x, y, z]})"},
    };
    for (const auto& [text, message] : cases) {
        const Result<Scene> r = parseScene(text, "scene.json");
        ASSERT_FALSE(r.ok()) << text;
        EXPECT_EQ(r.error().message, message) << text;
    }
}
