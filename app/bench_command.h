// `brume bench`: per-pass medians of repeated renders after a warm-up. A benchmark, not a test:
// its numbers depend on the machine.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "command.h"

namespace brume::app {

struct BenchOptions {
    std::string scenePath;
    int width = 0;
    int height = 0;
    std::string quality;
    int frames = 20;
    int warmup = 3;
    bool cpu = false;
    bool noLightCulling = false;
    bool noVdbCulling = false;
    float orbit = 0.0f;        // --orbit: degrees the camera turns per render (settings::cli_orbit)
    std::string device;
    std::string jsonPath;      // --json: medians written here (atomically)
    std::string baselinePath;  // --baseline: an earlier --json output to print ratios against
    CLI::Option* widthOption = nullptr;
    CLI::Option* heightOption = nullptr;
    CLI::Option* qualityOption = nullptr;
};

CLI::App* addBenchCommand(CLI::App& app, BenchOptions& options);
CommandResult runBench(const BenchOptions& options);

}  // namespace brume::app
