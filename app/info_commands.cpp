#include "info_commands.h"
#include "vdb_command.h"

#include <cstdio>
#include <map>

#include "cli_text.h"
#include "core/scene.h"
#include "io/scene_json.h"

namespace brume::app {

CLI::App* addValidateCommand(CLI::App& app, ValidateOptions& o) {
    CLI::App* cmd = app.add_subcommand(
        "validate", "Check a scene file strictly (unknown keys, types, ranges) and print a one-line summary.");
    cmd->add_option("SCENE", o.scenePath, "Scene file (JSON; see docs/scene-format.md).")->required();
    return cmd;
}

// "3 lights (1 directional, 2 point)"; counts by kind name, in name order.
template <class T>
static std::string countByKind(const std::vector<T>& items, const char* noun, const char* plural) {
    std::string s = std::to_string(items.size()) + " " + (items.size() == 1 ? noun : plural);
    if (items.empty()) return s;
    std::map<std::string, int> counts;
    for (const T& item : items) ++counts[toString(item.type)];
    std::string parts;
    for (const auto& [name, n] : counts) parts += (parts.empty() ? "" : ", ") + std::to_string(n) + " " + name;
    return s + " (" + parts + ")";
}

CommandResult runValidate(const ValidateOptions& o) {
    Result<Scene> scene = loadSceneFile(o.scenePath);
    if (!scene) return badInput(scene.error().message);
    // A scene whose vdb file is unreadable would fail to render: validate reads the grids too.
    if (Result<void> g = loadGridsPrintingWarnings(scene.value(), o.scenePath, settings::cli_vdb_memory.i()); !g)
        return badInput(g.error().message);
    const Scene& s = scene.value();
    std::printf("%s: ok\n", o.scenePath.c_str());
    std::printf("  %dx%d px, quality %s; %s; %s; %s\n", s.render.width, s.render.height, toString(s.render.quality),
                countByKind(s.lights, "light", "lights").c_str(), countByKind(s.volumes, "volume", "volumes").c_str(),
                countByKind(s.geometry, "surface", "surfaces").c_str());
    return success();
}

CLI::App* addSettingsCommand(CLI::App& app, SettingsOptions& o) {
    CLI::App* cmd = app.add_subcommand(
        "settings", "Print every scene setting with its unit, default and range (from core/settings.h).");
    cmd->add_flag("--markdown", o.markdown, "Print a Markdown table (the one in docs/scene-format.md). Default: off.");
    return cmd;
}

CommandResult runSettings(const SettingsOptions& o) {
    const std::string text = o.markdown ? settingsMarkdownTable() : settingsPlainTable();
    std::fwrite(text.data(), 1, text.size(), stdout);
    return success();
}

}  // namespace brume::app
