// Temporal convergence study (docs/temporal.md): error of the CPU froxel renderer against the
// reference after N frames on a scene file. Not a test: run it by hand.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/render.h"
#include "io/image_io.h"
#include "io/scene_json.h"
#include "tests/shaft_scenes.h"

using namespace brume;

int main(int argc, char** argv) {
    if (argc < 5) { std::fprintf(stderr, "usage: temporal_study SCENE W H QUALITY [REF.exr]\n"); return 2; }
    const std::string name = argv[1];
    Result<Scene> scene = name == "sunshaft" ? Result<Scene>(test::sunShaftScene(1.5f))
                        : name == "spotshaft" ? Result<Scene>(test::spotShaftScene()) : loadSceneFile(argv[1]);
    if (!scene) { std::fprintf(stderr, "%s\n", scene.error().message.c_str()); return 2; }
    RenderRequest req;
    req.width = std::atoi(argv[2]);
    req.height = std::atoi(argv[3]);
    req.quality = std::string(argv[4]) == "low" ? Quality::Low : std::string(argv[4]) == "medium" ? Quality::Medium
                : std::string(argv[4]) == "ultra" ? Quality::Ultra : Quality::High;
    Image ref;
    if (argc > 5) {
        auto r = readExr(argv[5]);
        if (r) ref = r.value();
    }
    if (ref.width != req.width) {
        ref = renderReference(scene.value(), req);
        if (argc > 5) (void)writeExr(ref, argv[5]);
    }
    for (int frames : {1, 2, 4, 8, 16, 32}) {
        req.frames = frames;
        const double err = relativeMeanAbsError(renderFroxelCpu(scene.value(), req).image, ref);
        std::printf("%d %.3f%%\n", frames, 100.0 * err);
        std::fflush(stdout);
    }
}
