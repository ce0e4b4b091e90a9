#include "fog_source.h"

#include <filesystem>

#include "io/preset.h"
#include "io/scene_json.h"
#include "io/scene_json_parts.h"

namespace brume {

Result<FogSource> loadFogSource(const std::string& path) {
    Result<std::string> text = scene_json::readTextFile(path);
    if (!text) return text.error();
    FogSource out;
    out.name = std::filesystem::path(path).stem().string();
    // Only the top-level key decides; each reader then checks the whole file strictly.
    Result<nlohmann::json> root = scene_json::parseStrictJson(text.value(), path);
    if (!root) return root.error();
    if (root.value().is_object() && root.value().contains("brume_preset")) {
        Result<Preset> p = loadPresetFile(path);
        if (!p) return p.error();
        out.isPreset = true;
        out.name = p.value().name;
        out.scene.ambient = p.value().ambient;
        if (p.value().lights) out.scene.lights = *p.value().lights;
        out.scene.volumes = p.value().volumes;
        std::error_code ec;
        out.scene.baseDir = std::filesystem::absolute(path, ec).lexically_normal().parent_path().string();
        return out;
    }
    Result<Scene> s = loadSceneFile(path);
    if (!s) return s.error();
    out.scene = std::move(s.value());
    return out;
}

}  // namespace brume
