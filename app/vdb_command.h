// OpenVDB on the command line: `brume info FILE.vdb [--json]`, and the grid loading that render,
// bench and validate share (warnings to stderr as "warning: ...").
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "command.h"
#include "core/result.h"
#include "core/scene.h"

namespace brume::app {

// Loads every vdb volume's grid; prints each warning on stderr.
Result<void> loadGridsPrintingWarnings(Scene& scene, const std::string& scenePath, int memoryLimitMb);

struct InfoOptions {
    std::string path;
    bool json = false;
};

CLI::App* addInfoCommand(CLI::App& app, InfoOptions& options);
CommandResult runInfo(const InfoOptions& options);

}  // namespace brume::app
