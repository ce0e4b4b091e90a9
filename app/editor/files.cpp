#include "files.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "io/atomic_file.h"
#include "io/scene_json.h"
#include "io/mesh_import.h"
#include "io/vdb_import.h"

namespace brume::editor {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

std::string absolutePath(const std::string& path) {
    std::error_code ec;
    const fs::path abs = fs::absolute(path, ec);
    return ec ? path : abs.lexically_normal().string();
}

bool exists(const std::string& path) {
    std::error_code ec;
    return fs::is_regular_file(path, ec);
}

// `path` relative to `dir` when it lies inside it (no "..": moving the folder keeps it valid),
// else absolute.
std::string relativeIfInside(const std::string& path, const std::string& dir) {
    const std::string abs = absolutePath(path);
    if (dir.empty()) return abs;
    const fs::path rel = fs::path(abs).lexically_relative(fs::path(dir).lexically_normal());
    if (rel.empty() || *rel.begin() == "..") return abs;
    return rel.string();
}

bool hasDiscard(std::vector<std::string>& args) {
    const auto it = std::find(args.begin(), args.end(), "--discard");
    if (it == args.end()) return false;
    args.erase(it);
    return true;
}

// Moves an imported grid volume so that its grid's centre is at the camera's target, or 5 m ahead
// when the target is behind the camera.
void placeInView(const Camera& c, Volume& v) {
    const glm::vec3 forward = glm::normalize(c.target - c.position);
    const bool targetAhead = glm::dot(c.target - c.position, forward) > c.near;
    const glm::vec3 place = targetAhead ? c.target : c.position + forward * 5.0f;
    glm::vec3 centre(0.0f);
    if (!v.density->empty()) {
        const glm::vec3 mid = (v.density->indexMin() + v.density->indexMax()) * 0.5f;
        centre = glm::vec3(v.density->gridFromIndex() * glm::vec4(mid, 1.0f));
    }
    v.transform.translation = place - centre;
}

}  // namespace

std::string recentFilesPath() {
    fs::path dir;
    if (const char* config = std::getenv("XDG_CONFIG_HOME"); config && *config) dir = config;
    else if (const char* home = std::getenv("HOME"); home && *home) dir = fs::path(home) / ".config";
    else return "";
    return (dir / "brume" / "recent.json").string();
}

std::vector<std::string> RecentFiles::load() {
    paths_.clear();
    std::ifstream f(store_);
    if (store_.empty() || !f) return {};
    std::stringstream ss;
    ss << f.rdbuf();
    const json j = json::parse(ss.str(), nullptr, false);
    if (j.is_discarded() || !j.is_object() || !j.contains("recent") || !j["recent"].is_array())
        return {store_ + ": not a recent-files list; starting a new one."};
    for (const json& p : j["recent"])
        if (p.is_string() && paths_.size() < kMax) paths_.push_back(p.get<std::string>());
    return prune();
}

Result<void> RecentFiles::add(const std::string& path) {
    const std::string abs = absolutePath(path);
    std::erase(paths_, abs);
    paths_.insert(paths_.begin(), abs);
    if (paths_.size() > kMax) paths_.resize(kMax);
    return write();
}

std::vector<std::string> RecentFiles::prune() {
    std::vector<std::string> gone;
    for (const std::string& p : paths_)
        if (!exists(p)) gone.push_back(p + " is missing: removed from the recent files.");
    if (gone.empty()) return gone;
    std::erase_if(paths_, [](const std::string& p) { return !exists(p); });
    if (Result<void> r = write(); !r) gone.push_back(r.error().message);
    return gone;
}

Result<void> RecentFiles::write() const {
    if (store_.empty()) return {};
    std::error_code ec;
    fs::create_directories(fs::path(store_).parent_path(), ec);
    if (ec) return Error{store_ + ": cannot create its folder: " + ec.message()};
    return writeTextFileAtomic(store_, json{{"recent", paths_}}.dump(2) + "\n");
}

Scene newScene() {
    Scene s;
    Light sun = makeLight(LightType::Directional);
    sun.name = "sun";
    s.lights.push_back(sun);
    Geometry ground;
    ground.type = GeometryType::Plane;
    ground.name = "ground";
    s.geometry.push_back(ground);
    return s;
}

Result<OpenedScene> openSceneFile(const std::string& path) {
    Result<Scene> s = loadSceneFile(path);
    if (!s) return s.error();
    OpenedScene out{std::move(s.value()), absolutePath(path), {}};
    for (size_t i = 0; i < out.scene.volumes.size(); ++i) {
        Volume& v = out.scene.volumes[i];
        // A texture that cannot be read leaves the volume plain (an unloaded texture modulates nothing).
        if (v.density_texture) {
            Result<void> t = loadDensityTexture(*v.density_texture, out.scene, path, i, VdbImportOptions{}.memoryLimitBytes,
                                                out.warnings);
            if (!t) out.warnings.push_back(t.error().message + " The texture is left out.");
        }
        if (v.type == VolumeType::Mesh) {
            Result<void> m = loadMeshVolume(v, out.scene, path, i, VdbImportOptions{}.memoryLimitBytes, out.warnings);
            if (!m) out.warnings.push_back(m.error().message + " The volume stays empty.");
        }
        if (v.type != VolumeType::Vdb) continue;
        fs::path p(v.file);
        if (p.is_relative()) p = fs::path(out.scene.baseDir) / p;
        VdbImportOptions options;
        options.grid = v.grid;
        options.encoding = v.encoding;
        Result<VdbLoad> load = loadVdbDensity(p.lexically_normal().string(), options);
        if (load) v.density = load.value().grid;
        else out.warnings.push_back(path + ": volumes[" + std::to_string(i) + "].file: " + load.error().message +
                                    " The volume stays empty.");
    }
    return out;
}

Result<Volume> importVdbVolume(const Scene& scene, const std::string& sceneDir, const std::string& path) {
    if (!exists(path)) return Error{path + ": no such file."};
    // A scene's vdb volumes share one encoding (io/scene_json.cpp): the new one takes theirs.
    VdbImportOptions options;
    for (const Volume& other : scene.volumes)
        if (other.type == VolumeType::Vdb) options.encoding = other.encoding;
    Result<VdbLoad> load = loadVdbDensity(absolutePath(path), options);
    if (!load) return load.error();
    Volume v;
    v.type = VolumeType::Vdb;
    v.encoding = options.encoding;
    v.name = fs::path(path).stem().string();
    v.file = relativeIfInside(path, sceneDir);
    v.grid = load.value().gridName;
    v.density = load.value().grid;
    placeInView(scene.camera, v);
    return v;
}

Result<Volume> importMeshVolume(const Scene& scene, const std::string& sceneDir, const std::string& path) {
    if (!exists(path)) return Error{path + ": no such file."};
    Volume v;
    v.type = VolumeType::Mesh;
    v.name = fs::path(path).stem().string();
    v.file = relativeIfInside(path, sceneDir);
    // A scene's grids share one encoding (io/scene_json.cpp): the hull takes its vdb volumes'.
    VdbImportOptions options;
    for (const Volume& other : scene.volumes)
        if (other.type == VolumeType::Vdb) options.encoding = other.encoding;
    Result<VdbLoad> load = loadMeshDensity(absolutePath(path), v.edge_fade_m, options);
    if (!load) return load.error();
    v.density = load.value().grid;
    placeInView(scene.camera, v);  // like an imported VDB
    return v;
}

Scene rebasedTo(Scene scene, const std::string& dir) {
    auto rebase = [&](std::string& file) {
        if (file.empty()) return;
        const fs::path p(file);
        file = relativeIfInside((p.is_absolute() ? p : fs::path(scene.baseDir) / p).string(), dir);
    };
    for (Volume& v : scene.volumes) {
        if (v.type == VolumeType::Vdb || v.type == VolumeType::Mesh) rebase(v.file);
        // Density textures and their detail layers name files relative to the scene too.
        if (v.density_texture) rebase(v.density_texture->file);
        if (v.density_texture && v.density_texture->detail) rebase(v.density_texture->detail->file);
    }
    scene.baseDir = dir;
    return scene;
}

Result<std::vector<DirEntry>> listDirectory(const std::string& dir, const std::string& ext) {
    std::error_code ec;
    fs::directory_iterator it(dir, ec);
    if (ec) return Error{dir + ": cannot list the folder: " + ec.message()};
    std::vector<DirEntry> out;
    for (; it != fs::directory_iterator(); it.increment(ec)) {
        if (ec) return Error{dir + ": cannot list the folder: " + ec.message()};
        const std::string name = it->path().filename().string();
        if (name.empty() || name[0] == '.') continue;
        const bool isDir = it->is_directory(ec);
        // ext: one extension or several separated by '|' (".obj|.ply").
        if (!isDir && !ext.empty() && ("|" + ext + "|").find("|" + it->path().extension().string() + "|") == std::string::npos)
            continue;
        out.push_back({name, isDir});
    }
    std::sort(out.begin(), out.end(), [](const DirEntry& a, const DirEntry& b) {
        return a.isDir != b.isDir ? a.isDir : a.name < b.name;
    });
    return out;
}

bool Files::isFileVerb(const std::string& verb) { return verb == "new" || verb == "open" || verb == "import"; }

Result<void> Files::apply(Document& doc, const Action& a) {
    std::vector<std::string> args = a.args;
    if (a.verb == "import") {
        if (args.size() != 2 || (args[0] != "vdb" && args[0] != "mesh"))
            return Error{"import takes: import vdb PATH, or import mesh PATH."};
        const std::string dir = doc.path().empty() ? "" : fs::path(doc.path()).parent_path().string();
        Result<Volume> v = args[0] == "mesh" ? importMeshVolume(doc.scene(), dir, args[1])
                                             : importVdbVolume(doc.scene(), dir, args[1]);
        if (!v) return v.error();
        Scene next = doc.scene();
        next.volumes.push_back(v.value());
        doc.replaceScene(next);
        return {};
    }
    const bool discard = hasDiscard(args);
    if (a.verb == "new" ? !args.empty() : args.size() != 1)
        return Error{"File actions take: new [--discard], open PATH [--discard]."};
    if (doc.dirty() && !discard)
        return Error{(doc.path().empty() ? std::string("untitled") : doc.path()) +
                     " has unsaved changes: save them first, or " + a.verb + " with --discard to drop them."};
    if (a.verb == "new") {
        doc.reset(newScene(), "");
        return {};
    }
    Result<OpenedScene> opened = openSceneFile(args[0]);
    if (!opened) return opened.error();
    for (std::string& w : opened.value().warnings) message(std::move(w));
    doc.reset(std::move(opened.value().scene), opened.value().path);
    noteRecent(doc.path());
    return {};
}

void Files::noteRecent(const std::string& path) {
    if (path.empty()) return;
    if (Result<void> r = recent_.add(path); !r) message(r.error().message);
}

std::vector<std::string> Files::takeMessages() { return std::exchange(messages_, {}); }

}  // namespace brume::editor
