// Where the light-shaft error of the froxel renderers comes from (docs/shadows.md, "Shaft error"):
// the sun shaft (1.5 and 2.5 m gaps) and the spot shaft scenes of tests/test_sun_shadow.cpp and
// tests/test_local_shadow.cpp, rendered by the CPU froxel renderer against the reference while one
// factor at a time moves away from `high`: froxel tile, depth slices, transmittance-volume
// reduction, temporal frames (jittered samples averaged). Prints one table row per setting.
// Not a test: it takes minutes; run it by hand (build/bench/shaft_study).
#include <cstdio>
#include <string>

#include "core/render.h"
#include "tests/shaft_scenes.h"

using namespace brume;

namespace {

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
    if (only.empty() || only == "sun15") study("sun, 1.5 m gap", test::sunShaftScene(1.5f));
    if (only.empty() || only == "spot") study("spot, 1.5 m gap", test::spotShaftScene());
    if (only.empty() || only == "sun25") study("sun, 2.5 m gap", test::sunShaftScene(2.5f));
    return 0;
}
