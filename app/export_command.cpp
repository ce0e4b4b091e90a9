#include "export_command.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "core/settings.h"
#include "io/atomic_file.h"
#include "io/blender_export.h"
#include "io/fog_source.h"
#include "io/godot_export.h"
#include "io/vdb_import.h"

namespace brume::app {

namespace fs = std::filesystem;

CLI::App* addExportCommand(CLI::App& app, ExportOptions& o) {
    CLI::App* cmd = app.add_subcommand(
        "export", "Export a scene's or a preset's fog to another tool. Every setting the target cannot express is "
                  "printed as one 'loss:' line on stdout (and written as a comment in the file); see docs/export.md.");
    cmd->add_option("INPUT", o.input, "Scene or preset file (JSON).")->required();
    cmd->add_option("--to", o.to,
                    "Target: godot (a Godot 4 .tscn text scene) or blender (a Python script for Blender 3.4+ that "
                    "rebuilds the fog and, run as blender -b --factory-startup --python OUT.py -- --render OUT.exr "
                    "[--samples N] [--width W --height H], renders it with Cycles at single scattering).")
        ->required();
    cmd->add_option("-o,--output", o.out,
                    "Output file (.tscn for godot, .py for blender); written atomically, its folder must exist.")
        ->required();
    return cmd;
}

CommandResult runExport(const ExportOptions& o) {
    if (o.to != "godot" && o.to != "blender")
        return badInput("--to '" + o.to + "' is not a known target; expected godot or blender.");
    const bool godot = o.to == "godot";
    const fs::path path(o.out);
    const char* ext = godot ? ".tscn" : ".py";
    if (path.extension() != ext) return badInput(o.out + ": the output of --to " + o.to + " must be a " + ext + " file.");
    const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    if (!fs::is_directory(dir)) return badInput(o.out + ": the folder " + dir.string() + " does not exist.");
    Result<FogSource> source = loadFogSource(o.input);
    if (!source) return badInput(source.error().message);
    std::string text;
    std::vector<std::string> losses;
    std::map<size_t, std::string> bakedFiles;
    if (godot) {
        GodotExport g = exportGodot(source.value());
        text = std::move(g.tscn);
        losses = std::move(g.losses);
    } else {
        // Density textures are baked into VDB files beside the script (io/blender_export.h).
        Scene& scene = source.value().scene;
        std::vector<std::string> warnings;
        const bool textured = std::any_of(scene.volumes.begin(), scene.volumes.end(),
                                          [](const Volume& v) { return v.density_texture.has_value(); });
        if (textured)
            if (Result<void> g = loadSceneGrids(scene, o.input, static_cast<uint64_t>(settings::cli_vdb_memory.i()) << 20, warnings); !g)
                return badInput(g.error().message);
        for (const std::string& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
        Result<std::map<size_t, std::string>> baked = bakeTexturedVolumes(scene, o.out, o.input);
        if (!baked) return badInput(baked.error().message);
        bakedFiles = baked.value();
        BlenderExport b = exportBlender(source.value(), bakedFiles);
        text = std::move(b.script);
        losses = std::move(b.losses);
    }
    if (Result<void> w = writeTextFileAtomic(o.out, text); !w) {
        std::error_code ec;
        for (const auto& [i, file] : bakedFiles) fs::remove(file, ec);  // nothing half-written
        return badInput(w.error().message);
    }
    for (const std::string& loss : losses) std::printf("loss: %s\n", loss.c_str());
    return success();
}

}  // namespace brume::app
