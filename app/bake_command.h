// `brume bake SCENE -o FOG.vdb --voxel-size M [--bounds ...]`: the fog as OpenVDB grids (docs/export.md).
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command.h"

namespace brume::app {

struct BakeCommandOptions {
    std::string scene;
    std::string out;
    double voxelSize = 0.0;
    std::vector<double> bounds;
    int threads = 0;
    int vdbMemoryMb = 4096;
};

CLI::App* addBakeCommand(CLI::App& app, BakeCommandOptions& options);
CommandResult runBake(const BakeCommandOptions& options);

}  // namespace brume::app
