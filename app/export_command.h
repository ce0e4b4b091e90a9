// `brume export SCENE_OR_PRESET --to godot -o PATH`: the fog for another tool (docs/export.md).
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "command.h"

namespace brume::app {

struct ExportOptions {
    std::string input;
    std::string to;
    std::string out;
};

CLI::App* addExportCommand(CLI::App& app, ExportOptions& options);
CommandResult runExport(const ExportOptions& options);

}  // namespace brume::app
