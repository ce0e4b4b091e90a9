// `brume noise OUT.vdb`: writes a tileable 3D noise grid for density textures (docs/vdb.md).
#pragma once

#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

#include "command.h"

namespace brume::app {

struct NoiseOptions {
    std::string out;
    int size = 64;
    int octaves = 4;
    int frequency = 4;
    int64_t seed = 1;  // wide, so that out-of-range values are reported, not wrapped
    std::string grid = "density";
    int threads = 0;
};

CLI::App* addNoiseCommand(CLI::App& app, NoiseOptions& options);
CommandResult runNoise(const NoiseOptions& options);

}  // namespace brume::app
