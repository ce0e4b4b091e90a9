// `brume preset save|apply|list`: fog looks as files shared between scenes (docs/presets.md).
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "command.h"

namespace brume::app {

struct PresetOptions {
    // save
    std::string scene;
    std::string out;
    std::string name;
    std::string description;
    std::vector<std::string> tags;
    bool noLights = false;
    bool noThumbnail = false;
    int thumbnailWidth = 160;
    int thumbnailHeight = 90;
    // apply
    std::string preset;
    bool replace = false;
    bool add = false;
    // list
    std::string dir;
};

struct PresetCommands {
    CLI::App* preset = nullptr;
    CLI::App* save = nullptr;
    CLI::App* apply = nullptr;
    CLI::App* list = nullptr;
};

PresetCommands addPresetCommand(CLI::App& app, PresetOptions& options);
CommandResult runPreset(const PresetCommands& commands, const PresetOptions& options);

}  // namespace brume::app
