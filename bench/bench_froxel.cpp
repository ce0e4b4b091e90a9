// Time of the CPU froxel renderer per quality preset and image width, on a box and height
// fog scene close to the one tests/test_froxel_renderer.cpp compares with the reference; and of the
// sun shadow map's host ray cast, which every camera move repeats (core/sun_shadow.cpp).
// Run: bench_froxel --benchmark_filter=... ; arguments are (quality, width) and (resolution, culled).
#include <benchmark/benchmark.h>

#include <cstdio>

#include "core/froxel_frame.h"
#include "core/geometry.h"
#include "core/render.h"
#include "core/sun_shadow.h"
#include "io/scene_json.h"

namespace {

using namespace brume;

Scene benchScene() {
    Scene s;
    s.camera.position = {0.0f, 1.8f, 7.0f};
    s.camera.target = {0.0f, 1.0f, 0.0f};
    s.camera.fov_y_deg = 55.0f;
    s.camera.far = 60.0f;
    s.ambient = {0.02f, 0.025f, 0.03f};
    Light sun = makeLight(LightType::Directional);
    sun.direction = glm::normalize(glm::vec3(0.2f, -0.9f, 0.45f));
    Light point = makeLight(LightType::Point);
    point.position = {-3.0f, 4.5f, 0.0f};
    s.lights = {sun, point};
    Volume box;
    box.type = VolumeType::Box;
    box.transform.translation = {0.0f, 1.5f, -3.0f};
    box.transform.scale = {10.0f, 3.0f, 10.0f};
    box.edge_fade = 0.3f;
    Volume ground;
    ground.type = VolumeType::Height;
    ground.medium.scattering = glm::vec3(0.02f);
    s.volumes = {box, ground};
    Geometry plane;
    plane.albedo = glm::vec3(0.05f);
    s.geometry = {plane};
    return s;
}

void BM_FroxelCpu(benchmark::State& state) {
    const Scene scene = benchScene();
    RenderRequest req;
    req.quality = static_cast<Quality>(state.range(0));
    req.width = static_cast<int>(state.range(1));
    req.height = req.width * 9 / 16;
    size_t froxels = 0;
    for (auto _ : state) {
        FroxelResult r = renderFroxelCpu(scene, req);
        froxels = r.volumes.source.size();
        benchmark::DoNotOptimize(r.image.pixels.data());
    }
    state.counters["froxels"] = static_cast<double>(froxels);
    state.SetLabel(toString(req.quality));
}

BENCHMARK(BM_FroxelCpu)
    ->ArgsProduct({{0, 1, 2, 3}, {160, 640}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The default scene's sun shadow map at 512 (`low`) and 1024 texels, each texel's rays against the
// primitives over it (1) or against every primitive (0): the same map (docs/performance.md, "sunmap").
void BM_SunShadowMap(benchmark::State& state) {
    Result<Scene> loaded = loadSceneFile(BRUME_SOURCE_DIR "/assets/scenes/default.json");
    if (!loaded) {
        state.SkipWithError(loaded.error().message.c_str());
        return;
    }
    const Scene& scene = loaded.value();
    const CompiledScene cs = compileScene(scene);
    shd::FrameUniforms frame =
        makeFrameUniforms(scene, cs, 1280, 720, resolveFroxelSettings(scene, Quality::High), glm::vec3(0.5f));
    applySunShadowSettings(frame, cs);
    const GeometrySet geometry(scene.geometry);
    const int n = static_cast<int>(state.range(0));
    const bool culled = state.range(1) != 0;
    for (auto _ : state) {
        SunShadowMap map = buildSunShadowMap(cs, geometry, frame, n, 0, culled);
        benchmark::DoNotOptimize(map.depth.data());
    }
    state.SetLabel(culled ? "primitives over each texel" : "every primitive");
}

BENCHMARK(BM_SunShadowMap)->ArgsProduct({{512, 1024}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
