#include "preset_shelf.h"

#include <cctype>
#include <filesystem>

#include "core/settings.h"

#include "io/vdb_import.h"

#ifndef BRUME_PRESET_LIBRARY
#define BRUME_PRESET_LIBRARY ""
#endif

namespace brume::editor {

namespace fs = std::filesystem;

std::string presetLibraryDir() {
    std::error_code ec;
    const std::string dir = BRUME_PRESET_LIBRARY;
    return !dir.empty() && fs::is_directory(dir, ec) ? dir : std::string();
}

std::vector<ShelfEntry> scanPresetShelf(const std::string& libraryDir, const std::string& userDir) {
    std::vector<ShelfEntry> out;
    for (const std::string& dir : {libraryDir, userDir}) {
        std::error_code ec;
        if (dir.empty() || !fs::is_directory(dir, ec)) continue;
        for (PresetListing& l : listPresets(dir))
            out.push_back({std::move(l.path), dir == libraryDir, std::move(l.preset), std::move(l.error), l.hasThumbnail});
    }
    return out;
}

Result<void> applyPresetToDocument(Document& doc, const std::string& presetPath, PresetApply mode) {
    Result<Preset> read = loadPresetFile(presetPath);
    if (!read) return read.error();
    Preset preset = std::move(read.value());
    // The preset's grids, loaded on their own (its paths are absolute), so the scene's stay as they are.
    Scene grids;
    grids.volumes = preset.volumes;
    std::vector<std::string> warnings;
    // (density textures too: the shared io/vdb_import.h loader)
    if (Result<void> g = loadSceneGrids(grids, presetPath, VdbImportOptions{}.memoryLimitBytes, warnings); !g) return g.error();
    preset.volumes = std::move(grids.volumes);
    const Scene& scene = doc.scene();
    std::error_code ec;
    const std::string outDir = scene.baseDir.empty() ? fs::current_path(ec).string() : scene.baseDir;
    Result<Scene> applied = applyPreset(scene, preset, mode, outDir, doc.path().empty() ? "untitled" : doc.path());
    if (!applied) return Error{presetPath + ": " + applied.error().message};
    doc.replaceScene(applied.value());
    return {};
}

std::string presetFileStem(const std::string& name) {
    std::string stem;
    for (unsigned char c : name) {
        if (std::isalnum(c) && c < 0x80) stem += static_cast<char>(std::tolower(c));
        else if (!stem.empty() && stem.back() != '-') stem += '-';
    }
    while (!stem.empty() && stem.back() == '-') stem.pop_back();
    return stem.empty() ? "preset" : stem;
}

Result<std::string> saveFogAsPreset(const Scene& scene, const std::string& dir, const PresetMeta& meta,
                                    glm::ivec2 thumbnailSize) {
    if (meta.name.empty()) return Error{"Save fog as preset: the name must not be empty."};
    for (const std::string& t : meta.tags)
        if (t.empty()) return Error{"Save fog as preset: a tag must not be empty."};
    if (dir.empty()) return Error{"Save fog as preset: there is no user preset folder (neither XDG_DATA_HOME nor HOME is set)."};
    const std::string path = (fs::path(dir) / (presetFileStem(meta.name) + ".json")).string();
    std::error_code ec;
    if (fs::exists(path, ec)) return Error{path + ": a preset of that name exists already; choose another name."};
    fs::create_directories(dir, ec);
    if (ec) return Error{dir + ": cannot create the preset folder: " + ec.message() + "."};
    Preset preset = presetFromScene(scene, meta.name, true);
    preset.description = meta.description;
    preset.tags = meta.tags;
    // Every volume, hidden ones too (the renderers do not read `hidden`): all are part of the look.
    Result<Image> thumbnail = renderPresetThumbnail(scene, thumbnailSize.x, thumbnailSize.y);
    if (!thumbnail) return Error{path + ": " + thumbnail.error().message};
    const std::string source = scene.baseDir.empty() ? "the scene" : scene.baseDir;
    if (Result<void> w = savePresetWithThumbnail(preset, path, source, &thumbnail.value()); !w) return w.error();
    return path;
}

Result<void> runPresetAction(Document& doc, const Action& a) {
    const std::vector<std::string>& w = a.args;
    if (w.size() == 3 && w[0] == "apply" && (w[2] == "replace" || w[2] == "add"))
        return applyPresetToDocument(doc, w[1], w[2] == "add" ? PresetApply::Add : PresetApply::Replace);
    if (w.size() >= 2 && w[0] == "save") {
        PresetMeta meta{w[1], w.size() > 2 ? w[2] : "", {}};
        if (w.size() > 3) meta.tags.assign(w.begin() + 3, w.end());
        const glm::ivec2 size(settings::cli_thumbnail_width.i(), settings::cli_thumbnail_height.i());
        Result<std::string> saved = saveFogAsPreset(doc.scene(), userPresetDir(), meta, size);
        if (!saved) return saved.error();
        return {};
    }
    return Error{"preset takes: preset apply FILE replace|add, or preset save NAME [DESCRIPTION [TAG...]]."};
}

}  // namespace brume::editor
