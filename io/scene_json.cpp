#include "scene_json.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <optional>
#include <set>
#include <type_traits>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/animate.h"
#include "io/atomic_file.h"
#include "io/one_line.h"

namespace brume {
namespace {

using json = nlohmann::json;
using ojson = nlohmann::ordered_json;

constexpr int kVersion = 1;

// ---------------------------------------------------------------------------------------------
// Formatting for messages and docs.

// Shortest digits that read back exactly; plain notation for everyday magnitudes, exponents for the
// rest ("0.0001", "16384", "1e+06").
std::string fmtNum(double v) {
    char buf[400];
    const double a = std::abs(v);
    const bool plain = a == 0.0 || (a >= 1.0e-4 && a < 1.0e5);
    const auto r = std::to_chars(buf, buf + sizeof buf, v, plain ? std::chars_format::fixed : std::chars_format::scientific);
    return std::string(buf, r.ptr);
}

std::string withUnit(double v, const Setting& s) {
    return s.unit.empty() ? fmtNum(v) : fmtNum(v) + " " + std::string(s.unit);
}

std::string rangeText(const Setting& s) {
    std::string r = "[" + fmtNum(s.min) + ", " + fmtNum(s.max) + "]";
    return s.unit.empty() ? r : r + " " + std::string(s.unit);
}

// The last component of a setting's path is its key in the object that holds it.
std::string keyOf(const Setting& s) {
    const size_t dot = s.path.rfind('.');
    return std::string(dot == std::string_view::npos ? s.path : s.path.substr(dot + 1));
}

std::vector<std::string> choicesOf(const Setting& s) {
    std::vector<std::string> out;
    size_t start = 0;
    while (start <= s.choices.size()) {
        const size_t bar = std::min(s.choices.find('|', start), s.choices.size());
        out.emplace_back(s.choices.substr(start, bar - start));
        start = bar + 1;
    }
    return out;
}

template <class List>
std::string joinList(const List& items) {
    std::string out;
    for (const auto& item : items) out += (out.empty() ? "" : ", ") + std::string(item);
    return out;
}

// How a wrong value is shown in a message: short, and never the whole of a big object.
std::string describe(const json& v) {
    if (v.is_object()) return "an object";
    if (v.is_array()) return "an array of " + std::to_string(v.size()) + (v.size() == 1 ? " value" : " values");
    std::string s = v.dump(-1, ' ', false, json::error_handler_t::replace);
    return s.size() > 40 ? s.substr(0, 37) + "..." : s;
}

// Control characters in a key are written escaped (cam\nt), so an error naming it stays one
// line (found by tests/fuzz/fuzz_scene_json and fuzz_preset_json: a key holding a newline).
std::string child(const std::string& path, std::string_view key) {
    const std::string k = escapeControlCharacters(key);
    return path.empty() ? k : path + "." + k;
}

std::string indexed(const std::string& path, size_t i) { return path + "[" + std::to_string(i) + "]"; }

}  // namespace

namespace {

// ---------------------------------------------------------------------------------------------
// Reading. The first error wins: later checks still run but cannot replace it, so the readers
// below stay linear instead of testing a result after every key.

struct Ctx {
    const std::string& file;
    std::optional<Error> error;

    void fail(const std::string& path, const std::string& what) {
        if (!error) error = Error{file + ": " + (path.empty() ? "" : path + ": ") + what};
    }
    bool failed() const { return error.has_value(); }
};

// Edit distance counting a swap of neighbours as one edit ("widht"), for "did you mean" (keys are
// short: the quadratic cost is nothing).
size_t editDistance(std::string_view a, std::string_view b) {
    std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
    for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
    for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
    for (size_t i = 1; i <= a.size(); ++i)
        for (size_t j = 1; j <= b.size(); ++j) {
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[a.size()][b.size()];
}

// The key of `candidates` nearest to `key`, if near enough to be the one meant.
std::optional<std::string> closestKey(const std::string& key, const std::vector<std::string>& candidates) {
    std::optional<std::string> best;
    size_t bestDistance = std::max<size_t>(1, std::min<size_t>(3, key.size() / 3)) + 1;
    for (const std::string& k : candidates) {
        const size_t d = editDistance(key, k);
        if (d < bestDistance) {
            bestDistance = d;
            best = k;
        }
    }
    return best;
}

// One JSON object being read, after pbrt-v4's ParameterDictionary: every lookup names a key the
// reader knows and marks it used when present; finish() reports the first key nobody looked up,
// listing the keys that were. So each key is spelled once, where it is read, and the allowed keys
// of an object are exactly those its reader asks for.
// Unknown keys are reported before problems with the object's values (a misspelt key usually causes
// them: "fiel" leaves "file" missing), so finish() replaces an error raised while this object was
// read. Readers therefore look up every key they know even after an error.
class Obj {
public:
    // `where` names the object in the message ("a box volume").
    Obj(Ctx& c, const json& v, std::string path, std::string where)
        : path(std::move(path)), c_(c), v_(v), where_(std::move(where)), errorBefore_(c.failed()) {
        if (!v.is_object()) c.fail(this->path, "expected an object, got " + describe(v));
    }
    bool isObject() const { return v_.is_object(); }
    const json& raw() const { return v_; }
    void setWhere(std::string where) { where_ = std::move(where); }

    const json* get(std::string_view key) {
        if (std::find(asked_.begin(), asked_.end(), key) == asked_.end()) asked_.emplace_back(key);
        if (!v_.is_object()) return nullptr;
        const auto it = v_.find(std::string(key));
        return it == v_.end() ? nullptr : &*it;
    }
    bool has(std::string_view key) { return get(key) != nullptr; }
    std::string at(std::string_view key) const { return child(path, key); }

    void finish() {
        if (errorBefore_ || !v_.is_object()) return;
        for (const auto& item : v_.items()) {
            if (std::find(asked_.begin(), asked_.end(), item.key()) != asked_.end()) continue;
            std::string what = "unknown key";
            if (const std::optional<std::string> near = closestKey(item.key(), asked_)) what += " (did you mean \"" + *near + "\"?)";
            c_.error.reset();
            c_.fail(at(item.key()), what + "; allowed in " + where_ + ": " + joinList(asked_));
            return;
        }
    }

    const std::string path;  // the object's JSON path

private:
    Ctx& c_;
    const json& v_;
    std::string where_;
    bool errorBefore_;
    std::vector<std::string> asked_;
};

// The range is checked on the float that will be stored as well as on the written value, so that a
// float sitting on a bound (float(1e-4) < 1e-4) reads back after being written.
bool inRange(double d, const Setting& s) {
    if (d >= s.min && d <= s.max) return true;
    if (std::abs(d) > 1.0e38) return false;
    const float f = static_cast<float>(d);
    return f == static_cast<float>(s.min) || f == static_cast<float>(s.max);
}

std::optional<double> asNumber(Ctx& c, const json& v, const std::string& path, const Setting& s) {
    if (!v.is_number()) {
        c.fail(path, "expected a number, got " + describe(v));
        return std::nullopt;
    }
    const double d = v.get<double>();
    if (!std::isfinite(d)) {
        c.fail(path, "expected a finite number, got " + v.dump());
        return std::nullopt;
    }
    if (!inRange(d, s)) {
        c.fail(path, withUnit(d, s) + " is out of range " + rangeText(s));
        return std::nullopt;
    }
    return d;
}

std::optional<int> asInteger(Ctx& c, const json& v, const std::string& path, const Setting& s) {
    if (!v.is_number()) {
        c.fail(path, "expected an integer, got " + describe(v));
        return std::nullopt;
    }
    const double d = v.get<double>();
    if (!std::isfinite(d) || d != std::floor(d)) {
        c.fail(path, "expected an integer, got " + v.dump());
        return std::nullopt;
    }
    if (d < s.min || d > s.max) {
        c.fail(path, withUnit(d, s) + " is out of range " + rangeText(s));
        return std::nullopt;
    }
    return static_cast<int>(d);
}

std::optional<glm::vec3> asVec3(Ctx& c, const json& v, const std::string& path, const Setting& s) {
    if (!v.is_array() || v.size() != 3) {
        c.fail(path, "expected an array of 3 numbers, got " + describe(v));
        return std::nullopt;
    }
    glm::vec3 out;
    for (size_t i = 0; i < 3; ++i) {
        const std::optional<double> d = asNumber(c, v[i], indexed(path, i), s);
        if (!d) return std::nullopt;
        out[static_cast<int>(i)] = static_cast<float>(*d);
    }
    return out;
}

// Each read* leaves `out` (already holding the default) alone when the key is absent or invalid.
void readFloat(Ctx& c, Obj& o, const Setting& s, float& out) {
    const std::string key = keyOf(s);
    if (const json* v = o.get(key))
        if (const std::optional<double> d = asNumber(c, *v, o.at(key), s)) out = static_cast<float>(*d);
}

void readInt(Ctx& c, Obj& o, const Setting& s, int& out) {
    const std::string key = keyOf(s);
    if (const json* v = o.get(key))
        if (const std::optional<int> i = asInteger(c, *v, o.at(key), s)) out = *i;
}

void readVec3(Ctx& c, Obj& o, const Setting& s, glm::vec3& out) {
    const std::string key = keyOf(s);
    if (const json* v = o.get(key))
        if (const std::optional<glm::vec3> x = asVec3(c, *v, o.at(key), s)) out = *x;
}

void readBool(Ctx& c, Obj& o, const Setting& s, bool& out) {
    const std::string key = keyOf(s);
    const json* v = o.get(key);
    if (!v) return;
    if (v->is_boolean()) out = v->get<bool>();
    else c.fail(o.at(key), "expected true or false, got " + describe(*v));
}

// A string. File and grid names must not be empty; a required one's `required` says what it is for
// the message when it is absent.
enum class Text { Any, NonEmpty };
void readString(Ctx& c, Obj& o, const Setting& s, std::string& out, Text rule = Text::Any, const char* required = nullptr) {
    const std::string key = keyOf(s);
    const json* v = o.get(key);
    if (!v) {
        if (required) c.fail(o.at(key), std::string("missing required key (") + required + ")");
        return;
    }
    if (!v->is_string()) {
        c.fail(o.at(key), "expected a string, got " + describe(*v));
        return;
    }
    out = v->get<std::string>();
    if (out.empty() && rule == Text::NonEmpty) c.fail(o.at(key), "must not be empty");
}

// Choices are matched against the enum's toString(), so settings.h and scene.h cannot disagree
// silently (the round-trip test would fail).
template <class E, int N>
std::optional<E> asEnum(Ctx& c, const json& v, const std::string& path, const Setting& s) {
    const std::vector<std::string> choices = choicesOf(s);
    if (!v.is_string()) {
        c.fail(path, "expected a string (one of " + joinList(choices) + "), got " + describe(v));
        return std::nullopt;
    }
    const std::string name = v.get<std::string>();
    for (int i = 0; i < N; ++i)
        if (name == toString(static_cast<E>(i))) return static_cast<E>(i);
    c.fail(path, "unknown choice " + describe(v) + "; choices: " + joinList(choices));
    return std::nullopt;
}

template <class E, int N>
void readEnum(Ctx& c, Obj& o, const Setting& s, E& out) {
    const std::string key = keyOf(s);
    if (const json* v = o.get(key))
        if (const std::optional<E> e = asEnum<E, N>(c, *v, o.at(key), s)) out = *e;
}

// The "type" of a list element: required, and decides which keys are allowed.
template <class E, int N>
std::optional<E> readType(Ctx& c, Obj& o, const Setting& s) {
    if (!o.isObject()) return std::nullopt;
    const json* v = o.get(keyOf(s));
    if (!v) {
        c.fail(o.at(keyOf(s)), "missing required key; choices: " + joinList(choicesOf(s)));
        return std::nullopt;
    }
    return asEnum<E, N>(c, *v, o.at(keyOf(s)), s);
}

}  // namespace

namespace {

namespace st = settings;

// Direction-like vectors are compared in double: positions up to 1e6 m keep their differences.
glm::dvec3 toD(glm::vec3 v) { return glm::dvec3(v); }

void checkCamera(Ctx& c, const std::string& path, const Camera& cam) {
    if (c.failed()) return;
    if (!(cam.far > cam.near))
        c.fail(child(path, "far"), withUnit(cam.far, st::camera_far) + " must exceed camera.near (" +
                                       withUnit(cam.near, st::camera_near) + ")");
    const glm::dvec3 view = toD(cam.target) - toD(cam.position);
    if (view == glm::dvec3(0.0)) {
        c.fail(child(path, "target"), "must differ from camera.position");
        return;
    }
    const glm::dvec3 up = toD(cam.up);
    // Below this sine the look-at basis loses most of its precision.
    constexpr double kMinSine = 1.0e-3;
    if (glm::length(up) == 0.0 || glm::length(glm::cross(glm::normalize(up), glm::normalize(view))) < kMinSine)
        c.fail(child(path, "up"), "must not be zero or parallel to the view direction (target - position)");
}

// The object under `key` of `parent`, read by `read(Obj&)` and checked for unknown keys.
template <class ReadFn>
void readChild(Ctx& c, Obj& parent, std::string_view key, const char* where, ReadFn read) {
    const json* v = parent.get(key);
    if (!v) return;
    Obj o(c, *v, parent.at(key), where);
    if (o.isObject()) read(o);
    o.finish();
}

void readCamera(Ctx& c, Obj& o, Camera& cam) {
    readVec3(c, o, st::camera_position, cam.position);
    readVec3(c, o, st::camera_target, cam.target);
    readVec3(c, o, st::camera_up, cam.up);
    readFloat(c, o, st::camera_fov_y, cam.fov_y_deg);
    readFloat(c, o, st::camera_near, cam.near);
    readFloat(c, o, st::camera_far, cam.far);
    checkCamera(c, o.path, cam);
}

void readRender(Ctx& c, Obj& o, RenderBlock& r) {
    readInt(c, o, st::render_width, r.width);
    readInt(c, o, st::render_height, r.height);
    readEnum<Quality, 4>(c, o, st::render_quality, r.quality);
    readInt(c, o, st::render_frames, r.frames);
}

template <class T>
void readOptional(Ctx& c, Obj& o, const Setting& s, std::optional<T>& out) {
    if (!o.has(keyOf(s))) return;
    T value{};
    if constexpr (std::is_same_v<T, int>) readInt(c, o, s, value);
    else readFloat(c, o, s, value);
    if (!c.failed()) out = value;
}

void readFroxels(Ctx& c, Obj& o, FroxelOverrides& f) {
    readOptional(c, o, st::froxels_tile_px, f.tile_px);
    readOptional(c, o, st::froxels_slices, f.slices);
    readOptional(c, o, st::froxels_near, f.near);
    readOptional(c, o, st::froxels_far, f.far);
    readOptional(c, o, st::froxels_distribution, f.distribution);
    if (!c.failed() && f.near && f.far && !(*f.far > *f.near))
        c.fail(o.at("far"), withUnit(*f.far, st::froxels_far) + " must exceed froxels.near (" +
                                withUnit(*f.near, st::froxels_near) + ")");
}

void readTemporal(Ctx& c, Obj& o, Temporal& t) {
    readBool(c, o, st::temporal_enabled, t.enabled);
    readFloat(c, o, st::temporal_history_weight, t.history_weight);
}

void readTransform(Ctx& c, Obj& parent, Transform& t) {
    readChild(c, parent, "transform", "a transform", [&](Obj& o) {
        readVec3(c, o, st::transform_translation, t.translation);
        readVec3(c, o, st::transform_rotation, t.rotation_deg);
        readVec3(c, o, st::transform_scale, t.scale);
    });
}

void readMedium(Ctx& c, Obj& parent, Medium& m) {
    readChild(c, parent, "medium", "a medium", [&](Obj& o) {
        readVec3(c, o, st::medium_scattering, m.scattering);
        readVec3(c, o, st::medium_absorption, m.absorption);
        readVec3(c, o, st::medium_emission, m.emission);
        readFloat(c, o, st::medium_phase_g, m.phase_g);
    });
}

}  // namespace

namespace {

// Directions are stored normalized; one already unit within float precision is kept bit for bit
// so that writing and reading again changes nothing.
void normalizeDirection(Ctx& c, const std::string& path, glm::vec3& dir) {
    const double len = glm::length(toD(dir));
    if (len < 1.0e-6) {
        c.fail(child(path, "direction"), "must not be zero");
        return;
    }
    if (std::abs(len - 1.0) > 1.0e-6) dir = glm::vec3(toD(dir) / len);
}

// "keys": {"TARGET": LIST, ...}, LIST = [KEY, ...] (linear) or {"interpolation": "linear" | "smooth",
// "keys": [KEY, ...]}, KEY = {"time": s, "value": v}. `targetOf` names the setting a target drives
// (null: not keyable on this object's type); `keyable` lists those that are, for the message.
void readKeyframe(Ctx& c, const json& v, const std::string& path, const Setting& target, KeyTrack& track) {
    Obj o(c, v, path, "a key");
    if (!o.isObject()) return;
    Keyframe k;
    const json* time = o.get(keyOf(st::keys_time));
    const json* value = o.get(keyOf(st::keys_value));
    if (!time) c.fail(o.at(keyOf(st::keys_time)), "missing required key (the key's scene time in s)");
    else if (const std::optional<double> t = asNumber(c, *time, o.at(keyOf(st::keys_time)), st::keys_time)) k.time = static_cast<float>(*t);
    if (!value) c.fail(o.at(keyOf(st::keys_value)), "missing required key (the setting's value at that time)");
    else if (target.kind == SettingKind::Vec3) {
        if (const std::optional<glm::vec3> x = asVec3(c, *value, o.at(keyOf(st::keys_value)), target)) k.value = *x;
    } else if (const std::optional<double> d = asNumber(c, *value, o.at(keyOf(st::keys_value)), target)) {
        k.value = glm::vec3(static_cast<float>(*d), 0.0f, 0.0f);
    }
    if (!c.failed() && !track.keys.empty() && !(k.time > track.keys.back().time))
        c.fail(o.at(keyOf(st::keys_time)), withUnit(k.time, st::keys_time) + " is not after the previous key's time (" +
                                               withUnit(track.keys.back().time, st::keys_time) +
                                               "); a list's keys must be in increasing time");
    o.finish();
    track.keys.push_back(k);
}

template <class TargetOf>
void readKeys(Ctx& c, Obj& parent, const std::string& where, TargetOf targetOf, const std::vector<std::string>& keyable,
              std::vector<KeyTrack>& out) {
    readChild(c, parent, "keys", "keys", [&](Obj& o) {
        for (const auto& item : o.raw().items()) o.get(item.key());  // every target is checked below
        for (const auto& item : o.raw().items()) {
            const std::string path = o.at(item.key());
            const Setting* target = targetOf(item.key());
            if (!target) {
                std::string what = "not a keyable setting of " + where;
                if (const std::optional<std::string> near = closestKey(item.key(), keyable)) what += " (did you mean \"" + *near + "\"?)";
                c.fail(path, what + "; keyable: " + joinList(keyable));
                return;
            }
            KeyTrack track;
            track.target = item.key();
            const json* list = &item.value();
            std::string listPath = path;
            std::optional<Obj> form;
            if (list->is_object()) {
                form.emplace(c, *list, path, "a key list");
                readEnum<Interpolation, 2>(c, *form, st::keys_interpolation, track.interpolation);
                list = form->get("keys");
                listPath = form->at("keys");
                if (!list) c.fail(listPath, "missing required key (the list of keys {\"time\": s, \"value\": v})");
            }
            if (list && (!list->is_array() || list->empty()))
                c.fail(listPath, "expected an array of at least one key {\"time\": s, \"value\": v}, got " + describe(*list));
            else if (list)
                for (size_t i = 0; i < list->size() && !c.failed(); ++i) readKeyframe(c, (*list)[i], indexed(listPath, i), *target, track);
            if (form) form->finish();
            if (c.failed()) return;
            out.push_back(std::move(track));
        }
    });
}

// The keys of each type are those its branch looks up, in the order the messages list them.
std::optional<Light> readLight(Ctx& c, const json& v, const std::string& path) {
    Obj o(c, v, path, "a light");
    const std::optional<LightType> type = readType<LightType, 3>(c, o, st::light_type);
    if (!type) return std::nullopt;
    o.setWhere(std::string("a ") + toString(*type) + " light");
    Light l = makeLight(*type);
    const bool local = *type != LightType::Directional;
    readString(c, o, st::light_name, l.name);
    if (local) readVec3(c, o, st::light_position, l.position);
    if (*type != LightType::Point) readVec3(c, o, st::light_direction, l.direction);
    if (*type == LightType::Spot) {
        readFloat(c, o, st::light_inner_deg, l.inner_deg);
        readFloat(c, o, st::light_outer_deg, l.outer_deg);
    }
    readVec3(c, o, st::light_color, l.color);
    readFloat(c, o, local ? st::light_intensity_local : st::light_intensity_directional, l.intensity);
    if (local) readFloat(c, o, st::light_range, l.range);
    readBool(c, o, local ? st::light_shadows_local : st::light_shadows_directional, l.shadows);
    readFloat(c, o, st::light_fog_scale, l.fog_scale);
    readKeys(c, o, std::string("a ") + toString(*type) + " light",
             [&](const std::string& t) { return lightKeyTarget(*type, t); }, lightKeyTargets(*type), l.keys);
    if (*type != LightType::Point && !c.failed()) normalizeDirection(c, path, l.direction);
    if (*type == LightType::Spot && !c.failed() && l.inner_deg > l.outer_deg)
        c.fail(o.at("inner_deg"), withUnit(l.inner_deg, st::light_inner_deg) + " must not exceed outer_deg (" +
                                      withUnit(l.outer_deg, st::light_outer_deg) + ")");
    o.finish();
    return l;
}

// The GPU samples all vdb volumes of a frame with one shader variant, compiled for one encoding
// (docs/vdb.md "Encodings"), so a scene's vdb volumes share one: the first one's.
void checkOneEncoding(Ctx& c, const std::vector<Volume>& volumes) {
    const Volume* first = nullptr;
    size_t firstIndex = 0;
    for (size_t i = 0; i < volumes.size() && !c.failed(); ++i) {
        if (volumes[i].type != VolumeType::Vdb) continue;
        if (!first) {
            first = &volumes[i];
            firstIndex = i;
        } else if (volumes[i].encoding != first->encoding) {
            c.fail("volumes[" + std::to_string(i) + "].encoding",
                   "is \"" + std::string(toString(volumes[i].encoding)) + "\" but volumes[" + std::to_string(firstIndex) +
                       "] is \"" + toString(first->encoding) + "\"; all vdb volumes of a scene must use the same encoding");
        }
    }
}

void readDensityTexture(Ctx& c, Obj& parent, Volume& vol) {
    readChild(c, parent, "density_texture", "density_texture", [&](Obj& o) {
        DensityTexture tex;
        readString(c, o, st::texture_file, tex.file, Text::NonEmpty, "the OpenVDB file of the texture");
        readString(c, o, st::texture_grid, tex.grid, Text::NonEmpty);
        readFloat(c, o, st::texture_tile_size, tex.tile_size_m);
        readVec3(c, o, st::texture_scroll, tex.scroll_mps);
        readFloat(c, o, st::texture_strength, tex.strength);
        readFloat(c, o, st::texture_exponent, tex.exponent);
        readChild(c, o, "detail", "density_texture.detail", [&](Obj& d) {
            TextureLayer layer = makeDetailLayer();
            readString(c, d, st::detail_file, layer.file, Text::NonEmpty, "the OpenVDB file of the detail layer");
            readString(c, d, st::detail_grid, layer.grid, Text::NonEmpty);
            readFloat(c, d, st::detail_tile_size, layer.tile_size_m);
            readVec3(c, d, st::detail_scroll, layer.scroll_mps);
            readFloat(c, d, st::detail_strength, layer.strength);
            readFloat(c, d, st::detail_exponent, layer.exponent);
            if (!c.failed()) tex.detail = layer;
        });
        if (!c.failed()) vol.density_texture = tex;
    });
}

std::vector<std::string> keyableOn(const Volume& v) {
    std::vector<std::string> out = volumeKeyTargets(v.type);
    if (!v.density_texture)
        std::erase_if(out, [](const std::string& t) { return t.starts_with("density_texture."); });
    return out;
}

std::optional<Volume> readVolume(Ctx& c, const json& v, const std::string& path) {
    Obj o(c, v, path, "a volume");
    const std::optional<VolumeType> type = readType<VolumeType, 7>(c, o, st::volume_type);
    if (!type) return std::nullopt;
    o.setWhere(std::string("a ") + toString(*type) + " volume");
    Volume vol;
    vol.type = *type;
    readString(c, o, st::volume_name, vol.name);
    switch (*type) {
        case VolumeType::Box:
        case VolumeType::Ellipsoid:
        case VolumeType::Cylinder:
            readTransform(c, o, vol.transform);
            readFloat(c, o, st::volume_edge_fade, vol.edge_fade);
            readFloat(c, o, st::volume_height_falloff, vol.height_falloff);
            break;
        case VolumeType::Height:
            readFloat(c, o, st::volume_base_height, vol.base_height);
            readEnum<HeightProfile, 2>(c, o, st::volume_profile, vol.profile);
            readFloat(c, o, st::volume_falloff, vol.falloff);
            readFloat(c, o, st::volume_transition_height, vol.transition_height);
            break;
        case VolumeType::Depth:
            readFloat(c, o, st::volume_visibility_distance, vol.visibility_distance);
            readFloat(c, o, st::volume_start_distance, vol.start_distance);
            break;
        case VolumeType::Vdb:
            readString(c, o, st::volume_file, vol.file, Text::NonEmpty, "the OpenVDB file of a vdb volume");
            readString(c, o, st::volume_grid, vol.grid, Text::NonEmpty);
            readEnum<VdbEncoding, 3>(c, o, st::volume_encoding, vol.encoding);
            readTransform(c, o, vol.transform);
            readFloat(c, o, st::volume_density_scale, vol.density_scale);
            readFloat(c, o, st::volume_height_falloff, vol.height_falloff);
            break;
        case VolumeType::Mesh:
            readString(c, o, st::volume_mesh_file, vol.file, Text::NonEmpty, "the mesh file (OBJ or PLY) of a mesh volume");
            readFloat(c, o, st::volume_edge_fade_m, vol.edge_fade_m);
            readTransform(c, o, vol.transform);
            readFloat(c, o, st::volume_height_falloff, vol.height_falloff);
            break;
    }
    readDensityTexture(c, o, vol);
    readMedium(c, o, vol.medium);
    readKeys(c, o, std::string("a ") + toString(*type) + " volume" + (vol.density_texture ? " with a density_texture" : ""),
             [&](const std::string& t) {
                 return t.starts_with("density_texture.") && !vol.density_texture ? nullptr : volumeKeyTarget(*type, t);
             },
             keyableOn(vol), vol.keys);
    o.finish();
    return vol;
}

// "path": [{"time": s, "position": [x, y, z]}, ...]: at least 2 points in strictly increasing time.
void readInfluencerPath(Ctx& c, Obj& o, KeyTrack& track) {
    track.target = "position";
    const json* list = o.get("path");
    const std::string path = o.at("path");
    if (!list) {
        c.fail(path, "missing required key (at least 2 points {\"time\": s, \"position\": [x, y, z]})");
        return;
    }
    if (!list->is_array() || list->size() < 2) {
        c.fail(path, "expected an array of at least 2 points {\"time\": s, \"position\": [x, y, z]}, got " + describe(*list));
        return;
    }
    for (size_t i = 0; i < list->size() && !c.failed(); ++i) {
        Obj p(c, (*list)[i], indexed(path, i), "a path point");
        if (!p.isObject()) return;
        Keyframe k;
        const json* time = p.get(keyOf(st::influencer_path_time));
        const json* position = p.get(keyOf(st::influencer_path_position));
        if (!time) c.fail(p.at(keyOf(st::influencer_path_time)), "missing required key (the point's scene time in s)");
        else if (const std::optional<double> t = asNumber(c, *time, p.at(keyOf(st::influencer_path_time)), st::influencer_path_time))
            k.time = static_cast<float>(*t);
        if (!position) c.fail(p.at(keyOf(st::influencer_path_position)), "missing required key (the centre at that time in m)");
        else if (const std::optional<glm::vec3> x = asVec3(c, *position, p.at(keyOf(st::influencer_path_position)), st::influencer_path_position))
            k.value = *x;
        if (!c.failed() && !track.keys.empty() && !(k.time > track.keys.back().time))
            c.fail(p.at(keyOf(st::influencer_path_time)), withUnit(k.time, st::influencer_path_time) +
                                                              " is not after the previous point's time (" +
                                                              withUnit(track.keys.back().time, st::influencer_path_time) +
                                                              "); a path's points must be in increasing time");
        p.finish();
        track.keys.push_back(k);
    }
}

std::optional<Influencer> readInfluencer(Ctx& c, const json& v, const std::string& path) {
    Obj o(c, v, path, "an influencer");
    const std::optional<InfluencerType> type = readType<InfluencerType, 2>(c, o, st::influencer_type);
    if (!type) return std::nullopt;
    o.setWhere(std::string("a ") + toString(*type) + " influencer");
    Influencer f;
    f.type = *type;
    readString(c, o, st::influencer_name, f.name);
    readFloat(c, o, st::influencer_radius, f.radius);
    if (*type == InfluencerType::Capsule) readFloat(c, o, st::influencer_length, f.length);
    readFloat(c, o, st::influencer_strength, f.strength);
    readFloat(c, o, st::influencer_half_life, f.wake_half_life_s);
    readFloat(c, o, st::influencer_wake_step, f.wake_step_s);
    readInt(c, o, st::influencer_wake_samples, f.wake_samples);
    readEnum<Interpolation, 2>(c, o, st::influencer_path_interpolation, f.path.interpolation);
    readInfluencerPath(c, o, f.path);
    o.finish();
    return f;
}

std::optional<Geometry> readGeometry(Ctx& c, const json& v, const std::string& path) {
    Obj o(c, v, path, "a geometry");
    const std::optional<GeometryType> type = readType<GeometryType, 3>(c, o, st::geometry_type);
    if (!type) return std::nullopt;
    o.setWhere(std::string("a ") + toString(*type));
    Geometry g;
    g.type = *type;
    readString(c, o, st::geometry_name, g.name);
    if (*type == GeometryType::Plane) readFloat(c, o, st::geometry_height, g.height);
    if (*type == GeometryType::Box) readTransform(c, o, g.transform);
    if (*type == GeometryType::Sphere) {
        readVec3(c, o, st::geometry_center, g.center);
        readFloat(c, o, st::geometry_radius, g.radius);
    }
    readVec3(c, o, st::geometry_albedo, g.albedo);
    readVec3(c, o, st::geometry_emission, g.emission);
    o.finish();
    return g;
}

template <class T, class ReadOne>
void readArray(Ctx& c, const json& v, const std::string& path, std::vector<T>& out, ReadOne readOne) {
    if (!v.is_array()) {
        c.fail(path, "expected an array, got " + describe(v));
        return;
    }
    for (size_t i = 0; i < v.size() && !c.failed(); ++i)
        if (std::optional<T> item = readOne(c, v[i], indexed(path, i))) out.push_back(std::move(*item));
}

template <class T, class ReadOne>
void readList(Ctx& c, Obj& parent, std::string_view key, std::vector<T>& out, ReadOne readOne) {
    if (const json* v = parent.get(key)) readArray(c, *v, parent.at(key), out, readOne);
}

}  // namespace

namespace {

// nlohmann keeps the last of two equal keys; a strict reader reports them instead. The callback
// tracks the path of the object being parsed to name the duplicate.
class DuplicateKeyFinder {
public:
    bool operator()(int, json::parse_event_t event, json& parsed) {
        using E = json::parse_event_t;
        if (event == E::object_start || event == E::array_start) stack_.push_back(Frame{event == E::array_start, {}, {}, 0});
        if (event == E::object_end || event == E::array_end) {
            stack_.pop_back();
            if (!stack_.empty() && stack_.back().array) ++stack_.back().index;
        }
        if (event == E::value && !stack_.empty() && stack_.back().array) ++stack_.back().index;
        if (event == E::key) {
            Frame& f = stack_.back();
            f.key = parsed.get<std::string>();
            if (!f.keys.insert(f.key).second && !duplicate) duplicate = currentPath();
        }
        return true;
    }
    std::optional<std::string> duplicate;

private:
    struct Frame {
        bool array;
        std::set<std::string> keys;
        std::string key;
        size_t index;
    };
    std::string currentPath() const {
        std::string path;
        for (const Frame& f : stack_) path = f.array ? indexed(path, f.index) : child(path, f.key);
        return path;
    }
    std::vector<Frame> stack_;
};

std::string lineColumn(std::string_view text, size_t offset) {
    const size_t at = std::min(offset, text.size());
    const std::string_view before = text.substr(0, at);
    const size_t line = 1 + static_cast<size_t>(std::count(before.begin(), before.end(), '\n'));
    const size_t lastNewline = before.rfind('\n');
    const size_t column = lastNewline == std::string_view::npos ? at + 1 : at - lastNewline;
    return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

std::optional<json> parseJson(Ctx& c, std::string_view text) {
    DuplicateKeyFinder dups;
    try {
        json root = json::parse(text.begin(), text.end(), std::ref(dups));
        if (dups.duplicate) {
            c.fail(*dups.duplicate, "duplicate key");
            return std::nullopt;
        }
        return root;
    } catch (const json::parse_error& e) {
        std::string what = e.what();
        const size_t colon = what.find(": ", what.find("column"));
        if (colon != std::string::npos) what = what.substr(colon + 2);
        c.fail(lineColumn(text, e.byte > 0 ? e.byte - 1 : 0), "JSON " + what);
    } catch (const json::out_of_range& e) {
        // Thrown for a number too large for a double (1e999): JSON has no Inf, so this is the only
        // way a non-finite number reaches us. It carries no position; the token's first occurrence
        // is the best guess.
        const std::string what = e.what();
        const size_t q0 = what.find('\'');
        const size_t q1 = what.rfind('\'');
        const std::string token = q0 < q1 ? what.substr(q0 + 1, q1 - q0 - 1) : std::string();
        const size_t at = token.empty() ? std::string_view::npos : text.find(token);
        c.fail(at == std::string_view::npos ? std::string() : lineColumn(text, at),
               "number " + token + " is not finite (it overflows a double)");
    }
    return std::nullopt;
}

bool checkVersion(Ctx& c, Obj& root) {
    const json* v = root.get("brume_scene");
    if (!v) {
        c.fail("brume_scene", "missing required key (the format version; this build reads " +
                                  std::to_string(kVersion) + ")");
        return false;
    }
    if (!v->is_number_integer() && !(v->is_number_float() && v->get<double>() == std::floor(v->get<double>()))) {
        c.fail("brume_scene", "expected an integer, got " + describe(*v));
        return false;
    }
    if (v->get<double>() != kVersion) {
        c.fail("brume_scene", "unsupported version " + v->dump() + " (this build reads version " +
                                  std::to_string(kVersion) + ")");
        return false;
    }
    return true;
}

void readScene(Ctx& c, const json& root, Scene& s) {
    if (!root.is_object()) {
        c.fail("", "expected a JSON object at the top level, got " + describe(root));
        return;
    }
    Obj o(c, root, "", "a scene");
    if (!checkVersion(c, o)) return;
    s.version = kVersion;
    readChild(c, o, "camera", "camera", [&](Obj& x) { readCamera(c, x, s.camera); });
    readChild(c, o, "render", "render", [&](Obj& x) { readRender(c, x, s.render); });
    readChild(c, o, "froxels", "froxels", [&](Obj& x) { readFroxels(c, x, s.froxels); });
    readChild(c, o, "temporal", "temporal", [&](Obj& x) { readTemporal(c, x, s.temporal); });
    readVec3(c, o, st::ambient, s.ambient);
    readList(c, o, "lights", s.lights, readLight);
    readList(c, o, "volumes", s.volumes, readVolume);
    checkOneEncoding(c, s.volumes);
    readList(c, o, "geometry", s.geometry, readGeometry);
    readList(c, o, "influencers", s.influencers, readInfluencer);
    o.finish();
}

Result<std::string> readTextFile(const std::string& path) {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return Error{path + ": cannot read: " + std::strerror(errno)};
    std::string text;
    char buf[65536];
    size_t n = 0;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) text.append(buf, n);
    const int err = std::ferror(f) ? errno : 0;
    std::fclose(f);
    if (err != 0) return Error{path + ": cannot read: " + std::strerror(err)};
    return text;
}

}  // namespace

Result<Scene> parseScene(std::string_view text, const std::string& fileName) {
    Ctx c{fileName, std::nullopt};
    const std::optional<json> root = parseJson(c, text);
    if (!root) return *c.error;
    Scene s;
    readScene(c, *root, s);
    if (c.error) return *c.error;
    return s;
}

Result<Scene> loadSceneFile(const std::string& path) {
    Result<std::string> text = readTextFile(path);
    if (!text) return text.error();
    Result<Scene> scene = parseScene(text.value(), path);
    if (!scene) return scene;
    std::error_code ec;
    const std::filesystem::path abs = std::filesystem::absolute(path, ec);
    if (ec) return Error{path + ": cannot resolve the scene's folder: " + ec.message()};
    scene.value().baseDir = abs.lexically_normal().parent_path().string();
    return scene;
}

// ---------------------------------------------------------------------------------------------
// Writing.

namespace {

// The fewest decimal digits that read back to the same float. The reader goes text -> double ->
// float; in the rare case where that double rounding lands on a neighbour, the exact double value
// of the float is written instead (17 digits, always exact).
ojson num(float f) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, f);
    double d = std::strtod(std::string(buf, r.ptr).c_str(), nullptr);
    if (static_cast<float>(d) != f) d = static_cast<double>(f);
    return d;
}

ojson vec(glm::vec3 v) { return ojson::array({num(v.x), num(v.y), num(v.z)}); }

ojson transformJson(const Transform& t) {
    ojson j;
    j["translation"] = vec(t.translation);
    j["rotation_deg"] = vec(t.rotation_deg);
    j["scale"] = vec(t.scale);
    return j;
}

ojson mediumJson(const Medium& m) {
    ojson j;
    j["scattering"] = vec(m.scattering);
    j["absorption"] = vec(m.absorption);
    j["emission"] = vec(m.emission);
    j["phase_g"] = num(m.phase_g);
    return j;
}

ojson keysJson(const std::vector<KeyTrack>& tracks, const std::function<const Setting*(const std::string&)>& targetOf) {
    ojson j = ojson::object();
    for (const KeyTrack& t : tracks) {
        const Setting* s = targetOf(t.target);
        ojson list = ojson::array();
        for (const Keyframe& k : t.keys) {
            ojson kj;
            kj["time"] = num(k.time);
            kj["value"] = s && s->kind == SettingKind::Vec3 ? vec(k.value) : num(k.value.x);
            list.push_back(kj);
        }
        if (t.interpolation == Interpolation::Linear) j[t.target] = list;
        else j[t.target] = {{"interpolation", toString(t.interpolation)}, {"keys", list}};
    }
    return j;
}

ojson lightJson(const Light& l) {
    ojson j;
    j["type"] = toString(l.type);
    j["name"] = l.name;
    if (l.type != LightType::Directional) j["position"] = vec(l.position);
    if (l.type != LightType::Point) j["direction"] = vec(l.direction);
    if (l.type == LightType::Spot) {
        j["inner_deg"] = num(l.inner_deg);
        j["outer_deg"] = num(l.outer_deg);
    }
    j["color"] = vec(l.color);
    j["intensity"] = num(l.intensity);
    if (l.type != LightType::Directional) j["range"] = num(l.range);
    j["shadows"] = l.shadows;
    j["fog_scale"] = num(l.fog_scale);
    if (!l.keys.empty()) j["keys"] = keysJson(l.keys, [&](const std::string& t) { return lightKeyTarget(l.type, t); });
    return j;
}

ojson volumeJson(const Volume& v) {
    ojson j;
    j["type"] = toString(v.type);
    j["name"] = v.name;
    switch (v.type) {
        case VolumeType::Box:
        case VolumeType::Ellipsoid:
        case VolumeType::Cylinder:
            j["transform"] = transformJson(v.transform);
            j["edge_fade"] = num(v.edge_fade);
            // Written when set, so scenes without it are saved as before this key existed.
            if (v.height_falloff != 0.0f) j["height_falloff"] = num(v.height_falloff);
            break;
        case VolumeType::Height:
            j["base_height"] = num(v.base_height);
            j["profile"] = toString(v.profile);
            j["falloff"] = num(v.falloff);
            j["transition_height"] = num(v.transition_height);
            break;
        case VolumeType::Depth:
            j["visibility_distance"] = num(v.visibility_distance);
            j["start_distance"] = num(v.start_distance);
            break;
        case VolumeType::Vdb:
            j["file"] = v.file;
            j["grid"] = v.grid;
            j["encoding"] = toString(v.encoding);
            j["transform"] = transformJson(v.transform);
            j["density_scale"] = num(v.density_scale);
            if (v.height_falloff != 0.0f) j["height_falloff"] = num(v.height_falloff);
            break;
        case VolumeType::Mesh:
            j["file"] = v.file;
            j["edge_fade_m"] = num(v.edge_fade_m);
            j["transform"] = transformJson(v.transform);
            if (v.height_falloff != 0.0f) j["height_falloff"] = num(v.height_falloff);
            break;
    }
    if (v.density_texture) {
        const DensityTexture& t = *v.density_texture;
        ojson tj;
        tj["file"] = t.file;
        tj["grid"] = t.grid;
        tj["tile_size_m"] = num(t.tile_size_m);
        tj["scroll_mps"] = vec(t.scroll_mps);
        tj["strength"] = num(t.strength);
        if (t.exponent != 1.0f) tj["exponent"] = num(t.exponent);
        if (t.detail) {
            ojson dj;
            dj["file"] = t.detail->file;
            dj["grid"] = t.detail->grid;
            dj["tile_size_m"] = num(t.detail->tile_size_m);
            dj["scroll_mps"] = vec(t.detail->scroll_mps);
            dj["strength"] = num(t.detail->strength);
            dj["exponent"] = num(t.detail->exponent);
            tj["detail"] = dj;
        }
        j["density_texture"] = tj;
    }
    j["medium"] = mediumJson(v.medium);
    if (!v.keys.empty()) j["keys"] = keysJson(v.keys, [&](const std::string& t) { return volumeKeyTarget(v.type, t); });
    return j;
}

ojson geometryJson(const Geometry& g) {
    ojson j;
    j["type"] = toString(g.type);
    j["name"] = g.name;
    if (g.type == GeometryType::Plane) j["height"] = num(g.height);
    if (g.type == GeometryType::Box) j["transform"] = transformJson(g.transform);
    if (g.type == GeometryType::Sphere) {
        j["center"] = vec(g.center);
        j["radius"] = num(g.radius);
    }
    j["albedo"] = vec(g.albedo);
    j["emission"] = vec(g.emission);
    return j;
}

ojson influencerJson(const Influencer& f) {
    ojson j;
    j["type"] = toString(f.type);
    j["name"] = f.name;
    j["radius"] = num(f.radius);
    if (f.type == InfluencerType::Capsule) j["length"] = num(f.length);
    j["strength"] = num(f.strength);
    j["wake_half_life_s"] = num(f.wake_half_life_s);
    j["wake_step_s"] = num(f.wake_step_s);
    j["wake_samples"] = f.wake_samples;
    j["path_interpolation"] = toString(f.path.interpolation);
    ojson list = ojson::array();
    for (const Keyframe& k : f.path.keys) list.push_back({{"time", num(k.time)}, {"position", vec(k.value)}});
    j["path"] = list;
    return j;
}

ojson froxelsJson(const FroxelOverrides& f) {
    ojson j = ojson::object();
    if (f.tile_px) j["tile_px"] = *f.tile_px;
    if (f.slices) j["slices"] = *f.slices;
    if (f.near) j["near"] = num(*f.near);
    if (f.far) j["far"] = num(*f.far);
    if (f.distribution) j["distribution"] = num(*f.distribution);
    return j;
}

template <class T, class ToJson>
ojson listJson(const std::vector<T>& items, ToJson toJson) {
    ojson j = ojson::array();
    for (const T& item : items) j.push_back(toJson(item));
    return j;
}

ojson sceneJson(const Scene& s) {
    ojson j;
    j["brume_scene"] = kVersion;
    const Camera& cam = s.camera;
    j["camera"] = {{"position", vec(cam.position)}, {"target", vec(cam.target)}, {"up", vec(cam.up)},
                   {"fov_y_deg", num(cam.fov_y_deg)}, {"near", num(cam.near)}, {"far", num(cam.far)}};
    j["render"] = {{"width", s.render.width}, {"height", s.render.height}, {"quality", toString(s.render.quality)}};
    // Written only when set, so scenes that never chose it read as before.
    if (s.render.frames != settings::render_frames.i()) j["render"]["frames"] = s.render.frames;
    if (const ojson f = froxelsJson(s.froxels); !f.empty()) j["froxels"] = f;
    j["temporal"] = {{"enabled", s.temporal.enabled}, {"history_weight", num(s.temporal.history_weight)}};
    j["ambient"] = vec(s.ambient);
    j["lights"] = listJson(s.lights, lightJson);
    j["volumes"] = listJson(s.volumes, volumeJson);
    j["geometry"] = listJson(s.geometry, geometryJson);
    // Written when present, so scenes without influencers are saved as before they existed.
    if (!s.influencers.empty()) j["influencers"] = listJson(s.influencers, influencerJson);
    return j;
}

bool isScalar(const ojson& j) { return !j.is_object() && !j.is_array(); }

// Like dump(2), but arrays of scalars stay on one line: a vec3 reads as [0.0, 1.5, 6.0].
void emit(const ojson& j, int indent, std::string& out) {
    const std::string pad(static_cast<size_t>(indent) + 2, ' ');
    if (isScalar(j)) {
        out += j.dump(-1, ' ', false, ojson::error_handler_t::replace);
    } else if (j.empty()) {
        out += j.is_object() ? "{}" : "[]";
    } else if (j.is_array() && std::all_of(j.begin(), j.end(), isScalar)) {
        out += "[";
        for (size_t i = 0; i < j.size(); ++i) {
            if (i > 0) out += ", ";
            emit(j[i], indent, out);
        }
        out += "]";
    } else {
        out += j.is_object() ? "{\n" : "[\n";
        size_t i = 0;
        for (auto it = j.begin(); it != j.end(); ++it, ++i) {
            out += pad;
            if (j.is_object()) out += ojson(it.key()).dump(-1, ' ', false, ojson::error_handler_t::replace) + ": ";
            emit(*it, indent + 2, out);
            out += i + 1 < j.size() ? ",\n" : "\n";
        }
        out += std::string(static_cast<size_t>(indent), ' ') + (j.is_object() ? "}" : "]");
    }
}

}  // namespace

std::string sceneToJson(const Scene& scene) {
    std::string out;
    emit(sceneJson(scene), 0, out);
    return out + "\n";
}

Result<void> saveSceneFile(const Scene& scene, const std::string& path) {
    return writeTextFileAtomic(path, sceneToJson(scene));
}

// ---------------------------------------------------------------------------------------------
// Docs.

namespace {

std::string defaultText(const Setting& s) {
    switch (s.kind) {
        case SettingKind::Number: return fmtNum(s.def[0]);
        case SettingKind::Integer: return std::to_string(s.i());
        case SettingKind::Vec3: return "[" + fmtNum(s.def[0]) + ", " + fmtNum(s.def[1]) + ", " + fmtNum(s.def[2]) + "]";
        case SettingKind::Bool: return s.b() ? "true" : "false";
        case SettingKind::Choice: return choicesOf(s).at(static_cast<size_t>(s.i()));
        case SettingKind::String: return "—";  // string defaults, where any, are in the help text
    }
    return "";
}

std::string rangeCell(const Setting& s) {
    switch (s.kind) {
        case SettingKind::Number:
        case SettingKind::Integer: return "[" + fmtNum(s.min) + ", " + fmtNum(s.max) + "]";
        case SettingKind::Vec3: return "[" + fmtNum(s.min) + ", " + fmtNum(s.max) + "] each";
        case SettingKind::Bool: return "true, false";
        case SettingKind::Choice: return joinList(choicesOf(s));
        case SettingKind::String: return "any string";
    }
    return "";
}

// '|' separates cells, so it is escaped inside them (GFM also honours the escape in code spans).
std::string cell(std::string_view text) {
    std::string out;
    for (char ch : text) out += ch == '|' ? std::string("\\|") : std::string(1, ch);
    return out;
}

}  // namespace

std::string settingsMarkdownTable() {
    std::string out = "| key | unit | default | range | description |\n|---|---|---|---|---|\n";
    for (const Setting* s : settings::kAll)
        out += "| `" + cell(s->path) + "` | " + cell(s->unit) + " | " + cell(defaultText(*s)) + " | " +
               cell(rangeCell(*s)) + " | " + cell(s->help) + " |\n";
    return out;
}

}  // namespace brume

// ---------------------------------------------------------------------------------------------
// Pieces shared with other formats built on scenes (io/scene_json_parts.h): thin wrappers, so that
// those formats read and write volumes and lights exactly as scenes do.

namespace brume::scene_json {

Result<nlohmann::json> parseStrictJson(std::string_view text, const std::string& file) {
    Ctx c{file, std::nullopt};
    std::optional<json> root = parseJson(c, text);
    if (!root) return *c.error;
    return std::move(*root);
}

Result<std::vector<Light>> readLights(const nlohmann::json& value, const std::string& file, const std::string& path) {
    Ctx c{file, std::nullopt};
    std::vector<Light> out;
    readArray(c, value, path, out, readLight);
    if (c.error) return *c.error;
    return out;
}

Result<std::vector<Volume>> readVolumes(const nlohmann::json& value, const std::string& file, const std::string& path) {
    Ctx c{file, std::nullopt};
    std::vector<Volume> out;
    readArray(c, value, path, out, readVolume);
    checkOneEncoding(c, out);
    if (c.error) return *c.error;
    return out;
}

Result<glm::vec3> readAmbient(const nlohmann::json& object, const std::string& file, glm::vec3 fallback) {
    Ctx c{file, std::nullopt};
    glm::vec3 out = fallback;
    Obj o(c, object, "", "a preset");  // its other keys are the caller's (checkKeys)
    readVec3(c, o, st::ambient, out);
    if (c.error) return *c.error;
    return out;
}

Result<void> checkKeys(const nlohmann::json& object, const std::string& file, const std::string& path,
                       const std::vector<std::string>& allowed, const std::string& where) {
    if (!object.is_object()) return Error{file + ": " + (path.empty() ? "" : path + ": ") +
                                          "expected an object, got " + describe(object)};
    for (const auto& item : object.items()) {
        if (std::find(allowed.begin(), allowed.end(), item.key()) != allowed.end()) continue;
        return Error{file + ": " + child(path, item.key()) + ": unknown key; allowed in " + where + ": " +
                     joinList(allowed)};
    }
    return {};
}

nlohmann::ordered_json lightToJson(const Light& light) { return lightJson(light); }
nlohmann::ordered_json volumeToJson(const Volume& volume) { return volumeJson(volume); }
nlohmann::ordered_json vec3ToJson(glm::vec3 v) { return vec(v); }

std::string prettyJson(const nlohmann::ordered_json& j) {
    std::string out;
    emit(j, 0, out);
    return out + "\n";
}

Result<std::string> readTextFile(const std::string& path) { return brume::readTextFile(path); }

}  // namespace brume::scene_json
