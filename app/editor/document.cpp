#include "document.h"

#include <charconv>
#include <filesystem>
#include <optional>
#include <utility>

#include <nlohmann/json.hpp>

#include "files.h"
#include "io/scene_json.h"
#include "io/vdb_import.h"
#include "view.h"

namespace brume::editor {
namespace {

using json = nlohmann::json;

Error usage(const std::string& verb, const std::string& form) {
    return Error{"The action \"" + verb + "\" takes: " + verb + " " + form + "."};
}

bool parseNumber(const std::string& s, double& out) {
    const char* end = s.data() + s.size();
    auto r = std::from_chars(s.data(), end, out);
    return r.ec == std::errc() && r.ptr == end;
}

bool parseIndex(const std::string& s, size_t& out) {
    const char* end = s.data() + s.size();
    auto r = std::from_chars(s.data(), end, out);
    return r.ec == std::errc() && r.ptr == end;
}

// "volumes[0].medium.phase_g" -> "/volumes/0/medium/phase_g".
Result<json::json_pointer> pointerOf(const std::string& path) {
    std::string p;
    for (char c : path) {
        if (c == '.' || c == '[') p += '/';
        else if (c == ']') continue;
        else if (c == '/' || c == '~' || c == ' ') return Error{"\"" + path + "\" is not a settings path."};
        else p += c;
    }
    if (path.empty()) return Error{"The action \"set\" needs a settings path."};
    // An empty step ("a..b", "x[]", "volumes][") names nothing (found by fuzzing: it reached the JSON
    // pointer code, which threw).
    const std::string full = "/" + p;
    if (full.back() == '/' || full.find("//") != std::string::npos) return Error{"\"" + path + "\" is not a settings path."};
    return json::json_pointer(full);
}

// The JSON value of the words typed after the path, shaped like the value it replaces.
Result<json> valueFromWords(const std::string& path, const std::vector<std::string>& words, const json* old) {
    std::vector<double> numbers;
    for (const std::string& w : words) {
        double d = 0.0;
        if (!parseNumber(w, d)) break;
        numbers.push_back(d);
    }
    const bool allNumbers = numbers.size() == words.size() && !words.empty();
    if (old && old->is_array()) {
        if (!allNumbers || numbers.size() != old->size())
            return Error{path + ": expected " + std::to_string(old->size()) + " numbers."};
        return json(numbers);
    }
    if (old && old->is_number()) {
        if (!allNumbers || numbers.size() != 1) return Error{path + ": expected one number."};
        return json(numbers[0]);
    }
    if (old && old->is_boolean()) {
        if (words.size() != 1 || (words[0] != "true" && words[0] != "false"))
            return Error{path + ": expected true or false."};
        return json(words[0] == "true");
    }
    if (old && !old->is_string()) return Error{path + ": this is a group of settings, not one value."};
    if (!old && allNumbers) return numbers.size() == 1 ? json(numbers[0]) : json(numbers);
    if (!old && words.size() == 1 && (words[0] == "true" || words[0] == "false")) return json(words[0] == "true");
    std::string text;
    for (const std::string& w : words) text += (text.empty() ? "" : " ") + w;
    return json(text);
}

Result<std::string> collectionOf(const std::string& kind) {
    if (kind == "volume") return std::string("volumes");
    if (kind == "light") return std::string("lights");
    if (kind == "geometry") return std::string("geometry");
    if (kind == "influencer") return std::string("influencers");
    return Error{"\"" + kind + "\" is not a kind of object: use volume, light, geometry or influencer."};
}

// Whether `s` is well-formed UTF-8 (Unicode Table 3-7: no overlong forms, surrogates or values past
// U+10FFFF). Scene text goes through JSON, whose writer throws on anything else.
bool isUtf8(const std::string& s) {
    size_t i = 0;
    const size_t n = s.size();
    auto byte = [&](size_t k) { return static_cast<unsigned char>(s[k]); };
    while (i < n) {
        const unsigned char c = byte(i);
        int len = 0;
        unsigned char lo = 0x80, hi = 0xBF;
        if (c < 0x80) len = 1;
        else if (c >= 0xC2 && c <= 0xDF) len = 2;
        else if (c == 0xE0) len = 3, lo = 0xA0;
        else if ((c >= 0xE1 && c <= 0xEC) || c == 0xEE || c == 0xEF) len = 3;
        else if (c == 0xED) len = 3, hi = 0x9F;
        else if (c == 0xF0) len = 4, lo = 0x90;
        else if (c >= 0xF1 && c <= 0xF3) len = 4;
        else if (c == 0xF4) len = 4, hi = 0x8F;
        else return false;
        if (i + static_cast<size_t>(len) > n) return false;
        for (int k = 1; k < len; ++k) {
            const unsigned char b = byte(i + static_cast<size_t>(k));
            if (k == 1 ? (b < lo || b > hi) : (b < 0x80 || b > 0xBF)) return false;
        }
        i += static_cast<size_t>(len);
    }
    return true;
}

Result<Scene> parseEdited(const json& j, const Scene& current) {
    Result<Scene> s = parseScene(j.dump(), "edit");
    if (!s) return s.error();
    s.value().baseDir = current.baseDir;
    // Hidden is editor state the JSON form does not carry; a set never changes the counts.
    Scene& n = s.value();
    for (size_t i = 0; i < n.volumes.size() && i < current.volumes.size(); ++i) n.volumes[i].hidden = current.volumes[i].hidden;
    // A loaded VDB grid is not in the JSON form either: it stays while its file, grid and encoding do,
    // and is read again when an edit changes them (a file that cannot be read refuses the edit).
    for (size_t i = 0; i < n.volumes.size() && i < current.volumes.size(); ++i) {
        Volume& v = n.volumes[i];
        const Volume& was = current.volumes[i];
        if (v.file == was.file && v.grid == was.grid && v.encoding == was.encoding && v.type == was.type &&
            v.edge_fade_m == was.edge_fade_m) {
            v.density = was.density;
        } else if (v.type == VolumeType::Vdb && !v.file.empty()) {
            const std::filesystem::path p(v.file);
            VdbImportOptions options;
            options.grid = v.grid;
            options.encoding = v.encoding;
            Result<VdbLoad> load = loadVdbDensity((p.is_absolute() ? p : std::filesystem::path(n.baseDir) / p).string(), options);
            if (!load) return Error{"edit: volumes[" + std::to_string(i) + "].file: " + load.error().message};
            v.density = load.value().grid;
        } else if (v.type == VolumeType::Mesh && !v.file.empty()) {
            std::vector<std::string> warnings;  // an empty hull shows as an empty volume
            if (Result<void> r = loadMeshVolume(v, n, "edit", i, VdbImportOptions{}.memoryLimitBytes, warnings); !r)
                return r.error();
        }
    }
    // Density textures likewise: kept while file and grid stay, read again when an edit changes them.
    for (size_t i = 0; i < n.volumes.size() && i < current.volumes.size(); ++i) {
        std::optional<DensityTexture>& t = n.volumes[i].density_texture;
        const std::optional<DensityTexture>& was = current.volumes[i].density_texture;
        if (!t) continue;
        // A layer is kept when its file and grid stay; the mean is of value^exponent: measured again
        // when the exponent changes.
        auto keep = [](TextureLayer& layer, const TextureLayer& before) {
            if (!before.density || layer.file != before.file || layer.grid != before.grid) return false;
            layer.density = before.density;
            layer.mean = layer.exponent == before.exponent ? before.mean
                                                           : static_cast<float>(before.density->activeBoxMean(layer.exponent));
            return true;
        };
        if (was && keep(*t, *was) && (!t->detail || (was->detail && keep(*t->detail, *was->detail)))) continue;
        std::vector<std::string> warnings;
        Result<void> load = loadDensityTexture(*t, n, "edit", i, VdbImportOptions{}.memoryLimitBytes, warnings);
        if (!load) return load.error();
    }
    for (size_t i = 0; i < n.lights.size() && i < current.lights.size(); ++i) n.lights[i].hidden = current.lights[i].hidden;
    for (size_t i = 0; i < n.geometry.size() && i < current.geometry.size(); ++i) n.geometry[i].hidden = current.geometry[i].hidden;
    for (size_t i = 0; i < n.influencers.size() && i < current.influencers.size(); ++i)
        n.influencers[i].hidden = current.influencers[i].hidden;
    return s;
}

}  // namespace

bool Document::dirty() const { return !(withoutViewState(scene_) == withoutViewState(saved_)); }

Document::Document(Scene scene, std::string path) : scene_(std::move(scene)), saved_(scene_), path_(std::move(path)) {}

bool Document::isDocumentVerb(const std::string& verb) {
    for (const char* v : {"add", "delete", "duplicate", "rename", "hide", "show", "set", "begin", "end", "undo", "redo", "save", "key", "unkey", "interpolate"})
        if (verb == v) return true;
    return false;
}

Result<void> Document::apply(const Action& a) {
    // Found by fuzzing (tests/fuzz/fuzz_action): a byte that is not UTF-8 in a path or a name made the
    // JSON writer throw, and the editor end on an uncaught exception.
    for (const std::string& w : a.args)
        if (!isUtf8(w)) return Error{a.verb + ": an argument is not valid UTF-8 text."};
    if (a.verb == "add") return add(a.args);
    if (a.verb == "delete" || a.verb == "duplicate") return removeOrDuplicate(a.verb, a.args);
    if (a.verb == "rename") return rename(a.args);
    if (a.verb == "hide" || a.verb == "show") return hide(a.verb, a.args);
    if (a.verb == "set") return set(a.args);
    if (a.verb == "save") return save(a.args);
    if (a.verb == "key" || a.verb == "unkey" || a.verb == "interpolate") return key(a.verb, a.args);
    if (!a.args.empty()) return usage(a.verb, "(no arguments)");
    if (a.verb == "begin") {
        if (groupDepth_++ == 0) groupSnapshotTaken_ = false;
    } else if (a.verb == "end") {
        groupDepth_ = groupDepth_ > 0 ? groupDepth_ - 1 : 0;
    } else if (a.verb == "undo") {
        undo();
    } else if (a.verb == "redo") {
        redo();
    } else {
        return Error{"Unknown action \"" + a.verb + "\"."};
    }
    return {};
}

void Document::commit(Scene next) {
    if (next == scene_) return;
    if (groupDepth_ == 0 || !groupSnapshotTaken_) {
        undo_.push_back(scene_);
        groupSnapshotTaken_ = groupDepth_ > 0;
    }
    redo_.clear();
    scene_ = std::move(next);
    ++revision_;
}

void Document::replaceScene(const Scene& scene) { commit(scene); }

void Document::reset(Scene scene, std::string path) {
    scene_ = std::move(scene);
    saved_ = scene_;
    path_ = std::move(path);
    undo_.clear();
    redo_.clear();
    groupDepth_ = 0;
    ++revision_;
}

void Document::undo() {
    groupDepth_ = 0;
    if (undo_.empty()) return;
    redo_.push_back(std::move(scene_));
    scene_ = std::move(undo_.back());
    undo_.pop_back();
    followFolder();
    ++revision_;
}

void Document::redo() {
    groupDepth_ = 0;
    if (redo_.empty()) return;
    undo_.push_back(std::move(scene_));
    scene_ = std::move(redo_.back());
    redo_.pop_back();
    followFolder();
    ++revision_;
}

// A snapshot from before a Save As into another folder holds VDB paths relative to the old folder:
// restored, they are rebased to the folder the document now lives in (else a save after undoing
// past the Save As would write paths that name other files).
void Document::followFolder() {
    if (path_.empty()) return;
    std::error_code ec;
    const std::string dir = std::filesystem::absolute(path_, ec).lexically_normal().parent_path().string();
    if (ec || dir == scene_.baseDir) return;
    scene_ = rebasedTo(std::move(scene_), dir);
}

Result<void> Document::add(const std::vector<std::string>& a) {
    if (a.size() < 2 || a.size() > 4) return usage("add", "volume|light|geometry|influencer TYPE [NAME]");
    const std::string name = a.size() > 2 ? a[2] : a[1];
    Scene next = scene_;
    if (a[0] == "volume") {
        Volume v;
        if (a[1] == "box") v.type = VolumeType::Box;
        else if (a[1] == "ellipsoid") v.type = VolumeType::Ellipsoid;
        else if (a[1] == "cylinder") v.type = VolumeType::Cylinder;
        else if (a[1] == "height") v.type = VolumeType::Height;
        else if (a[1] == "depth") v.type = VolumeType::Depth;
        else if (a[1] == "vdb" && a.size() == 4) v.type = VolumeType::Vdb, v.file = a[3];
        else return Error{"\"" + a[1] + "\" is not a volume type to add: use box, ellipsoid, cylinder, height, depth or vdb NAME FILE."};
        // A vdb volume arrives with its grid, as `import vdb` does; a file that cannot be read refuses the add.
        if (v.type == VolumeType::Vdb) {
            const std::filesystem::path p(v.file);
            Result<VdbLoad> load = loadVdbDensity((p.is_absolute() ? p : std::filesystem::path(next.baseDir) / p).string(), {});
            if (!load) return Error{"add volume vdb: " + load.error().message};
            v.density = load.value().grid;
        }
        v.name = name;
        next.volumes.push_back(v);
    } else if (a[0] == "light") {
        LightType t = LightType::Directional;
        if (a[1] == "point") t = LightType::Point;
        else if (a[1] == "spot") t = LightType::Spot;
        else if (a[1] != "directional") return Error{"\"" + a[1] + "\" is not a light type: use directional, point or spot."};
        Light l = makeLight(t);
        l.name = name;
        next.lights.push_back(l);
    } else if (a[0] == "geometry") {
        Geometry g;
        if (a[1] == "box") g.type = GeometryType::Box;
        else if (a[1] == "sphere") g.type = GeometryType::Sphere;
        else if (a[1] != "plane") return Error{"\"" + a[1] + "\" is not a geometry type: use plane, box or sphere."};
        g.name = name;
        next.geometry.push_back(g);
    } else if (a[0] == "influencer") {
        Influencer f;
        if (a[1] == "capsule") f.type = InfluencerType::Capsule;
        else if (a[1] != "sphere") return Error{"\"" + a[1] + "\" is not an influencer type: use sphere or capsule."};
        // A path across the origin over two seconds, to be moved with the gizmo or edited.
        f.path.target = "position";
        f.path.keys = {Keyframe{0.0f, glm::vec3(-2.0f, 1.0f, 0.0f)}, Keyframe{2.0f, glm::vec3(2.0f, 1.0f, 0.0f)}};
        f.name = name;
        next.influencers.push_back(f);
    } else {
        return collectionOf(a[0]).error();
    }
    commit(std::move(next));
    return {};
}

template <class T>
Result<void> editList(std::vector<T>& list, const std::string& verb, size_t i) {
    if (i >= list.size())
        return Error{"There is no element " + std::to_string(i) + " (the list has " + std::to_string(list.size()) + ")."};
    if (verb == "delete") {
        list.erase(list.begin() + static_cast<std::ptrdiff_t>(i));
    } else {
        T copy = list[i];
        copy.name += " copy";
        list.insert(list.begin() + static_cast<std::ptrdiff_t>(i) + 1, copy);
    }
    return {};
}

Result<void> Document::removeOrDuplicate(const std::string& verb, const std::vector<std::string>& a) {
    size_t i = 0;
    if (a.size() != 2 || !parseIndex(a[1], i)) return usage(verb, "volume|light|geometry|influencer INDEX");
    Scene next = scene_;
    Result<void> r = a[0] == "volume" ? editList(next.volumes, verb, i)
                     : a[0] == "light" ? editList(next.lights, verb, i)
                     : a[0] == "geometry" ? editList(next.geometry, verb, i)
                     : a[0] == "influencer" ? editList(next.influencers, verb, i)
                                          : Result<void>(collectionOf(a[0]).error());
    if (!r) return r;
    commit(std::move(next));
    return {};
}

template <class T>
Result<void> setHidden(std::vector<T>& list, size_t i, bool hidden) {
    if (i >= list.size())
        return Error{"There is no element " + std::to_string(i) + " (the list has " + std::to_string(list.size()) + ")."};
    list[i].hidden = hidden;
    return {};
}

Result<void> Document::hide(const std::string& verb, const std::vector<std::string>& a) {
    size_t i = 0;
    if (a.size() != 2 || !parseIndex(a[1], i)) return usage(verb, "volume|light|geometry|influencer INDEX");
    Scene next = scene_;
    const bool h = verb == "hide";
    Result<void> r = a[0] == "volume" ? setHidden(next.volumes, i, h)
                     : a[0] == "light" ? setHidden(next.lights, i, h)
                     : a[0] == "geometry" ? setHidden(next.geometry, i, h)
                     : a[0] == "influencer" ? setHidden(next.influencers, i, h)
                                          : Result<void>(collectionOf(a[0]).error());
    if (!r) return r;
    if (next == scene_) return {};  // hiding a hidden object is not an undo step
    commit(std::move(next));
    return {};
}

Result<void> Document::rename(const std::vector<std::string>& a) {
    size_t i = 0;
    if (a.size() != 3 || !parseIndex(a[1], i)) return usage("rename", "volume|light|geometry|influencer INDEX NAME");
    Result<std::string> c = collectionOf(a[0]);
    if (!c) return c.error();
    return set({c.value() + "[" + a[1] + "].name", a[2]});
}

Result<void> Document::set(const std::vector<std::string>& a) {
    if (a.size() < 2) return usage("set", "PATH VALUE...");
    Result<json::json_pointer> ptr = pointerOf(a[0]);
    if (!ptr) return ptr.error();
    json j = json::parse(sceneToJson(scene_));
    try {
        const json::json_pointer parent = ptr.value().parent_pointer();
        if (!j.contains(parent) || !j.at(parent).is_object())
            return Error{"edit: " + a[0] + ": there is no such setting in this scene."};
        const json* old = j.contains(ptr.value()) ? &j.at(ptr.value()) : nullptr;
        Result<json> v = valueFromWords(a[0], {a.begin() + 1, a.end()}, old);
        if (!v) return Error{"edit: " + v.error().message};
        j[ptr.value()] = v.value();
    } catch (const json::exception&) {  // a path the JSON pointer code refuses: a sentence, never a crash
        return Error{"edit: " + a[0] + ": there is no such setting in this scene."};
    }
    Result<Scene> next = parseEdited(j, scene_);
    if (!next) return next.error();
    commit(std::move(next.value()));
    return {};
}

Result<std::string> Document::valueText(const std::string& path) const {
    Result<json::json_pointer> ptr = pointerOf(path);
    if (!ptr) return ptr.error();
    const json j = json::parse(sceneToJson(scene_));
    if (!j.contains(ptr.value())) return Error{path + ": there is no such setting in this scene."};
    return j.at(ptr.value()).dump();
}

Result<void> Document::save(const std::vector<std::string>& a) {
    if (a.size() > 1) return usage("save", "[PATH]");
    const std::string target = a.empty() ? path_ : a[0];
    if (target.empty()) return Error{"This scene has no file yet: use Save As (save PATH)."};
    // Relative VDB paths follow the scene into its new folder (they stay undoable edits).
    std::error_code ec;
    const std::string dir = std::filesystem::absolute(target, ec).lexically_normal().parent_path().string();
    if (!ec && dir != scene_.baseDir) {
        commit(rebasedTo(scene_, dir));
        scene_.baseDir = dir;  // not part of Scene's ==: set even when no path changed
    }
    Result<void> r = saveSceneFile(scene_, target);
    if (!r) return r;
    path_ = target;
    saved_ = scene_;
    return {};
}

Result<Action> parseAction(const std::string& line) {
    if (!isUtf8(line)) return Error{"The action line is not valid UTF-8 text."};
    Action a;
    std::vector<std::string> words;
    std::string cur;
    bool inWord = false, quoted = false;
    for (size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quoted) {
            if (c == '\\' && i + 1 < line.size()) cur += line[++i];
            else if (c == '"') quoted = false;
            else cur += c;
        } else if (c == '"') {
            quoted = inWord = true;
        } else if (c == ' ' || c == '\t' || c == '\r') {
            if (inWord) words.push_back(std::move(cur)), cur.clear();
            inWord = false;
        } else if (c == '#' && !inWord && words.empty()) {
            break;
        } else {
            cur += c;
            inWord = true;
        }
    }
    if (quoted) return Error{"Unterminated quote in the action \"" + line + "\"."};
    if (inWord) words.push_back(std::move(cur));
    if (words.empty()) return a;
    a.verb = words[0];
    a.args.assign(words.begin() + 1, words.end());
    return a;
}

std::string formatAction(const Action& action) {
    // The verb too (fuzzing found `dup"key \"lamp\""`: one word with a space, written back as two),
    // and every byte parseAction splits words on (fuzzing found a quoted carriage return written
    // back bare, which split the word in two).
    auto word = [](const std::string& w) {
        const bool plain = !w.empty() && w.find_first_of(" \t\r\"\\#") == std::string::npos;
        if (plain) return w;
        std::string q = "\"";
        for (char c : w) q += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
        return q + "\"";
    };
    if (action.verb.empty() && action.args.empty()) return "";
    std::string line = word(action.verb);
    for (const std::string& w : action.args) line += " " + word(w);
    return line;
}

}  // namespace brume::editor
