// `brume`: the command line. Exit codes: 0 success, 2 bad input or arguments, 1 internal failure;
// on failure stderr holds exactly one line, "error: ...".
#include <cstdio>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

#include "bake_command.h"
#include "bench_command.h"
#include "command.h"
#include "export_command.h"
#include "info_commands.h"
#include "noise_command.h"
#include "preset_command.h"
#include "render_command.h"
#include "tradeoff_command.h"
#include "vdb_command.h"

namespace {

using namespace brume::app;

// Keeps the one-line promise even when a message (a library's what()) spans lines.
void printError(std::string message) {
    for (char& c : message)
        if (c == '\n' || c == '\r') c = ' ';
    std::fprintf(stderr, "error: %s\n", message.c_str());
}

int finish(const CommandResult& r) {
    std::fflush(stdout);
    if (r.exitCode != kExitOk) printError(r.error);
    return r.exitCode;
}

bool hasSubcommand(CLI::App& app, const std::string& name) {
    return !app.get_subcommands([&name](CLI::App* sub) { return sub->check_name(name); }).empty();
}

int run(int argc, char** argv) {
    CLI::App app{"Brume: physically based volumetric fog (froxels), from the command line."};
    app.name("brume");
    app.require_subcommand(1);
    RenderOptions render;
    ValidateOptions validate;
    SettingsOptions settings;
    CLI::App* renderCmd = addRenderCommand(app, render);
    CLI::App* validateCmd = addValidateCommand(app, validate);
    CLI::App* settingsCmd = addSettingsCommand(app, settings);
    BenchOptions bench;
    CLI::App* benchCmd = addBenchCommand(app, bench);
    InfoOptions info;
    CLI::App* infoCmd = addInfoCommand(app, info);
    NoiseOptions noise;
    CLI::App* noiseCmd = addNoiseCommand(app, noise);
    PresetOptions preset;
    ExportOptions exportOptions;
    BakeCommandOptions bake;
    TradeoffOptions tradeoff;
    CLI::App* bakeCmd = addBakeCommand(app, bake);
    CLI::App* exportCmd = addExportCommand(app, exportOptions);
    const PresetCommands presetCmds = addPresetCommand(app, preset);
    CLI::App* tradeoffCmd = addTradeoffCommand(app, tradeoff);
    // CLI11 would answer both with "A subcommand is required"; say what is expected instead.
    if (argc < 2) return finish(badInput("no command given; expected render, validate, settings, bench, tradeoff, info, noise, preset, export or bake (see brume --help)."));
    if (argv[1][0] != '-' && !hasSubcommand(app, argv[1])) {
        return finish(badInput(std::string("unknown command '") + argv[1] + "'; expected render, validate, settings, bench, tradeoff, info, noise, preset, export or bake."));
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // --help and friends are "errors" with exit code 0: let CLI11 print them.
        if (e.get_exit_code() == 0) return app.exit(e);
        printError(e.what());
        return kExitBadInput;
    }
    if (*renderCmd) return finish(runRender(render));
    if (*validateCmd) return finish(runValidate(validate));
    if (*settingsCmd) return finish(runSettings(settings));
    if (*benchCmd) return finish(runBench(bench));
    if (*infoCmd) return finish(runInfo(info));
    if (*noiseCmd) return finish(runNoise(noise));
    if (*presetCmds.preset) return finish(runPreset(presetCmds, preset));
    if (*exportCmd) return finish(runExport(exportOptions));
    if (*bakeCmd) return finish(runBake(bake));
    if (*tradeoffCmd) return finish(runTradeoff(tradeoff));
    return finish(badInput("no command given; expected render, validate, settings, bench, tradeoff, info, noise, preset, export or bake (see brume --help)."));
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& e) {
        printError(std::string("internal failure: ") + e.what());
    } catch (...) {
        printError("internal failure (unknown exception).");
    }
    return kExitInternal;
}
