// Scenes at the ends of every range (issue 17; docs/reliability.md), rendered at 160x90 by all three
// renderers: sigma_t 0 and 1e9, g = +-1, near 1e-4 with far 1e4, coordinates at 1e5 m, boxes of 1e-4
// and 1e6 m, depth fog with a visibility of 1 mm, a point light at a froxel's sample point, a 0 deg
// spot. Every image must be finite and non-negative; where only the sky lights the scene no pixel may
// exceed the sky radiance (energy is never created); inside an opaque box the froxel renderers must
// agree with the reference's closed form; the lights' glow stays finite near the froxel near plane
// (near 1e-4 m, far 1e4 m, lights at the camera). Render times are printed (docs/reliability.md quotes them),
// never asserted.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "core/compile.h"
#include "core/quality.h"
#include "core/reference_detail.h"
#include "core/render.h"
#include "io/vdb_import.h"
#include "gpu_test_support.h"
#include "test_support.h"

namespace brume {
namespace {

using test::boxFog;

constexpr int kWidth = 160, kHeight = 90;
const glm::vec3 kSky(0.5f);

struct Case {
    std::string name;
    Scene scene;
    bool ambientOnly = false;  // no light but the sky: no pixel above the sky radiance
};

Scene baseScene() {
    Scene s;
    s.camera.position = {0.0f, 1.0f, 5.0f};
    s.camera.target = {0.0f, 1.0f, 0.0f};
    s.camera.near = 0.1f;
    s.camera.far = 100.0f;
    s.ambient = kSky;
    s.render.width = kWidth;
    s.render.height = kHeight;
    return s;
}

std::vector<Light> someLights(glm::vec3 offset = glm::vec3(0.0f)) {
    Light sun = makeLight(LightType::Directional);
    sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.2f));
    Light point = test::pointLight(offset + glm::vec3(0.5f, 1.2f, 0.5f), 0.0f, 20.0f);
    point.shadows = true;
    Light spot = makeLight(LightType::Spot);
    spot.position = offset + glm::vec3(-1.0f, 3.0f, 0.0f);
    spot.direction = {0.0f, -1.0f, 0.0f};
    spot.intensity = 50.0f;
    return {sun, point, spot};
}

// Scattering-only fog (albedo 1) and, beside it, absorbing fog: in a sky of radiance A neither may
// ever look brighter than A.
void addAmbientOnlyVariant(std::vector<Case>& cases, const std::string& name, Scene s) {
    s.lights.clear();
    s.geometry.clear();
    cases.push_back({name + ", sky only", s, true});
}

// assets/noise/mist.vdb (the example scenes' noise), loaded once.
DensityGridPtr mistGrid() {
    static const DensityGridPtr grid = [] {
        Result<VdbLoad> r = loadVdbDensity(std::string(BRUME_SOURCE_DIR) + "/assets/noise/mist.vdb", {});
        EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
        return r.ok() ? r.value().grid : nullptr;
    }();
    return grid;
}

// The smallest tile in range (1 mm; mist.vdb is 32^3: voxels of 31 um) on a texture and its detail (strength 2:
// more contrast, the factor held at 0 in places).
DensityTexture smallestTexture() {
    DensityTexture t;
    t.file = t.detail.emplace().file = "mist.vdb";
    t.tile_size_m = t.detail->tile_size_m = 1e-3f;
    t.detail->strength = 2.0f;
    t.density = t.detail->density = mistGrid();
    t.mean = t.detail->mean = t.density ? static_cast<float>(t.density->activeBoxMean()) : 0.0f;
    return t;
}

// The range's extremes for the camera: near 1e-4, far 1e4.
Scene nearAndFarScene() {
    Scene s = baseScene();
    s.camera.near = 1e-4f;
    s.camera.far = 1e4f;
    return s;
}

// Height fog that every ray crosses out to the far plane.
Volume unboundedHeightFog() {
    Volume h;
    h.type = VolumeType::Height;
    h.falloff = 0.5f;
    h.medium.scattering = glm::vec3(0.02f);
    h.medium.absorption = glm::vec3(0.005f);
    return h;
}

// Unbounded fog modulated by the smallest texture, near 1e-4, far 1e4: rays cross 1e4 m of fog whose
// texture changes every 31 um. Height fog with the texture and its detail; depth fog with the texture
// alone at strength 2.
std::vector<Scene> texturedUnboundedScenes() {
    Scene s = nearAndFarScene();
    Volume h = unboundedHeightFog();
    h.density_texture = smallestTexture();
    Volume d;
    d.type = VolumeType::Depth;
    d.visibility_distance = 50.0f;
    d.medium.scattering = glm::vec3(0.01f);
    d.medium.absorption = glm::vec3(0.002f);
    d.density_texture = smallestTexture();
    d.density_texture->detail.reset();
    d.density_texture->strength = 2.0f;
    Scene height = s, depth = s;
    height.volumes = {h};
    depth.volumes = {d};
    return {height, depth};
}

std::vector<Case> extremeCases() {
    std::vector<Case> cases;
    auto withLights = [&](const std::string& name, Scene s) {
        addAmbientOnlyVariant(cases, name, s);
        s.lights = someLights();
        s.geometry = {test::groundPlane(glm::vec3(0.5f))};
        cases.push_back({name, s, false});
    };
    for (float sigma : {0.0f, 1e9f}) {
        Scene s = baseScene();
        s.volumes = {boxFog({0.0f, 1.0f, 0.0f}, {3.0f, 2.0f, 3.0f}, 0.3f, sigma, 0.0f),
                     boxFog({1.5f, 1.0f, -2.0f}, {2.0f, 2.0f, 2.0f}, 0.0f, sigma, sigma)};
        withLights(sigma == 0.0f ? "sigma_t 0" : "sigma_t 1e9", s);
    }
    for (float g : {1.0f, -1.0f}) {
        Scene s = baseScene();
        s.volumes = {boxFog({0.0f, 1.0f, 0.0f}, {4.0f, 2.0f, 4.0f}, 0.3f, 0.5f, 0.05f)};
        s.volumes[0].medium.phase_g = g;
        withLights(g > 0.0f ? "g = +1" : "g = -1", s);
    }
    {
        Scene s = nearAndFarScene();
        s.volumes = {unboundedHeightFog(), boxFog({0.0f, 1.0f, 0.0f}, {2.0f, 2.0f, 2.0f}, 0.5f, 0.4f, 0.0f)};
        withLights("near 1e-4, far 1e4", s);
    }
    {
        const std::vector<Scene> textured = texturedUnboundedScenes();
        withLights("height fog, 1 mm texture, far 1e4", textured[0]);
        withLights("depth fog, 1 mm texture, far 1e4", textured[1]);
    }
    {
        Scene s = baseScene();
        const glm::vec3 shift(1e5f, 0.0f, -1e5f);
        s.camera.position += shift;
        s.camera.target += shift;
        s.volumes = {boxFog(shift + glm::vec3(0.0f, 1.0f, 0.0f), {3.0f, 2.0f, 3.0f}, 0.3f, 0.5f, 0.05f)};
        addAmbientOnlyVariant(cases, "coordinates at 1e5 m", s);
        s.lights = someLights(shift);
        cases.push_back({"coordinates at 1e5 m", s, false});
    }
    for (float size : {1e-4f, 1e6f}) {
        Scene s = baseScene();
        s.volumes = {boxFog({0.0f, 1.0f, 0.0f}, glm::vec3(size), 0.2f, 0.3f, 0.05f)};
        withLights(size < 1.0f ? "box of 1e-4 m" : "box of 1e6 m", s);
    }
    {
        Scene s = baseScene();
        Volume d;
        d.type = VolumeType::Depth;
        d.visibility_distance = 1e-3f;
        d.medium.scattering = glm::vec3(0.05f);
        d.medium.absorption = glm::vec3(0.01f);
        s.volumes = {d};
        withLights("depth fog, visibility 1 mm", s);
    }
    {
        // A point light exactly on a froxel's sample point (slice 10, centre column), in fog.
        Scene s = baseScene();
        s.volumes = {boxFog({0.0f, 1.0f, 0.0f}, {6.0f, 3.0f, 8.0f}, 0.2f, 0.3f, 0.05f)};
        const CompiledScene cs = compileScene(s);
        const FroxelSettings fs = resolveFroxelSettings(s, Quality::High);
        const shd::FrameUniforms f = makeFrameUniforms(s, cs, kWidth, kHeight, fs);
        const glm::vec3 coord(std::floor(static_cast<float>(f.froxelDims.x) * 0.5f),
                              std::floor(static_cast<float>(f.froxelDims.y) * 0.5f), 10.0f);
        s.lights = {test::pointLight(shd::worldFromFroxelCoord(coord + glm::vec3(f.jitter), f), 0.0f, 100.0f)};
        cases.push_back({"point light at a froxel sample point", s, false});
    }
    {
        Scene s = baseScene();
        s.volumes = {boxFog({0.0f, 1.0f, 0.0f}, {6.0f, 3.0f, 6.0f}, 0.2f, 0.3f, 0.05f)};
        Light spot = makeLight(LightType::Spot);
        spot.position = {0.0f, 2.4f, 0.0f};
        spot.direction = {0.0f, -1.0f, 0.0f};
        spot.inner_deg = spot.outer_deg = 0.0f;
        spot.intensity = 1e3f;
        s.lights = {spot};
        s.geometry = {test::groundPlane(glm::vec3(0.5f))};
        cases.push_back({"0 deg spot", s, false});
    }
    return cases;
}

// The lights' glow near the froxel near plane (shaders/shared/glow.h): near 1e-4 m, far 1e4 m, the
// extreme slice distributions, point lights at the camera and just past the near plane and a spot
// at the camera, in fog around the camera. Froxel renderers only (the glow is their split of the
// inverse square); each image finite and non-negative.
std::vector<Case> glowCases() {
    std::vector<Case> cases;
    for (float k : {0.1f, 8.0f}) {
        Scene s = baseScene();
        s.camera.near = 1e-4f;
        s.camera.far = 1e4f;
        s.froxels.far = 1e4f;
        s.froxels.distribution = k;
        s.volumes = {boxFog(s.camera.position, glm::vec3(4.0f), 0.2f, 0.3f, 0.05f)};
        const glm::vec3 forward = glm::normalize(s.camera.target - s.camera.position);
        for (float depth : {0.0f, 2e-4f, 1e-3f}) {
            s.lights.push_back(test::pointLight(s.camera.position + forward * depth, 0.0f, 1e3f));
        }
        Light spot = makeLight(LightType::Spot);
        spot.position = s.camera.position;
        spot.direction = forward;
        spot.intensity = 1e3f;
        s.lights.push_back(spot);
        cases.push_back({"glow at the near plane, k = " + std::to_string(k), s, false});
    }
    return cases;
}

// The camera inside a box of sigma_s = sigma_a = 1e9/m with emission 1e6, a 1e6 sun and a 1e6 point
// light 0.5 m ahead. Neither light reaches the camera; every pixel sees sigma_s A / sigma_t +
// emission / sigma_t = 0.25 + 5e-4 (the closed form, exact in the reference).
Scene opaqueBoxScene() {
    Scene s = baseScene();
    s.camera.position = {0.0f, 1.0f, 0.0f};
    s.camera.target = {0.0f, 1.0f, -1.0f};
    Volume box = boxFog({0.0f, 1.0f, 0.0f}, glm::vec3(10.0f), 0.0f, 1e9f, 1e9f);
    box.medium.emission = glm::vec3(1e6f);
    Light sun = makeLight(LightType::Directional);
    sun.direction = glm::normalize(glm::vec3(0.0f, -1.0f, -0.3f));
    sun.intensity = 1e6f;
    s.volumes = {box};
    s.lights = {sun, test::pointLight({0.0f, 1.0f, -0.5f}, 0.0f, 1e6f)};
    return s;
}
constexpr float kOpaqueClosedForm = 0.25f + 1e6f / 2e9f;

RenderRequest request160x90() {
    RenderRequest r;
    r.width = kWidth;
    r.height = kHeight;
    r.quality = Quality::High;
    return r;
}

const char* qualityName(Quality q) {
    switch (q) {
        case Quality::Low: return "low";
        case Quality::Medium: return "medium";
        case Quality::High: return "high";
        default: return "ultra";
    }
}

double seconds(std::chrono::steady_clock::time_point since) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

float median(const Image& img, int channel) {
    std::vector<float> v;
    for (const glm::vec3& p : img.pixels) v.push_back(p[channel]);
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    return v[v.size() / 2];
}

float maxValue(const Image& img) {
    float m = 0.0f;
    for (const glm::vec3& p : img.pixels) m = std::max({m, p.x, p.y, p.z});
    return m;
}

void expectSane(const Image& img, const Case& c, const char* renderer) {
    ASSERT_EQ(img.pixels.size(), size_t(kWidth) * kHeight) << c.name << " (" << renderer << ")";
    EXPECT_TRUE(allFinite(img)) << c.name << " (" << renderer << ")";
    float lowest = 0.0f;
    for (const glm::vec3& p : img.pixels) lowest = std::min({lowest, p.x, p.y, p.z});
    EXPECT_GE(lowest, 0.0f) << c.name << " (" << renderer << ")";
    if (c.ambientOnly) {
        EXPECT_LE(maxValue(img), kSky.x * (1.0f + 1e-4f)) << c.name << " (" << renderer << "): brighter than the sky";
    }
}

using Renderer = std::function<Image(const Scene&, const RenderRequest&)>;

void checkAll(const Renderer& render, const char* renderer, const std::vector<Case>& cases = extremeCases()) {
    for (const Case& c : cases) {
        const auto start = std::chrono::steady_clock::now();
        const Image img = render(c.scene, request160x90());
        std::printf("%-10s %-42s %7.2f s  max %.4g\n", renderer, c.name.c_str(), seconds(start), maxValue(img));
        expectSane(img, c, renderer);
    }
}

// Every quality: low once left point and spot lights unshadowed by fog (3.8e5 instead of 0.25).
void checkOpaque(const Renderer& render, const char* renderer) {
    const Case c{"opaque box", opaqueBoxScene(), false};
    for (Quality q : {Quality::Low, Quality::Medium, Quality::High, Quality::Ultra}) {
        RenderRequest r = request160x90();
        r.quality = q;
        const Image img = render(c.scene, r);
        expectSane(img, c, renderer);
        const float m = median(img, 1), peak = maxValue(img);
        std::printf("%-10s opaque box, %-6s: median %.4g, max %.4g (closed form %.4g)\n", renderer,
                    qualityName(q), m, peak, kOpaqueClosedForm);
        EXPECT_GT(m, 0.5f * kOpaqueClosedForm) << renderer << " " << qualityName(q);
        EXPECT_LT(m, 2.0f * kOpaqueClosedForm) << renderer << " " << qualityName(q);
        EXPECT_LT(peak, 2.0f * kOpaqueClosedForm) << renderer << " " << qualityName(q);
    }
}

TEST(Extremes, ReferenceRendersEveryCaseFiniteAndBounded) {
    checkAll([](const Scene& s, const RenderRequest& r) { return renderReference(s, r); }, "reference");
}

// The reference's work on unbounded fog under the smallest texture, without timing it: a render whose
// march is cut at 2^14 steps per pixel is the same image as one with the default cap (2^20), so no
// pixel needed more. Before, every step was held to a quarter texture voxel (7.8 um) along 1e4 m of
// fog: each pixel stopped at the 2^20 cap, 8 m into the fog.
TEST(Extremes, ReferenceWorkOnTexturedUnboundedFogIsBounded) {
    for (const Scene& s : texturedUnboundedScenes()) {
        ASSERT_TRUE(s.volumes[0].density_texture->density);
        RenderRequest r = request160x90();
        r.width = 80;
        r.height = 45;
        reference::StepParams capped;
        capped.max_steps = 1 << 14;
        const Image full = renderReference(s, r), cut = reference::render(s, r, capped);
        EXPECT_TRUE(allFinite(full));
        EXPECT_EQ(full.pixels, cut.pixels) << "some pixel took more than 2^14 steps";
    }
}

TEST(Extremes, ReferenceOpaqueBoxIsTheClosedForm) {
    const Image img = renderReference(opaqueBoxScene(), request160x90());
    for (const glm::vec3& p : img.pixels) ASSERT_NEAR(p.y, kOpaqueClosedForm, 1e-4f * kOpaqueClosedForm);
}

TEST(Extremes, CpuFroxelRendersEveryCaseFiniteAndBounded) {
    checkAll([](const Scene& s, const RenderRequest& r) { return renderFroxelCpu(s, r).image; }, "cpu");
}

TEST(Extremes, CpuFroxelGlowNearTheNearPlaneIsFinite) {
    checkAll([](const Scene& s, const RenderRequest& r) { return renderFroxelCpu(s, r).image; }, "cpu", glowCases());
}

TEST(Extremes, CpuFroxelOpaqueBoxAgreesWithTheReference) {
    checkOpaque([](const Scene& s, const RenderRequest& r) { return renderFroxelCpu(s, r).image; }, "cpu");
}

#ifdef BRUME_TEST_GPU
class ExtremesGpu : public test::ValidatedGpuTest {};

TEST_F(ExtremesGpu, RendersEveryCaseFiniteAndBounded) {
    checkAll(
        [this](const Scene& s, const RenderRequest& r) {
            auto out = renderer->render(s, r);
            EXPECT_TRUE(out.ok()) << (out.ok() ? "" : out.error().message);
            return out.ok() ? out.value().image : Image();
        },
        "gpu");
}

TEST_F(ExtremesGpu, GlowNearTheNearPlaneIsFinite) {
    checkAll(
        [this](const Scene& s, const RenderRequest& r) {
            auto out = renderer->render(s, r);
            EXPECT_TRUE(out.ok()) << (out.ok() ? "" : out.error().message);
            return out.ok() ? out.value().image : Image();
        },
        "gpu", glowCases());
}

TEST_F(ExtremesGpu, OpaqueBoxAgreesWithTheReference) {
    checkOpaque(
        [this](const Scene& s, const RenderRequest& r) {
            auto out = renderer->render(s, r);
            EXPECT_TRUE(out.ok()) << (out.ok() ? "" : out.error().message);
            return out.ok() ? out.value().image : Image();
        },
        "gpu");
}
#endif

}  // namespace
}  // namespace brume
