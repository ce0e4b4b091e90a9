#include "noise_command.h"

#include <cmath>
#include <filesystem>
#include <optional>

#include "cli_text.h"
#include "core/noise.h"
#include "core/settings.h"
#include "io/vdb_export.h"
#include "progress.h"

namespace brume::app {

namespace fs = std::filesystem;

// Tiles at least this many voxels (128^3) take a second or more: they show progress.
static constexpr int64_t kProgressVoxels = int64_t(128) * 128 * 128;

CLI::App* addNoiseCommand(CLI::App& app, NoiseOptions& o) {
    CLI::App* cmd = app.add_subcommand(
        "noise", "Write a tileable (periodic) 3D noise grid, fBm of gradient noise with values in [0, 1] and mean "
                 "0.5, for a volume's density_texture (see docs/vdb.md).");
    cmd->add_option("OUT", o.out, "Output OpenVDB file (.vdb); written atomically.")->required();
    o.size = settings::noise_size.i();
    cmd->add_option("--size", o.size, optionHelp(settings::noise_size));
    o.octaves = settings::noise_octaves.i();
    cmd->add_option("--octaves", o.octaves, optionHelp(settings::noise_octaves));
    o.frequency = settings::noise_frequency.i();
    cmd->add_option("--frequency", o.frequency, optionHelp(settings::noise_frequency));
    o.seed = settings::noise_seed.i();
    cmd->add_option("--seed", o.seed, optionHelp(settings::noise_seed));
    cmd->add_option("--grid", o.grid, optionHelp(settings::noise_grid, "density"));
    o.threads = settings::cli_threads.i();
    cmd->add_option("--threads", o.threads, optionHelp(settings::cli_threads));
    return cmd;
}

namespace {

std::optional<CommandResult> checkRange(const char* name, double v, const Setting& s) {
    if (std::isfinite(v) && v >= s.min && v <= s.max) return std::nullopt;
    return badInput(std::string(name) + " " + formatNumber(v) + " is out of range: expected " + formatRange(s) + ".");
}

std::optional<CommandResult> checkOptions(const NoiseOptions& o) {
    if (auto e = checkRange("--size", o.size, settings::noise_size)) return e;
    if (auto e = checkRange("--octaves", o.octaves, settings::noise_octaves)) return e;
    if (auto e = checkRange("--frequency", o.frequency, settings::noise_frequency)) return e;
    if (auto e = checkRange("--seed", static_cast<double>(o.seed), settings::noise_seed)) return e;
    if (auto e = checkRange("--threads", o.threads, settings::cli_threads)) return e;
    // '#' addresses one of several same-named grids (docs/vdb.md), so a name cannot hold it.
    if (o.grid.empty() || o.grid.find('#') != std::string::npos)
        return badInput("--grid '" + o.grid + "' is not a usable grid name: it must be non-empty and without '#'.");
    return checkOutputPath(o.out, ".vdb");
}

}  // namespace

CommandResult runNoise(const NoiseOptions& o) {
    if (auto e = checkOptions(o)) return *e;
    NoiseTileParams p;
    p.size = o.size;
    p.octaves = o.octaves;
    p.frequency = o.frequency;
    p.seed = static_cast<uint32_t>(o.seed);
    std::optional<ProgressLine> progress;
    if (int64_t(o.size) * o.size * o.size >= kProgressVoxels) progress.emplace("noise " + o.out);
    std::vector<float> values = makeNoiseTile(p, o.threads, [&](float f) {
        if (progress) progress->update(f);
    });
    if (progress) progress->complete();
    if (Result<void> w = writeDenseVdb(o.out, o.grid, o.size, values); !w) return badInput(w.error().message);
    return success();
}

}  // namespace brume::app
