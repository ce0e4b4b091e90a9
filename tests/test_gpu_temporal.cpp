// The GPU temporal pass against its oracle, the CPU froxel renderer's (core/temporal.cpp), frame by
// frame through a sequence with camera motion, a scene edit (a light switched off: the history is
// dropped on both sides) and a restart, on lavapipe with validation on and silent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "core/clusters.h"
#include "core/froxel_frame.h"
#include "core/light_reach.h"
#include "core/media_region.h"
#include "core/render.h"
#include "gpu/gpu_renderer.h"
#include "gpu_test_support.h"

using namespace brume;
using namespace brume::gpu;

namespace {

using test::asImage;

constexpr double kTolerance = 0.01;  // relative mean abs error, as for every GPU-vs-CPU test

Scene temporalScene() {
    Scene s;
    s.camera.position = {0.0f, 1.8f, 7.0f};
    s.camera.target = {0.0f, 1.0f, 0.0f};
    s.camera.far = 60.0f;
    s.ambient = {0.02f, 0.025f, 0.03f};
    s.froxels.tile_px = 8;
    s.froxels.slices = 48;
    s.froxels.far = 30.0f;
    Light spot = makeLight(LightType::Spot);
    spot.position = {1.5f, 4.0f, -1.0f};
    spot.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, 0.1f));
    spot.intensity = 120.0f;
    spot.inner_deg = 12.0f;
    spot.outer_deg = 18.0f;
    Light point = makeLight(LightType::Point);
    point.position = {-2.0f, 2.0f, 1.0f};
    point.intensity = 8.0f;
    s.lights = {spot, point};
    Volume box;
    box.type = VolumeType::Box;
    box.transform.translation = {0.0f, 1.5f, -2.0f};
    box.transform.scale = {10.0f, 3.0f, 12.0f};
    box.edge_fade = 0.3f;
    box.medium.scattering = glm::vec3(0.03f);
    box.medium.absorption = glm::vec3(0.003f);
    box.medium.phase_g = 0.3f;
    Volume height;
    height.type = VolumeType::Height;
    height.falloff = 0.7f;
    height.medium.scattering = glm::vec3(0.02f);
    s.volumes = {box, height};
    Geometry ground;
    ground.type = GeometryType::Plane;
    s.geometry = {ground};
    return s;
}

}  // namespace

TEST(GpuTemporal, MatchesTheCpuFrameByFrameThroughMotionEditsAndRestarts) {
    GpuOptions options;
    options.validation = true;
    auto created = GpuRenderer::create(options);
    ASSERT_TRUE(created.ok()) << created.error().message;
    GpuRenderer& gpu = *created.value();
    FroxelCpuRenderer cpu;

    const Scene base = temporalScene();
    RenderRequest req;
    req.width = 96;
    req.height = 54;
    req.threads = 2;
    double worst = 0.0;
    Image last;
    Scene lastScene;
    for (int n = 0; n < 12; ++n) {
        Scene s = base;
        s.camera = orbitCamera(base.camera, 2.0f * static_cast<float>(n));  // moving from frame 0
        if (n >= 6) s.lights[0].intensity = 0.0f;                          // edit: history dropped
        req.history = n == 9 ? HistoryMode::Restart : HistoryMode::Continue;  // caller's restart
        const FroxelResult c = cpu.render(s, req);
        auto g = gpu.render(s, req, true);
        ASSERT_TRUE(g.ok()) << g.error().message;
        const FroxelVolumes& gv = g.value().volumes;
        ASSERT_EQ(gv.dims, c.volumes.dims);
        const double source = relativeMeanAbsError(asImage(gv.source), asImage(c.volumes.source));
        const double scattering =
            relativeMeanAbsError(asImage(gv.integratedScattering), asImage(c.volumes.integratedScattering));
        const double image = relativeMeanAbsError(g.value().image, c.image);
        EXPECT_TRUE(brume::allFinite(g.value().image));
        EXPECT_LT(source, kTolerance) << "frame " << n;
        EXPECT_LT(scattering, kTolerance) << "frame " << n;
        EXPECT_LT(image, kTolerance) << "frame " << n;
        worst = std::max({worst, source, scattering, image});
        last = g.value().image;
        lastScene = s;
    }
    std::printf("[gpu-vs-cpu temporal] 12 frames, worst relative mean abs error %.2e\n", worst);
    // The history mattered: the last frame without it (a fresh render) differs well beyond the tolerance.
    req.history = HistoryMode::Restart;
    EXPECT_GT(relativeMeanAbsError(last, renderFroxelCpu(lastScene, req).image), 10.0 * worst);
    const std::vector<std::string> messages = gpu.validationMessages();
    EXPECT_TRUE(messages.empty()) << messages.size() << " validation messages, first: " << messages.front();
}

// The history keeps S and sigma_t in two texels, sigma_t's red channel beside S (shaders/shared/
// frame_table.h). Grey media would hide a channel packed in the wrong place, so here the box's
// sigma_t is 4:2:1 and its albedo differs per channel; the resolved S and sigma_t read back, the
// integrated scattering and the image follow the CPU through frames in motion (temporal pass) and at
// rest (integrate_rest).
using GpuTemporalChannels = test::ValidatedGpuTest;  // its TearDown fails on any validation message

TEST_F(GpuTemporalChannels, ColouredMediaKeepEveryChannelThroughTheHistory) {
    GpuRenderer& gpu = *renderer;
    FroxelCpuRenderer cpu;
    Scene base = temporalScene();
    base.volumes[0].medium.scattering = {0.05f, 0.03f, 0.018f};
    base.volumes[0].medium.absorption = {0.03f, 0.01f, 0.002f};
    base.volumes[1].medium.scattering = {0.004f, 0.012f, 0.02f};
    RenderRequest req;
    req.width = 96;
    req.height = 54;
    req.threads = 2;
    req.history = HistoryMode::Continue;
    double worst = 0.0;
    for (int n = 0; n < 10; ++n) {
        Scene s = base;
        s.camera = orbitCamera(base.camera, 3.0f * static_cast<float>(std::min(n, 5)));  // rests from frame 6
        const FroxelResult c = cpu.render(s, req);
        auto g = gpu.render(s, req, true);
        ASSERT_TRUE(g.ok()) << g.error().message;
        const FroxelVolumes& gv = g.value().volumes;
        ASSERT_EQ(gv.dims, c.volumes.dims);
        const double errors[] = {
            relativeMeanAbsError(asImage(gv.source), asImage(c.volumes.source)),
            relativeMeanAbsError(asImage(gv.mediaExtinction), asImage(c.volumes.mediaExtinction)),
            relativeMeanAbsError(asImage(gv.integratedScattering), asImage(c.volumes.integratedScattering)),
            relativeMeanAbsError(g.value().image, c.image)};
        for (double e : errors) EXPECT_LT(e, kTolerance) << "frame " << n;
        for (double e : errors) worst = std::max(worst, e);
        // Most froxels' sigma_t has three distinct channels (a third apart at least), and the alphas the
        // layout leaves out read back as 0.
        size_t coloured = 0;
        for (size_t i = 0; i < gv.mediaExtinction.size(); ++i) {
            const glm::vec4 e = gv.mediaExtinction[i];
            const float lo = std::min({e.r, e.g, e.b}), hi = std::max({e.r, e.g, e.b});
            if (hi > 0.0f && hi - lo > hi / 3.0f) ++coloured;
            ASSERT_EQ(e.a, 0.0f) << "froxel " << i;
            ASSERT_EQ(gv.source[i].a, 0.0f) << "froxel " << i;
        }
        EXPECT_GT(coloured, gv.mediaExtinction.size() / 2) << "frame " << n;
    }
    std::printf("[gpu-vs-cpu temporal] coloured media, 10 frames: worst relative mean abs error %.2e\n", worst);
}

TEST(GpuTemporal, FramesOptionAccumulatesLikeTheCpu) {
    GpuOptions options;
    options.validation = true;
    auto created = GpuRenderer::create(options);
    ASSERT_TRUE(created.ok()) << created.error().message;
    const Scene scene = temporalScene();
    RenderRequest req;
    req.width = 96;
    req.height = 54;
    req.threads = 2;
    req.frames = 8;
    const FroxelResult c = renderFroxelCpu(scene, req);
    auto g = created.value()->render(scene, req, true);
    ASSERT_TRUE(g.ok()) << g.error().message;
    const double image = relativeMeanAbsError(g.value().image, c.image);
    req.frames = 1;
    const double versusOneFrame = relativeMeanAbsError(g.value().image, renderFroxelCpu(scene, req).image);
    std::printf("[gpu-vs-cpu temporal] 8 frames: image %.2e (vs 1 frame: %.2e)\n", image, versusOneFrame);
    EXPECT_LT(image, kTolerance);
    EXPECT_GT(versusOneFrame, 10.0 * image);  // the 8 frames did accumulate something else than frame 1
    const std::vector<std::string> messages = created.value()->validationMessages();
    EXPECT_TRUE(messages.empty()) << messages.size() << " validation messages, first: " << messages.front();
}

namespace {

// temporalScene's box alone (the height fog would make the media region the whole grid), smaller,
// centred at `at`.
Scene regionScene(glm::vec3 at) {
    Scene s = temporalScene();
    s.volumes.pop_back();
    s.volumes[0].transform.translation = at;
    s.volumes[0].transform.scale = {2.0f, 1.6f, 2.0f};
    return s;
}

bool sameBytes(const std::vector<glm::vec4>& a, const std::vector<glm::vec4>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec4)) == 0;
}

}  // namespace

// The temporal and integrate passes run over the temporal region only (core/media_region.h
// temporalFroxelRegion) and write the rest by clears. Through a box that rests, moves out of its
// region to the other side of the view (the key drops the history; the side written next still holds
// the old box), rests, the camera orbiting, and the box moving back: every froxel volume and the image
// are byte-identical to the same renderer over the whole grid; outside the region the GPU holds
// exactly what the CPU's pass over the whole grid writes (S = sigma_t = 0, and the CPU's history is
// 0 there too: the old box's history does not linger), and in front of it scattering 0 and
// transmittance 1.
TEST(GpuTemporal, RegionEqualsTheWholeGridAndTheHistoryOfAMovedVolumeDoesNotLinger) {
    GpuOptions options;
    options.validation = true;
    auto region = GpuRenderer::create(options);
    ASSERT_TRUE(region.ok()) << region.error().message;
    options.froxelRegions = false;
    auto whole = GpuRenderer::create(options);
    ASSERT_TRUE(whole.ok()) << whole.error().message;
    CpuHistory cpuHistory;

    RenderRequest req;
    req.width = 160;
    req.height = 90;
    req.threads = 2;
    req.history = HistoryMode::Continue;
    const glm::vec3 left(-2.6f, 1.2f, -1.0f), right(2.6f, 1.2f, 0.0f);
    size_t outside = 0;
    for (int n = 0; n < 14; ++n) {
        const glm::vec3 at = n < 4 || n >= 11 ? left : right;
        Scene s = regionScene(at);
        if (n >= 7) s.camera = orbitCamera(s.camera, 1.5f * static_cast<float>(n - 6));
        auto g = region.value()->render(s, req, true);
        ASSERT_TRUE(g.ok()) << g.error().message;
        auto w = whole.value()->render(s, req, true);
        ASSERT_TRUE(w.ok()) << w.error().message;
        const FroxelResult c = renderFroxelFrameCpu(s, req, cpuHistory);
        const FroxelVolumes& gv = g.value().volumes;
        const FroxelVolumes& wv = w.value().volumes;
        EXPECT_TRUE(sameBytes(gv.source, wv.source)) << "frame " << n;
        EXPECT_TRUE(sameBytes(gv.mediaExtinction, wv.mediaExtinction)) << "frame " << n;
        EXPECT_TRUE(sameBytes(gv.integratedScattering, wv.integratedScattering)) << "frame " << n;
        EXPECT_TRUE(sameBytes(gv.integratedTransmittance, wv.integratedTransmittance)) << "frame " << n;
        const Image& gi = g.value().image;
        const Image& wi = w.value().image;
        ASSERT_EQ(gi.pixels.size(), wi.pixels.size());
        EXPECT_EQ(std::memcmp(gi.pixels.data(), wi.pixels.data(), gi.pixels.size() * sizeof(glm::vec3)), 0)
            << "frame " << n;

        const glm::ivec3 dims = gv.dims;
        const FroxelRegion t = temporalFroxelRegion(mediaFroxelRegion(compileScene(s), gv.frame), dims);
        ASSERT_FALSE(t.empty()) << "frame " << n;
        EXPECT_LT(t.froxels() * 3, int64_t(dims.x) * dims.y * dims.z) << "frame " << n;  // a small part
        const HistoryVolume& ch = cpuHistory.pair[static_cast<size_t>(cpuHistory.state.lastWritten)];
        int bad = 0;
        for (int z = 0; z < dims.z; ++z)
            for (int y = 0; y < dims.y; ++y)
                for (int x = 0; x < dims.x; ++x) {
                    const glm::ivec3 f(x, y, z);
                    const size_t i = (size_t(z) * size_t(dims.y) + size_t(y)) * size_t(dims.x) + size_t(x);
                    const bool column = glm::all(glm::greaterThanEqual(glm::ivec2(f), glm::ivec2(t.lo))) &&
                                        glm::all(glm::lessThan(glm::ivec2(f), glm::ivec2(t.hi)));
                    const bool in = column && z >= t.lo.z && z < t.hi.z;
                    if (!in) {
                        ++outside;
                        const glm::vec4 zero(0.0f);
                        bad += gv.source[i] != zero || gv.mediaExtinction[i] != zero;
                        bad += c.volumes.source[i] != zero || c.volumes.mediaExtinction[i] != zero;
                        bad += ch.source[i] != zero || ch.extinction[i] != zero;
                    }
                    if (!column || z < t.lo.z) {  // nothing in front: what empty froxels integrate to
                        const glm::vec4 one(1.0f, 1.0f, 1.0f, 0.0f);
                        bad += gv.integratedScattering[i] != glm::vec4(0.0f) || gv.integratedTransmittance[i] != one;
                        bad += c.volumes.integratedScattering[i] != glm::vec4(0.0f) ||
                               c.volumes.integratedTransmittance[i] != one;
                    }
                }
        EXPECT_EQ(bad, 0) << "frame " << n;
        // Inside, the GPU agrees with the CPU as everywhere else (kTolerance).
        EXPECT_LT(relativeMeanAbsError(gi, c.image), kTolerance) << "frame " << n;
    }
    EXPECT_GT(outside, 0u);
    for (auto* r : {region.value().get(), whole.value().get()}) {
        const std::vector<std::string> messages = r->validationMessages();
        EXPECT_TRUE(messages.empty()) << messages.size() << " validation messages, first: " << messages.front();
    }
}

// The shadow volume pass computes only the cells some reader needs (core/media_region.h
// shadowCellRegion). The region renderer fills its fog transmittance volume with NaN before every
// frame (GpuOptions::poisonShadowVolume), so a light pass reading a cell not written this frame would
// get a NaN source, or take the exact fallback where the whole grid's blend was trusted: either way its
// froxel volumes and image would differ from the whole-grid renderer's (froxelRegions off: every cell
// of every listed layer written). With a sun and the two local lights, at high and low (reductions 2
// and 4), a box resting, moved to the other side, partly off screen, orbited, and a wide box that a
// short-ranged point light reaches in part: byte-identical. The local lights' layers are computed
// around the froxels whose clusters list them only (core/light_reach.h listedFroxelRegions): fewer
// cells than the media region's in the last frame.
TEST(GpuTemporal, ShadowVolumeRegionWritesEveryCellItsReadersRead) {
    test::PoisonedRegionAndWholeGrid pair;
    pair.create();
    if (HasFatalFailure()) return;

    auto finite = [](const std::vector<glm::vec4>& v) {
        return std::all_of(v.begin(), v.end(), [](const glm::vec4& x) {
            return std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z) && std::isfinite(x.w);
        });
    };
    int smallerLayers = 0;  // local lights' layers with fewer cells than the media region's
    for (Quality q : {Quality::High, Quality::Low}) {
        RenderRequest req;
        req.width = 160;
        req.height = 90;
        req.quality = q;
        req.history = HistoryMode::Continue;
        const std::vector<glm::vec3> places = {{-2.6f, 1.2f, -1.0f}, {-2.6f, 1.2f, -1.0f}, {2.6f, 1.2f, 0.0f},
                                               {5.2f, 0.8f, 1.0f}, {0.0f, 1.5f, -6.0f}};
        for (size_t n = 0; n < places.size() + 2; ++n) {
            Scene s = regionScene(places[std::min(n, places.size() - 1)]);
            Light sun = makeLight(LightType::Directional);
            sun.direction = glm::normalize(glm::vec3(0.5f, -0.8f, -0.3f));
            sun.intensity = 2.0f;
            s.lights.push_back(sun);
            if (n >= places.size()) s.camera = orbitCamera(s.camera, 12.0f);
            const bool wide = n == places.size() + 1;  // a wide box the point light's short range reaches in part
            if (wide) {
                s.volumes[0].transform.translation = {0.0f, 1.2f, -1.0f};
                s.volumes[0].transform.scale = {9.0f, 3.0f, 9.0f};
                s.lights[1].range = 3.0f;
            }
            const std::string what = std::string(q == Quality::High ? "high" : "low") + " frame " + std::to_string(n);
            auto g = pair.region->render(s, req, true);
            ASSERT_TRUE(g.ok()) << g.error().message;
            auto w = pair.whole->render(s, req, true);
            ASSERT_TRUE(w.ok()) << w.error().message;
            const FroxelVolumes& gv = g.value().volumes;
            const FroxelVolumes& wv = w.value().volumes;
            EXPECT_TRUE(finite(gv.source)) << what;
            EXPECT_TRUE(sameBytes(gv.source, wv.source)) << what;
            EXPECT_TRUE(sameBytes(gv.integratedScattering, wv.integratedScattering)) << what;
            const Image& gi = g.value().image;
            const Image& wi = w.value().image;
            ASSERT_EQ(gi.pixels.size(), wi.pixels.size());
            EXPECT_EQ(std::memcmp(gi.pixels.data(), wi.pixels.data(), gi.pixels.size() * sizeof(glm::vec3)), 0) << what;
            // The pass did skip cells: the region is a small part of the volume, and the box is lit.
            const FroxelRegion cells = shadowCellRegion(mediaFroxelRegion(compileScene(s), gv.frame), gv.frame, true);
            const glm::ivec3 all = shd::shadowVolumeDims(gv.dims, gv.frame.shadowReduction);
            if (!wide) {
                EXPECT_LT(cells.froxels() * 3, int64_t(all.x) * all.y * all.z) << what;
            }
            EXPECT_GT(g.value().litFroxels, 0u) << what;
            const CompiledScene cs = compileScene(s);
            const std::vector<FroxelRegion> listed = listedFroxelRegions(
                buildLightClusters(cs, gv.frame), cs.lights.size(), mediaFroxelRegion(cs, gv.frame));
            for (size_t i = 0; i < listed.size(); ++i)
                if (cs.lights[i].kind.x != shd::LIGHT_DIRECTIONAL && !listed[i].empty() &&
                    shadowCellRegion(listed[i], gv.frame, true).froxels() < cells.froxels())
                    ++smallerLayers;
        }
    }
    EXPECT_GT(smallerLayers, 0);
    pair.expectNoValidationMessages();
}

// The light pass writes S and sigma_t over the whole temporal region, the media region's shell of
// media-free froxels included (light_body.glsl), which is all the temporal and integrate passes read:
// the frame no longer clears them to 0 first. The region renderer fills them with 1 before every
// frame that reads no volumes back (GpuOptions::poisonSource); through a box at rest, moved, and the
// camera orbiting, at `high` and `low`, its images equal the whole grid renderer's byte for byte.
TEST(GpuTemporal, TheLightPassWritesEverySourceTheTemporalAndIntegratePassesRead) {
    test::PoisonedRegionAndWholeGrid pair;
    pair.create();
    if (HasFatalFailure()) return;
    for (Quality q : {Quality::High, Quality::Low}) {
        RenderRequest req;
        req.width = 160;
        req.height = 90;
        req.quality = q;
        const std::vector<glm::vec3> places = {{-2.6f, 1.2f, -1.0f}, {-2.6f, 1.2f, -1.0f}, {2.6f, 1.2f, 0.0f}};
        for (size_t n = 0; n < places.size() + 2; ++n) {
            Scene s = regionScene(places[std::min(n, places.size() - 1)]);
            if (n >= places.size()) s.camera = orbitCamera(s.camera, 6.0f * static_cast<float>(n + 1 - places.size()));
            req.history = n == 0 ? HistoryMode::Restart : HistoryMode::Continue;
            const std::string what = std::string(q == Quality::High ? "high" : "low") + " frame " + std::to_string(n);
            auto g = pair.region->render(s, req);
            ASSERT_TRUE(g.ok()) << g.error().message;
            auto w = pair.whole->render(s, req);
            ASSERT_TRUE(w.ok()) << w.error().message;
            const Image& gi = g.value().image;
            const Image& wi = w.value().image;
            EXPECT_TRUE(brume::allFinite(gi)) << what;
            ASSERT_EQ(gi.pixels.size(), wi.pixels.size());
            EXPECT_EQ(std::memcmp(gi.pixels.data(), wi.pixels.data(), gi.pixels.size() * sizeof(glm::vec3)), 0) << what;
        }
    }
    pair.expectNoValidationMessages();
}

namespace {

bool ranPass(const GpuRender& r, const char* name) {
    return std::any_of(r.passes.begin(), r.passes.end(), [&](const PassTiming& p) { return p.name == name; });
}

}  // namespace

// RenderRequest::reuseSurfaces (the editor's): the geometry and distant fog passes are left out while
// everything they read stays the same (the view at rest), and the image equals, bit for bit, the one
// a renderer that redraws them every frame makes, through rest, a light edit, a camera move, and a
// resize there and back (a parked set of screen images: their contents are another frame's).
TEST(GpuTemporal, SurfacesKeptAtRestRenderAsRedrawnThroughEditsMovesAndResizes) {
    GpuOptions options;
    options.validation = true;
    auto keeping = GpuRenderer::create(options);
    ASSERT_TRUE(keeping.ok()) << keeping.error().message;
    auto redrawing = GpuRenderer::create(options);
    ASSERT_TRUE(redrawing.ok()) << redrawing.error().message;
    Scene s = temporalScene();
    struct Step {
        const char* what;
        glm::ivec2 size;
        bool kept;  // expected: the surfaces of the previous frame are kept
    };
    const std::vector<Step> steps = {
        {"first frame", {96, 54}, false}, {"at rest", {96, 54}, true},     {"at rest", {96, 54}, true},
        {"light edit", {96, 54}, false},  {"at rest", {96, 54}, true},     {"camera move", {96, 54}, false},
        {"smaller", {64, 36}, false},     {"back to size", {96, 54}, false}, {"at rest", {96, 54}, true},
    };
    for (size_t n = 0; n < steps.size(); ++n) {
        const std::string what = steps[n].what;
        if (what == "light edit") s.lights[1].intensity *= 2.0f;
        if (what == "camera move") s.camera.position.x += 0.3f;
        RenderRequest request;
        request.width = steps[n].size.x;
        request.height = steps[n].size.y;
        request.quality = Quality::High;
        request.history = n == 0 ? HistoryMode::Restart : HistoryMode::Continue;
        RenderRequest reusing = request;
        reusing.reuseSurfaces = true;
        auto a = keeping.value()->render(s, reusing);
        ASSERT_TRUE(a.ok()) << a.error().message;
        auto b = redrawing.value()->render(s, request);
        ASSERT_TRUE(b.ok()) << b.error().message;
        EXPECT_TRUE(ranPass(b.value(), "geometry") && ranPass(b.value(), "distant fog")) << "step " << n;
        EXPECT_EQ(!ranPass(a.value(), "geometry"), steps[n].kept) << "step " << n << " (" << what << ")";
        EXPECT_EQ(!ranPass(a.value(), "distant fog"), steps[n].kept) << "step " << n << " (" << what << ")";
        const Image& x = a.value().image;
        const Image& y = b.value().image;
        ASSERT_EQ(x.pixels.size(), y.pixels.size());
        float largest = 0.0f;
        for (size_t i = 0; i < x.pixels.size(); ++i) largest = std::max(largest, glm::length(x.pixels[i] - y.pixels[i]));
        EXPECT_EQ(largest, 0.0f) << "step " << n << " (" << what << ")";
    }
}

namespace {

// A renderer that skips the hidden froxels (the default) and one that computes them all
// (GpuOptions::skipHiddenFroxels = false), both validated; when asked, the integrated scattering
// poisoned where unstored (GpuOptions::poisonIntegrated), and the skipping renderer's fog transmittance
// volume filled with NaN before each frame (GpuOptions::poisonShadowVolume: the shadow volume pass
// skips the cells behind the froxels the frame computes, and a light pass reading one would show).
// Stops the test on an error (HasFatalFailure()).
struct SkippingAndFull {
    std::unique_ptr<GpuRenderer> skipping, full;

    void create(bool poison) {
        GpuOptions options;
        options.validation = true;
        options.poisonIntegrated = poison;
        options.poisonShadowVolume = poison;
        auto a = GpuRenderer::create(options);
        ASSERT_TRUE(a.ok()) << a.error().message;
        skipping = std::move(a.value());
        options.poisonShadowVolume = false;
        options.skipHiddenFroxels = false;
        auto b = GpuRenderer::create(options);
        ASSERT_TRUE(b.ok()) << b.error().message;
        full = std::move(b.value());
    }
    void expectNoValidationMessages() const {
        for (const GpuRenderer* r : {skipping.get(), full.get()}) {
            const std::vector<std::string> messages = r->validationMessages();
            EXPECT_TRUE(messages.empty()) << messages.size() << " validation messages, first: " << messages.front();
        }
    }
};

}  // namespace

// The GPU lights and resolves only the froxels in front of each column's deepest stored integrated
// entry (shaders/column_entries.glsl, GpuOptions::skipHiddenFroxels), and computes only the shadow
// volume's cells those froxels read (shadow_volume.comp). The image at rest must not change: each
// frame of a rest equals, pixel for pixel, the frame of a renderer that computes every froxel (both
// with the integrated scattering poisoned where unstored, the skipping one's shadow volume too). Once
// the view moves, a froxel the motion uncovers has no history (the previous frame skipped it): those
// frames differ from the full renderer's a little, and stay within the GPU-vs-CPU tolerance of the CPU
// froxel renderer, which computes every froxel. Scenes: ground, sky, a sun and a glowing point light
// (temporalScene), the same with the camera inside the light's glow, and with a wall between the
// camera and the light; `low` and `high`; an odd size (partial last columns).
TEST(GpuTemporal, RestFramesThatSkipHiddenFroxelsEqualThoseThatComputeThemAll) {
    SkippingAndFull renderers;
    renderers.create(/*poison=*/true);
    if (HasFatalFailure()) return;
    Scene outside = temporalScene();
    outside.froxels.tile_px.reset();  // the presets' tiles and slices
    outside.froxels.slices.reset();
    // A sun too: its fog shadows read the shadow volume at every preset (the local lights' only at some).
    Light sun = makeLight(LightType::Directional);
    sun.direction = glm::normalize(glm::vec3(0.5f, -0.8f, -0.3f));
    sun.intensity = 2.0f;
    outside.lights.push_back(sun);
    Scene inside = outside;
    inside.lights[1].position = inside.camera.position + glm::vec3(0.05f, -0.05f, -0.1f);
    // The glowing light 0.6 m behind a wall, its glow ball (~0.9 m at `high`) poking through: the glow's
    // pixels on the wall read the resolved sigma_t at the light's froxel, behind the wall's depth
    // tiles' entries; the push constants' everywhere-entries (the glow's) keep it resolved.
    Scene walled = outside;
    Geometry wall;
    wall.type = GeometryType::Box;
    wall.transform.translation = outside.lights[1].position + glm::vec3(0.0f, 0.0f, 0.6f);
    wall.transform.scale = {3.0f, 3.0f, 0.1f};
    walled.geometry.push_back(wall);
    double worstMotion = 0.0, worstCpu = 0.0;
    for (const Scene* base : {&outside, &inside, &walled})
        for (Quality q : {Quality::Low, Quality::High}) {
            const std::string what = std::string(toString(q)) + (base == &inside   ? ", camera in a glow"
                                                                 : base == &walled ? ", light behind a wall"
                                                                                   : "");
            FroxelCpuRenderer cpu;
            RenderRequest req;
            req.width = 133;
            req.height = 71;
            req.quality = q;
            req.threads = 2;
            for (int n = 0; n < 9; ++n) {
                // Frames 0-5 rest, 6-8 orbit.
                Scene s = *base;
                s.camera = orbitCamera(base->camera, 2.0f * static_cast<float>(std::max(n - 5, 0)));
                req.history = n == 0 ? HistoryMode::Restart : HistoryMode::Continue;
                auto a = renderers.skipping->render(s, req);
                auto b = renderers.full->render(s, req);
                ASSERT_TRUE(a.ok()) << a.error().message;
                ASSERT_TRUE(b.ok()) << b.error().message;
                const Image& ai = a.value().image;
                const Image& bi = b.value().image;
                EXPECT_TRUE(brume::allFinite(ai)) << what << ", frame " << n;
                if (n <= 5) {
                    size_t differ = 0;
                    for (size_t k = 0; k < bi.pixels.size(); ++k) differ += ai.pixels[k] != bi.pixels[k] ? 1 : 0;
                    EXPECT_EQ(differ, 0u) << what << ", frame " << n << ": pixels that differ";
                    // The light pass counts the froxels it lit: fewer, it skips the hidden ones.
                    EXPECT_LT(a.value().litFroxels, b.value().litFroxels) << what << ", frame " << n;
                } else {
                    const double motion = relativeMeanAbsError(ai, bi);
                    const double againstCpu = relativeMeanAbsError(ai, cpu.render(s, req).image);
                    EXPECT_LT(motion, 1e-5) << what << ", frame " << n;
                    EXPECT_LT(againstCpu, kTolerance) << what << ", frame " << n;
                    worstMotion = std::max(worstMotion, motion);
                    worstCpu = std::max(worstCpu, againstCpu);
                }
                if (n <= 5) cpu.render(s, req);  // the CPU's history follows the same frames
            }
        }
    std::printf("[skip hidden] in motion after a rest: worst relative mean abs error %.2e against the full "
                "renderer, %.2e against the CPU\n", worstMotion, worstCpu);
    renderers.expectNoValidationMessages();
}

// A frame that computes every froxel (the read-back volumes, a debug view) after frames that skipped
// the hidden ones: those froxels' history was written by an older frame, at another view where the
// camera moved since, and must not be blended in (integrate_rest rejects the history past the previous
// frame's walk end, shaders/integrate.comp). Rest at one view, orbit away, rest again, then read the
// volumes back: the resolved S must be that of a renderer that computed every froxel all along, up to
// the samples' spread (the skipped froxels take this frame's sample alone, the full renderer's their
// mean), and far from the ghost of the first view.
TEST(GpuTemporal, AFrameThatComputesEveryFroxelReadsNoHistoryFromAnotherView) {
    SkippingAndFull renderers;
    renderers.create(/*poison=*/false);
    if (HasFatalFailure()) return;
    Scene base = temporalScene();
    RenderRequest req;
    req.width = 96;
    req.height = 54;
    req.threads = 2;
    GpuRender a, b;
    for (int n = 0; n < 10; ++n) {
        Scene s = base;
        // Frames 0-2 rest, 3-5 orbit 12 degrees a frame, 6-9 rest; frame 9 reads the volumes back.
        s.camera = orbitCamera(base.camera, 12.0f * static_cast<float>(std::clamp(n - 2, 0, 3)));
        req.history = n == 0 ? HistoryMode::Restart : HistoryMode::Continue;
        auto ra = renderers.skipping->render(s, req, n == 9);
        auto rb = renderers.full->render(s, req, n == 9);
        ASSERT_TRUE(ra.ok()) << ra.error().message;
        ASSERT_TRUE(rb.ok()) << rb.error().message;
        a = std::move(ra.value());
        b = std::move(rb.value());
    }
    const double source = relativeMeanAbsError(asImage(a.volumes.source), asImage(b.volumes.source));
    std::printf("[skip hidden] read-back after skipping frames: resolved S %.2e from the full renderer's\n", source);
    EXPECT_LT(source, 2e-3);
    EXPECT_TRUE(brume::allFinite(a.image));
    renderers.expectNoValidationMessages();
}
