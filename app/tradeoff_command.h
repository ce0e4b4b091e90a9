// `brume tradeoff`: the speed/accuracy trade on the user's own scene. Renders the reference once
// (cached by the scene's content hash), times every candidate (quality presets x temporal frames,
// plus --grid overrides) and measures its error against the reference; prints a table with the
// Pareto front, a recommendation, and optionally an SVG chart and JSON (docs/quality.md).
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command.h"

namespace brume::app {

struct TradeoffOptions {
    std::string scenePath;
    int width = 0;
    int height = 0;
    std::string qualities = "low,medium,high,ultra";
    std::string frames = "1,4,16";
    std::vector<std::string> grids;  // --grid TILExSLICES, repeatable
    int repeats = 3;
    int warmup = 1;
    bool cpu = false;
    int threads = 0;
    std::string device;
    double maxErrorPercent = -1.0;  // --max-error, < 0 = not given
    double budgetMs = -1.0;         // --budget-ms, < 0 = not given
    std::string svgPath;
    std::string jsonPath;
    std::string cacheDir;  // "" = $XDG_CACHE_HOME/brume/references or ~/.cache/brume/references
    CLI::Option* widthOption = nullptr;
    CLI::Option* heightOption = nullptr;
};

CLI::App* addTradeoffCommand(CLI::App& app, TradeoffOptions& options);
CommandResult runTradeoff(const TradeoffOptions& options);

}  // namespace brume::app
