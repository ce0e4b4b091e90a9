#include "preset_command.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "cli_text.h"
#include "core/settings.h"
#include "io/preset.h"
#include "io/scene_json.h"
#include "vdb_command.h"

#ifndef BRUME_PRESET_LIBRARY
#define BRUME_PRESET_LIBRARY ""
#endif

namespace brume::app {

namespace fs = std::filesystem;

PresetCommands addPresetCommand(CLI::App& app, PresetOptions& o) {
    PresetCommands c;
    c.preset = app.add_subcommand("preset", "Fog presets: save a scene's fog as a look, apply a look to a scene, list "
                                            "looks (see docs/presets.md).");
    c.preset->require_subcommand(1);

    c.save = c.preset->add_subcommand(
        "save", "Save a scene's fog (volumes, ambient, lights) as a preset file, with a thumbnail PNG beside it "
                "rendered from the scene (its camera and geometry) by the reference renderer.");
    c.save->add_option("SCENE", o.scene, "Scene file whose fog is saved.")->required();
    c.save->add_option("-o,--output", o.out,
                       "Preset file (.json); written atomically, VDB paths made relative to its folder. The "
                       "thumbnail goes beside it with the extension .png.")
        ->required();
    c.save->add_option("--name", o.name, std::string(settings::preset_name.help) + " Default: the output's file name.");
    c.save->add_option("--description", o.description, std::string(settings::preset_description.help));
    c.save->add_option("--tag", o.tags, "A tag (repeatable). " + std::string(settings::preset_tags.help));
    c.save->add_flag("--no-lights", o.noLights, "Leave the scene's lights out: applying the preset keeps the target's.");
    c.save->add_flag("--no-thumbnail", o.noThumbnail, "Do not render the thumbnail.");
    o.thumbnailWidth = settings::cli_thumbnail_width.i();
    c.save->add_option("--thumbnail-width", o.thumbnailWidth, optionHelp(settings::cli_thumbnail_width));
    o.thumbnailHeight = settings::cli_thumbnail_height.i();
    c.save->add_option("--thumbnail-height", o.thumbnailHeight, optionHelp(settings::cli_thumbnail_height));

    c.apply = c.preset->add_subcommand("apply", "Apply a preset to a scene and write the result as a new scene.");
    c.apply->add_option("PRESET", o.preset, "Preset file (.json).")->required();
    c.apply->add_option("SCENE", o.scene, "Scene file the look is applied to (it is not modified).")->required();
    c.apply->add_option("-o,--output", o.out, "Output scene (.json); written atomically, VDB paths relative to its folder.")
        ->required();
    CLI::Option* replace = c.apply->add_flag(
        "--replace", o.replace,
        "Replace the scene's volumes and ambient (and lights, where the preset has them) by the preset's (the default).");
    CLI::Option* add = c.apply->add_flag(
        "--add", o.add, "Add the preset's volumes (and lights, where it has them) to the scene's; the ambient stays.");
    replace->excludes(add);

    c.list = c.preset->add_subcommand(
        "list", "List the presets in DIR, or else in the shipped library (assets/presets) and the user's folder "
                "($XDG_DATA_HOME/brume/presets): file, name, tags, and whether a thumbnail is beside it.");
    c.list->add_option("DIR", o.dir, "Folder of preset files (not searched recursively).");
    return c;
}

namespace {

std::optional<CommandResult> checkOutput(const std::string& out) {
    const fs::path path(out);
    if (path.extension() != ".json") return badInput(out + ": the output must be a .json file.");
    const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    if (!fs::is_directory(dir)) return badInput(out + ": the folder " + dir.string() + " does not exist.");
    return std::nullopt;
}

std::optional<CommandResult> checkRange(const char* name, int v, const Setting& s) {
    if (v >= s.min && v <= s.max) return std::nullopt;
    return badInput(std::string(name) + " " + std::to_string(v) + " is out of range: expected " + formatRange(s) + ".");
}

// The scene as a small image (io/preset.h: the reference renderer), with its grids loaded.
Result<Image> renderThumbnail(Scene scene, const std::string& scenePath, int width, int height) {
    if (Result<void> g = loadGridsPrintingWarnings(scene, scenePath, settings::cli_vdb_memory.i()); !g) return g.error();
    Result<Image> image = renderPresetThumbnail(scene, width, height);
    if (!image) return Error{scenePath + ": " + image.error().message};
    return image;
}

CommandResult runSave(const PresetOptions& o) {
    if (auto e = checkOutput(o.out)) return *e;
    if (auto e = checkRange("--thumbnail-width", o.thumbnailWidth, settings::cli_thumbnail_width)) return *e;
    if (auto e = checkRange("--thumbnail-height", o.thumbnailHeight, settings::cli_thumbnail_height)) return *e;
    Result<Scene> scene = loadSceneFile(o.scene);
    if (!scene) return badInput(scene.error().message);
    if (Result<void> f = checkVolumeFiles(scene.value().volumes, scene.value().baseDir, o.scene); !f)
        return badInput(f.error().message);
    const std::string name = o.name.empty() ? fs::path(o.out).stem().string() : o.name;
    Preset preset = presetFromScene(scene.value(), name, !o.noLights);
    preset.description = o.description;
    preset.tags = o.tags;
    for (const std::string& t : o.tags)
        if (t.empty()) return badInput("--tag: a tag must not be empty.");
    std::optional<Image> thumbnail;
    if (!o.noThumbnail) {
        Result<Image> t = renderThumbnail(scene.value(), o.scene, o.thumbnailWidth, o.thumbnailHeight);
        if (!t) return t.error().badInput ? badInput(t.error().message) : internalFailure(t.error().message);
        thumbnail = std::move(t.value());
    }
    if (Result<void> w = savePresetWithThumbnail(preset, o.out, o.scene, thumbnail ? &*thumbnail : nullptr); !w)
        return badInput(w.error().message);
    return success();
}

CommandResult runApply(const PresetOptions& o) {
    if (auto e = checkOutput(o.out)) return *e;
    Result<Preset> preset = loadPresetFile(o.preset);
    if (!preset) return badInput(preset.error().message);
    Result<Scene> scene = loadSceneFile(o.scene);
    if (!scene) return badInput(scene.error().message);
    std::error_code ec;
    const std::string outDir = fs::absolute(o.out, ec).lexically_normal().parent_path().string();
    Result<Scene> applied =
        applyPreset(scene.value(), preset.value(), o.add ? PresetApply::Add : PresetApply::Replace, outDir, o.out);
    if (!applied) return badInput(applied.error().message);
    if (Result<void> w = saveSceneFile(applied.value(), o.out); !w) return badInput(w.error().message);
    return success();
}

void printListing(const std::vector<PresetListing>& listings) {
    for (const PresetListing& l : listings) {
        if (!l.preset) {
            std::fprintf(stderr, "warning: %s\n", l.error.c_str());
            continue;
        }
        std::string tags;
        for (const std::string& t : l.preset->tags) tags += (tags.empty() ? "" : ", ") + t;
        std::printf("%s\t%s\t[%s]\t%s\n", l.path.c_str(), l.preset->name.c_str(), tags.c_str(),
                    l.hasThumbnail ? "thumbnail" : "no thumbnail");
    }
}

CommandResult runList(const PresetOptions& o) {
    if (!o.dir.empty()) {
        if (!fs::is_directory(o.dir)) return badInput(o.dir + ": not a folder.");
        printListing(listPresets(o.dir));
        return success();
    }
    for (const std::string& dir : {std::string(BRUME_PRESET_LIBRARY), userPresetDir()})
        if (!dir.empty() && fs::is_directory(dir)) printListing(listPresets(dir));
    return success();
}

}  // namespace

CommandResult runPreset(const PresetCommands& c, const PresetOptions& o) {
    if (*c.save) return runSave(o);
    if (*c.apply) return runApply(o);
    if (*c.list) return runList(o);
    return badInput("brume preset: expected save, apply or list (see brume preset --help).");
}

}  // namespace brume::app
