#include "bake_command.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "cli_text.h"
#include "core/settings.h"
#include "io/fog_bake.h"
#include "io/scene_json.h"
#include "progress.h"
#include "vdb_command.h"

namespace brume::app {

namespace fs = std::filesystem;

// Bakes of at least this many voxels take a second or more: they show progress.
static constexpr uint64_t kProgressVoxels = uint64_t(1) << 21;

CLI::App* addBakeCommand(CLI::App& app, BakeCommandOptions& o) {
    CLI::App* cmd = app.add_subcommand(
        "bake", "Bake every volume of a scene into sparse world-space OpenVDB grids: density (sigma_t, 1/m), Cd "
                "(single-scattering albedo, vec3) and emission (vec3), with units and Brume's version in the file's "
                "metadata (see docs/export.md).");
    cmd->add_option("SCENE", o.scene, "Scene file (JSON).")->required();
    cmd->add_option("-o,--output", o.out, "Output OpenVDB file (.vdb); written atomically, its folder must exist.")->required();
    cmd->add_option("--voxel-size", o.voxelSize, optionHelp(settings::cli_voxel_size, "none (required)"))->required();
    cmd->add_option("--bounds", o.bounds, optionHelp(settings::cli_bounds, "the volumes' own bounds"))->expected(6);
    o.threads = settings::cli_threads.i();
    cmd->add_option("--threads", o.threads, optionHelp(settings::cli_threads));
    o.vdbMemoryMb = settings::cli_vdb_memory.i();
    cmd->add_option("--vdb-memory-mb", o.vdbMemoryMb, optionHelp(settings::cli_vdb_memory));
    return cmd;
}

namespace {

std::optional<CommandResult> checkOptions(const BakeCommandOptions& o) {
    const Setting& vs = settings::cli_voxel_size;
    if (!(std::isfinite(o.voxelSize) && o.voxelSize >= vs.min && o.voxelSize <= vs.max))
        return badInput("--voxel-size " + formatNumber(o.voxelSize) + " is out of range: expected " + formatRange(vs) + ".");
    if (!o.bounds.empty()) {
        for (double b : o.bounds)
            if (!(std::isfinite(b) && std::abs(b) <= settings::cli_bounds.max))
                return badInput("--bounds " + formatNumber(b) + " is out of range: expected " + formatRange(settings::cli_bounds) + ".");
        for (int a = 0; a < 3; ++a)
            if (!(o.bounds[size_t(a) + 3] > o.bounds[size_t(a)]))
                return badInput("--bounds: the maximum must exceed the minimum on every axis (XMIN YMIN ZMIN XMAX YMAX ZMAX).");
    }
    const Setting& th = settings::cli_threads;
    if (o.threads < th.min || o.threads > th.max)
        return badInput("--threads " + std::to_string(o.threads) + " is out of range: expected " + formatRange(th) + ".");
    return checkOutputPath(o.out, ".vdb");
}

}  // namespace

CommandResult runBake(const BakeCommandOptions& o) {
    if (auto e = checkOptions(o)) return *e;
    Result<Scene> scene = loadSceneFile(o.scene);
    if (!scene) return badInput(scene.error().message);
    if (Result<void> g = loadGridsPrintingWarnings(scene.value(), o.scene, o.vdbMemoryMb); !g)
        return badInput(g.error().message);
    BakeOptions options;
    options.voxelSize = static_cast<float>(o.voxelSize);
    options.threads = o.threads;
    if (!o.bounds.empty())
        options.bounds = WorldBox{glm::vec3(o.bounds[0], o.bounds[1], o.bounds[2]), glm::vec3(o.bounds[3], o.bounds[4], o.bounds[5])};
    Result<WorldBox> box = bakeBox(scene.value(), options, o.scene);
    if (!box) return badInput(box.error().message);
    const glm::vec3 cells = (box.value().max - box.value().min) / options.voxelSize;
    std::optional<ProgressLine> progress;
    if (double(cells.x) * cells.y * cells.z >= double(kProgressVoxels)) progress.emplace("baking " + o.out);
    options.progress = [&](float f) {
        if (progress) progress->update(f);
    };
    Result<BakeResult> r = bakeFogVdb(scene.value(), options, o.scene, o.out);
    if (!r) {
        if (progress) progress->end();
        return r.error().badInput ? badInput(r.error().message) : internalFailure(r.error().message);
    }
    if (progress) progress->complete();
    const BakeResult& b = r.value();
    std::printf("%s: %d x %d x %d voxels of %s m, %llu active\n", o.out.c_str(), b.voxels.x, b.voxels.y, b.voxels.z,
                formatNumber(o.voxelSize).c_str(), static_cast<unsigned long long>(b.activeVoxels));
    return success();
}

}  // namespace brume::app
