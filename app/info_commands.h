// `brume validate` and `brume settings`: read-only commands.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "command.h"

namespace brume::app {

struct ValidateOptions {
    std::string scenePath;
};

struct SettingsOptions {
    bool markdown = false;
};

CLI::App* addValidateCommand(CLI::App& app, ValidateOptions& options);
CommandResult runValidate(const ValidateOptions& options);

CLI::App* addSettingsCommand(CLI::App& app, SettingsOptions& options);
CommandResult runSettings(const SettingsOptions& options);

}  // namespace brume::app
