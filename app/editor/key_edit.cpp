// Document's key verbs (document.h): a key on a volume's or light's setting at a scene time, and
// its removal. A key records the object's own value of the setting (what the inspector edits), so
// "edit, then set key" at two times animates between the two values.
#include <algorithm>
#include <charconv>
#include <cmath>

#include <nlohmann/json.hpp>

#include "core/animate.h"
#include "document.h"
#include "io/scene_json.h"

namespace brume::editor {
namespace {

// Keys closer than this are the same key (a re-key replaces it; unkey finds it).
constexpr float kSameKeySeconds = 1.0e-4f;

struct KeyPath {
    bool light = false;
    size_t index = 0;
    std::string target;  // relative to the object: "medium.scattering"
};

// "volumes[2].medium.scattering" -> volume 2, "medium.scattering".
Result<KeyPath> parseKeyPath(const std::string& path) {
    KeyPath k;
    std::string rest;
    if (path.rfind("volumes[", 0) == 0) rest = path.substr(8);
    else if (path.rfind("lights[", 0) == 0) rest = path.substr(7), k.light = true;
    else return Error{path + ": keys go on a volume or light setting (volumes[i].KEY or lights[i].KEY)."};
    const size_t close = rest.find("].");
    const char* end = rest.data() + (close == std::string::npos ? 0 : close);
    if (close == std::string::npos || close == 0 || std::from_chars(rest.data(), end, k.index).ptr != end)
        return Error{path + ": keys go on a volume or light setting (volumes[i].KEY or lights[i].KEY)."};
    k.target = rest.substr(close + 2);
    return k;
}

bool parseSeconds(const std::string& s, float& out) {
    double d = 0.0;
    const char* end = s.data() + s.size();
    auto r = std::from_chars(s.data(), end, d);
    if (r.ec != std::errc() || r.ptr != end || !std::isfinite(d) || std::abs(d) > 1.0e6) return false;
    out = static_cast<float>(d);
    return true;
}

}  // namespace

Result<void> Document::key(const std::string& verb, const std::vector<std::string>& a) {
    if (verb == "interpolate") return interpolate(a);
    float time = 0.0f;
    if (a.size() != 2 || !parseSeconds(a[1], time))
        return Error{"The action \"" + verb + "\" takes: " + verb + " volumes[i].SETTING|lights[i].SETTING SECONDS."};
    Result<KeyPath> path = parseKeyPath(a[0]);
    if (!path) return path.error();
    const KeyPath& k = path.value();
    Scene next = scene_;
    const size_t count = k.light ? next.lights.size() : next.volumes.size();
    if (k.index >= count)
        return Error{a[0] + ": there is no " + (k.light ? "light " : "volume ") + std::to_string(k.index) + "."};
    std::vector<KeyTrack>& tracks = k.light ? next.lights[k.index].keys : next.volumes[k.index].keys;
    auto track = std::find_if(tracks.begin(), tracks.end(), [&](const KeyTrack& t) { return t.target == k.target; });
    if (verb == "unkey") {
        if (track == tracks.end()) return Error{a[0] + ": this setting has no keys."};
        auto key = std::find_if(track->keys.begin(), track->keys.end(),
                                [&](const Keyframe& f) { return std::abs(f.time - time) <= kSameKeySeconds; });
        if (key == track->keys.end()) return Error{a[0] + ": there is no key at " + a[1] + " s."};
        track->keys.erase(key);
        if (track->keys.empty()) tracks.erase(track);
        commit(std::move(next));
        return {};
    }
    const Setting* setting = k.light ? lightKeyTarget(next.lights[k.index].type, k.target)
                                     : volumeKeyTarget(next.volumes[k.index].type, k.target);
    if (!setting) return Error{a[0] + ": this setting cannot carry keys (docs/scene-format.md, \"Keyframes\")."};
    Result<std::string> text = valueText(a[0]);
    if (!text) return text.error();
    const nlohmann::json value = nlohmann::json::parse(text.value(), nullptr, false);
    Keyframe f;
    f.time = time;
    if (value.is_array() && value.size() == 3 && value[0].is_number())
        f.value = glm::vec3(value[0].get<float>(), value[1].get<float>(), value[2].get<float>());
    else if (value.is_number()) f.value = glm::vec3(value.get<float>(), 0.0f, 0.0f);
    else return Error{a[0] + ": this setting is not a number or a vec3, so it cannot carry keys."};
    if (track == tracks.end()) {
        tracks.push_back(KeyTrack{k.target, Interpolation::Linear, {}});
        track = tracks.end() - 1;
    }
    auto at = std::find_if(track->keys.begin(), track->keys.end(), [&](const Keyframe& g) { return g.time >= time - kSameKeySeconds; });
    if (at != track->keys.end() && std::abs(at->time - time) <= kSameKeySeconds) *at = f;
    else track->keys.insert(at, f);
    // The reader has the last word (ranges, keyable targets), as for every other edit.
    if (Result<Scene> check = parseScene(sceneToJson(next), "edit"); !check) return check.error();
    commit(std::move(next));
    return {};
}

// interpolate PATH linear|smooth: how a keyed setting moves between its keys (one undo step).
Result<void> Document::interpolate(const std::vector<std::string>& a) {
    if (a.size() != 2 || (a[1] != "linear" && a[1] != "smooth"))
        return Error{"The action \"interpolate\" takes: interpolate volumes[i].SETTING|lights[i].SETTING linear|smooth."};
    Result<KeyPath> path = parseKeyPath(a[0]);
    if (!path) return path.error();
    const KeyPath& k = path.value();
    Scene next = scene_;
    const size_t count = k.light ? next.lights.size() : next.volumes.size();
    if (k.index >= count)
        return Error{a[0] + ": there is no " + (k.light ? "light " : "volume ") + std::to_string(k.index) + "."};
    std::vector<KeyTrack>& tracks = k.light ? next.lights[k.index].keys : next.volumes[k.index].keys;
    auto track = std::find_if(tracks.begin(), tracks.end(), [&](const KeyTrack& t) { return t.target == k.target; });
    if (track == tracks.end()) return Error{a[0] + ": this setting has no keys."};
    const Interpolation mode = a[1] == "smooth" ? Interpolation::Smooth : Interpolation::Linear;
    if (track->interpolation == mode) return {};
    track->interpolation = mode;
    commit(std::move(next));
    return {};
}

}  // namespace brume::editor
