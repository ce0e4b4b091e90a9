#include "preset.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>

#include <nlohmann/json.hpp>

#include "core/render.h"
#include "core/settings.h"
#include "io/atomic_file.h"
#include "io/image_io.h"
#include "io/scene_json.h"
#include "io/scene_json_parts.h"

namespace brume {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using ojson = nlohmann::ordered_json;

constexpr const char* kVersionKey = "brume_preset";

// Migrations: step v turns a version-v document into version v + 1 in place (kMigrations[v - 1]).
// None yet: version 1 is the first. A new version appends its step here and bumps kPresetVersion,
// so every older file keeps reading.
using Migration = std::function<Result<void>(json& doc, const std::string& file)>;
const std::array<Migration, kPresetVersion - 1> kMigrations{};

Result<void> migrate(json& doc, int fromVersion, const std::string& file) {
    for (int v = fromVersion; v < kPresetVersion; ++v)
        if (Result<void> r = kMigrations[static_cast<size_t>(v - 1)](doc, file); !r) return r;
    doc[kVersionKey] = kPresetVersion;
    return {};
}

Result<int> readVersion(const json& root, const std::string& file) {
    const auto it = root.find(kVersionKey);
    const std::string reads = "this build of Brume reads versions 1 to " + std::to_string(kPresetVersion);
    if (it == root.end()) return Error{file + ": " + kVersionKey + ": missing required key (the preset format version; " + reads + ")"};
    const double d = it->is_number() ? it->get<double>() : std::nan("");
    if (!std::isfinite(d) || d != std::floor(d))
        return Error{file + ": " + kVersionKey + ": expected an integer version, got " + it->dump()};
    if (d > kPresetVersion)
        return Error{file + ": " + kVersionKey + ": version " + it->dump() + " is newer than this build of Brume reads (" +
                     std::to_string(kPresetVersion) + "); update Brume to use this preset"};
    if (d < 1) return Error{file + ": " + kVersionKey + ": unsupported version " + it->dump() + " (" + reads + ")"};
    return static_cast<int>(d);
}

Result<std::string> readString(const json& root, const std::string& file, const Setting& s, bool required) {
    const std::string key(s.path);
    const auto it = root.find(key);
    if (it == root.end()) {
        if (required) return Error{file + ": " + key + ": missing required key (" + std::string(s.help) + ")"};
        return std::string();
    }
    if (!it->is_string()) return Error{file + ": " + key + ": expected a string, got " + it->dump()};
    std::string v = it->get<std::string>();
    if (required && v.empty()) return Error{file + ": " + key + ": must not be empty"};
    return v;
}

Result<std::vector<std::string>> readTags(const json& root, const std::string& file) {
    const std::string key(settings::preset_tags.path);
    std::vector<std::string> tags;
    const auto it = root.find(key);
    if (it == root.end()) return tags;
    if (!it->is_array()) return Error{file + ": " + key + ": expected an array of strings"};
    for (size_t i = 0; i < it->size(); ++i) {
        const json& t = (*it)[i];
        if (!t.is_string() || t.get<std::string>().empty())
            return Error{file + ": " + key + "[" + std::to_string(i) + "]: expected a non-empty string, got " + t.dump()};
        tags.push_back(t.get<std::string>());
    }
    return tags;
}

fs::path absoluteFrom(const std::string& baseDir, const std::string& file) {
    const fs::path p(file);
    if (p.is_absolute()) return p.lexically_normal();
    std::error_code ec;
    const fs::path base = baseDir.empty() ? fs::current_path(ec) : fs::path(baseDir);
    return fs::absolute(base / p, ec).lexically_normal();
}

// Relative to `dir` where one exists (always on POSIX for absolute paths), else absolute.
std::string relativeTo(const fs::path& absolute, const std::string& dir) {
    std::error_code ec;
    const fs::path base = fs::absolute(dir.empty() ? fs::path(".") : fs::path(dir), ec).lexically_normal();
    const fs::path rel = absolute.lexically_relative(base);
    return rel.empty() ? absolute.string() : rel.generic_string();
}

// Applies `f` to every file path of the volumes (vdb file, density texture file).
void forEachFile(std::vector<Volume>& volumes, const std::function<void(std::string&)>& f) {
    for (Volume& v : volumes) {
        if (v.type == VolumeType::Vdb || v.type == VolumeType::Mesh) f(v.file);
        if (v.density_texture) f(v.density_texture->file);
        if (v.density_texture && v.density_texture->detail) f(v.density_texture->detail->file);
    }
}

void resolveFiles(std::vector<Volume>& volumes, const std::string& baseDir) {
    forEachFile(volumes, [&](std::string& file) { file = absoluteFrom(baseDir, file).string(); });
}

void relativizeFiles(std::vector<Volume>& volumes, const std::string& dir) {
    forEachFile(volumes, [&](std::string& file) { file = relativeTo(absoluteFrom("", file), dir); });
}

}  // namespace

Preset presetFromScene(const Scene& scene, const std::string& name, bool withLights) {
    Preset p;
    p.name = name;
    p.ambient = scene.ambient;
    if (withLights) p.lights = scene.lights;
    p.volumes = scene.volumes;
    for (Volume& v : p.volumes) {  // grids stay with the scene; the preset names their files
        v.density = nullptr;
        v.hidden = false;
        if (v.density_texture) v.density_texture->density = nullptr;
        if (v.density_texture && v.density_texture->detail) v.density_texture->detail->density = nullptr;
    }
    resolveFiles(p.volumes, scene.baseDir);
    return p;
}

Result<Preset> parsePreset(std::string_view text, const std::string& fileName, const std::string& baseDir) {
    Result<json> parsed = scene_json::parseStrictJson(text, fileName);
    if (!parsed) return parsed.error();
    json& root = parsed.value();
    if (!root.is_object()) return Error{fileName + ": expected a JSON object at the top level"};
    Result<int> version = readVersion(root, fileName);
    if (!version) return version.error();
    if (Result<void> m = migrate(root, version.value(), fileName); !m) return m.error();
    const std::string name(settings::preset_name.path), description(settings::preset_description.path),
        tags(settings::preset_tags.path);
    if (Result<void> k = scene_json::checkKeys(root, fileName, "",
                                                {kVersionKey, name, description, tags, "ambient", "lights", "volumes"},
                                                "a preset");
        !k)
        return k.error();
    Preset p;
    Result<std::string> n = readString(root, fileName, settings::preset_name, true);
    if (!n) return n.error();
    p.name = n.value();
    Result<std::string> d = readString(root, fileName, settings::preset_description, false);
    if (!d) return d.error();
    p.description = d.value();
    Result<std::vector<std::string>> t = readTags(root, fileName);
    if (!t) return t.error();
    p.tags = t.value();
    Result<glm::vec3> ambient = scene_json::readAmbient(root, fileName, p.ambient);
    if (!ambient) return ambient.error();
    p.ambient = ambient.value();
    if (const auto it = root.find("lights"); it != root.end()) {
        Result<std::vector<Light>> lights = scene_json::readLights(*it, fileName, "lights");
        if (!lights) return lights.error();
        p.lights = lights.value();
    }
    const auto vit = root.find("volumes");
    if (vit == root.end()) return Error{fileName + ": volumes: missing required key (the fog volumes of the look)"};
    Result<std::vector<Volume>> volumes = scene_json::readVolumes(*vit, fileName, "volumes");
    if (!volumes) return volumes.error();
    p.volumes = volumes.value();
    resolveFiles(p.volumes, baseDir);
    return p;
}

Result<void> checkVolumeFiles(const std::vector<Volume>& volumes, const std::string& baseDir, const std::string& fileName) {
    for (size_t i = 0; i < volumes.size(); ++i) {
        const Volume& v = volumes[i];
        const std::string at = fileName + ": volumes[" + std::to_string(i) + "]";
        std::error_code ec;
        if (v.type == VolumeType::Vdb && !fs::is_regular_file(absoluteFrom(baseDir, v.file), ec))
            return Error{at + ".file: the VDB file " + absoluteFrom(baseDir, v.file).string() + " does not exist"};
        if (v.type == VolumeType::Mesh && !fs::is_regular_file(absoluteFrom(baseDir, v.file), ec))
            return Error{at + ".file: the mesh file " + absoluteFrom(baseDir, v.file).string() + " does not exist"};
        if (v.density_texture && !fs::is_regular_file(absoluteFrom(baseDir, v.density_texture->file), ec))
            return Error{at + ".density_texture.file: the VDB file " +
                         absoluteFrom(baseDir, v.density_texture->file).string() + " does not exist"};
        if (v.density_texture && v.density_texture->detail &&
            !fs::is_regular_file(absoluteFrom(baseDir, v.density_texture->detail->file), ec))
            return Error{at + ".density_texture.detail.file: the VDB file " +
                         absoluteFrom(baseDir, v.density_texture->detail->file).string() + " does not exist"};
    }
    return {};
}

Result<Preset> loadPresetFile(const std::string& path) {
    Result<std::string> text = scene_json::readTextFile(path);
    if (!text) return text.error();
    std::error_code ec;
    const std::string dir = fs::absolute(path, ec).lexically_normal().parent_path().string();
    Result<Preset> p = parsePreset(text.value(), path, dir);
    if (!p) return p;
    if (Result<void> f = checkVolumeFiles(p.value().volumes, dir, path); !f) return f.error();
    return p;
}

std::string presetToJson(const Preset& preset, const std::string& presetDir) {
    std::vector<Volume> volumes = preset.volumes;
    relativizeFiles(volumes, presetDir);
    ojson j;
    j[kVersionKey] = kPresetVersion;
    j[std::string(settings::preset_name.path)] = preset.name;
    j[std::string(settings::preset_description.path)] = preset.description;
    j[std::string(settings::preset_tags.path)] = preset.tags;
    j["ambient"] = scene_json::vec3ToJson(preset.ambient);
    if (preset.lights) {
        ojson lights = ojson::array();
        for (const Light& l : *preset.lights) lights.push_back(scene_json::lightToJson(l));
        j["lights"] = lights;
    }
    ojson vols = ojson::array();
    for (const Volume& v : volumes) vols.push_back(scene_json::volumeToJson(v));
    j["volumes"] = vols;
    return scene_json::prettyJson(j);
}

Result<void> savePresetFile(const Preset& preset, const std::string& path, const std::string& sourceName) {
    if (Result<void> f = checkVolumeFiles(preset.volumes, "", sourceName); !f) return f;
    std::error_code ec;
    const std::string dir = fs::absolute(path, ec).lexically_normal().parent_path().string();
    return writeTextFileAtomic(path, presetToJson(preset, dir));
}

Result<Scene> applyPreset(const Scene& scene, const Preset& preset, PresetApply mode, const std::string& outDir,
                          const std::string& outName) {
    Scene out = scene;
    resolveFiles(out.volumes, scene.baseDir);
    std::vector<Volume> added = preset.volumes;
    if (mode == PresetApply::Replace) {
        out.volumes = added;
        out.ambient = preset.ambient;
        if (preset.lights) out.lights = *preset.lights;
    } else {
        out.volumes.insert(out.volumes.end(), added.begin(), added.end());
        if (preset.lights) out.lights.insert(out.lights.end(), preset.lights->begin(), preset.lights->end());
    }
    relativizeFiles(out.volumes, outDir);
    std::error_code ec;
    out.baseDir = fs::absolute(outDir.empty() ? fs::path(".") : fs::path(outDir), ec).lexically_normal().string();
    // The result must read back as a scene (the one-encoding rule can break when adding).
    Result<Scene> check = parseScene(sceneToJson(out), outName);
    if (!check) return Error{"cannot apply the preset: the result " + check.error().message};
    return out;
}

std::string presetThumbnailPath(const std::string& presetPath) {
    return fs::path(presetPath).replace_extension(".png").string();
}

Result<Image> renderPresetThumbnail(const Scene& scene, int width, int height) {
    RenderRequest request = requestFromScene(scene);
    request.width = width;
    request.height = height;
    Image image = renderReference(scene, request);
    if (!allFinite(image)) return Error{"the thumbnail render produced non-finite pixels"};
    return image;
}

Result<void> savePresetWithThumbnail(const Preset& preset, const std::string& path, const std::string& sourceName,
                                     const Image* thumbnail) {
    if (Result<void> f = checkVolumeFiles(preset.volumes, "", sourceName); !f) return f;
    const std::string png = presetThumbnailPath(path);
    std::error_code ec;
    const bool hadPng = fs::exists(png, ec);
    if (thumbnail)
        if (Result<void> w = writePng(*thumbnail, png); !w) return w;
    Result<void> w = savePresetFile(preset, path, sourceName);
    if (!w && thumbnail && !hadPng) fs::remove(png, ec);
    return w;
}

std::vector<PresetListing> listPresets(const std::string& dir) {
    std::vector<PresetListing> out;
    std::error_code ec;
    std::vector<fs::path> files;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
        if (it->path().extension() == ".json" && it->is_regular_file(ec)) files.push_back(it->path());
    std::sort(files.begin(), files.end());
    for (const fs::path& f : files) {
        Result<std::string> text = scene_json::readTextFile(f.string());
        if (text) {
            const json j = json::parse(text.value(), nullptr, false);
            if (!j.is_discarded() && !(j.is_object() && j.contains(kVersionKey))) continue;
        }
        PresetListing l;
        l.path = f.string();
        Result<Preset> p = loadPresetFile(l.path);
        if (p) l.preset = std::move(p.value());
        else l.error = p.error().message;
        l.hasThumbnail = fs::is_regular_file(presetThumbnailPath(l.path), ec);
        out.push_back(std::move(l));
    }
    return out;
}

std::string userPresetDir() {
    if (const char* xdg = std::getenv("XDG_DATA_HOME"); xdg && *xdg) return (fs::path(xdg) / "brume" / "presets").string();
    if (const char* home = std::getenv("HOME"); home && *home)
        return (fs::path(home) / ".local" / "share" / "brume" / "presets").string();
    return {};
}

}  // namespace brume
