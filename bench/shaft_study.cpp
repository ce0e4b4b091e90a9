// Where the light-shaft error of the froxel renderers comes from (docs/shadows.md, "Shaft error"):
// the sun shaft (1.5 and 2.5 m gaps) and the spot shaft scenes of tests/test_sun_shadow.cpp and
// tests/test_local_shadow.cpp, rendered by the CPU froxel renderer against the reference while one
// factor at a time moves away from `high`: froxel tile, depth slices, transmittance-volume
// reduction, temporal frames (jittered samples averaged). Prints one table row per setting.
// Not a test: it takes minutes; run it by hand (build/bench/shaft_study).
#include <cstdio>
#include <string>

#include "core/render.h"

using namespace brume;

namespace {

Geometry slab(glm::vec3 center, glm::vec3 size) {
    Geometry g;
    g.type = GeometryType::Box;
    g.transform.translation = center;
    g.transform.scale = size;
    g.albedo = glm::vec3(0.3f);
    return g;
}

Volume haze() {
    Volume v;
    v.type = VolumeType::Height;
    v.base_height = 0.0f;
    v.falloff = 0.4f;
    v.medium.scattering = glm::vec3(0.15f);
    v.medium.absorption = glm::vec3(0.01f);
    return v;
}

Geometry ground(float albedo) {
    Geometry g;
    g.type = GeometryType::Plane;
    g.albedo = glm::vec3(albedo);
    return g;
}

// tests/test_sun_shadow.cpp shaftScene with the gap as a parameter.
Scene sunShaft(float gap) {
    Scene s;
    s.camera.position = {7.0f, 1.5f, 0.0f};
    s.camera.target = {0.0f, 1.2f, 0.0f};
    s.camera.far = 40.0f;
    s.froxels.far = 30.0f;
    s.ambient = glm::vec3(0.03f);
    Light sun = makeLight(LightType::Directional);
    sun.direction = glm::normalize(glm::vec3(0.0f, -1.0f, 0.35f));
    sun.intensity = 3.0f;
    sun.shadows = true;
    s.lights = {sun};
    s.volumes = {haze()};
    const float c = 6.0f + 0.5f * gap;
    s.geometry = {ground(0.5f), slab({0.0f, 4.0f, -c}, {30.0f, 0.4f, 12.0f}), slab({0.0f, 4.0f, c}, {30.0f, 0.4f, 12.0f})};
    return s;
}

// tests/test_local_shadow.cpp spotShaft.
Scene spotShaft() {
    Scene s;
    s.camera.position = {0.0f, 1.5f, 8.0f};
    s.camera.target = {0.0f, 1.3f, 0.0f};
    s.camera.fov_y_deg = 55.0f;
    s.camera.far = 40.0f;
    s.froxels.far = 30.0f;
    s.ambient = glm::vec3(0.01f);
    Light spot = makeLight(LightType::Spot);
    spot.position = {0.0f, 6.0f, 0.0f};
    spot.direction = {0.0f, -1.0f, 0.0f};
    spot.outer_deg = 40.0f;
    spot.inner_deg = 32.0f;
    spot.intensity = 150.0f;
    spot.shadows = true;
    s.lights = {spot};
    s.volumes = {haze()};
    s.geometry = {ground(0.5f), slab({-4.75f, 4.0f, 0.0f}, {8.0f, 0.4f, 12.0f}),
                  slab({4.75f, 4.0f, 0.0f}, {8.0f, 0.4f, 12.0f})};
    return s;
}

void row(const char* scene, const std::string& setting, const Scene& s, RenderRequest req, const Image& ref) {
    const double err = relativeMeanAbsError(renderFroxelCpu(s, req).image, ref);
    std::printf("| %s | %s | %.2f%% |\n", scene, setting.c_str(), 100.0 * err);
    std::fflush(stdout);
}

void study(const char* name, const Scene& base) {
    RenderRequest req;
    req.width = 160;
    req.height = 90;
    req.quality = Quality::High;
    req.threads = 2;
    const Image ref = renderReference(base, req);
    row(name, "high", base, req, ref);
    for (int tile : {4, 2, 1}) {
        Scene s = base;
        s.froxels.tile_px = tile;
        row(name, "tile " + std::to_string(tile) + " px", s, req, ref);
    }
    for (int slices : {192, 384}) {
        Scene s = base;
        s.froxels.slices = slices;
        row(name, std::to_string(slices) + " slices", s, req, ref);
    }
    {
        Scene s = base;
        s.froxels.tile_px = 2;
        s.froxels.slices = 384;
        row(name, "tile 2 px, 384 slices", s, req, ref);
    }
    {
        // The same 8 px tiles on a 2x larger image: twice the froxel columns over the same view.
        RenderRequest big = req;
        big.width *= 2;
        big.height *= 2;
        row(name, "320x180 image (its own reference)", base, big, renderReference(base, big));
    }
    RenderRequest r1 = req;
    r1.shadowReduction = 1;
    row(name, "shadow reduction 1", base, r1, ref);
    for (int frames : {8, 32}) {
        Scene s = base;
        s.temporal.enabled = true;
        RenderRequest rf = req;
        rf.frames = frames;
        row(name, std::to_string(frames) + " temporal frames", s, rf, ref);
    }
}

}  // namespace

int main(int argc, char** argv) {
    const std::string only = argc > 1 ? argv[1] : "";
    std::printf("| scene | setting | error |\n|---|---|---|\n");
    if (only.empty() || only == "sun15") study("sun, 1.5 m gap", sunShaft(1.5f));
    if (only.empty() || only == "spot") study("spot, 1.5 m gap", spotShaft());
    if (only.empty() || only == "sun25") study("sun, 2.5 m gap", sunShaft(2.5f));
    return 0;
}
