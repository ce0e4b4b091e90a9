// Scene format v1: defaults from core/settings.h, lossless round trip, atomic saving, and every
// class of input error reported as "FILE: JSON-PATH: what is wrong".
#include <gtest/gtest.h>

#include "test_support.h"

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include <unistd.h>

#include "io/atomic_file.h"
#include "io/preset.h"
#include "io/scene_json.h"

#include <nlohmann/json.hpp>

namespace brume {
namespace {

namespace fs = std::filesystem;

std::string readAll(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// Each test's folder: brume_test_scene_json_NAME_PID under the system temp folder.
struct TempDir : test::TempDir {
    explicit TempDir(const std::string& name) : test::TempDir("test_scene_json", name) {}
};
using test::fileCount;

// Every type of light, volume and geometry, with values away from the defaults, including floats
// that have no short decimal form.
Scene richScene() {
    Scene s;
    s.camera = {{1.0f / 3.0f, 2.5f, -7.25f}, {0.1f, 0.2f, 0.3f}, {0, 1, 0}, 47.5f, 0.05f, 250.0f};
    s.render = {160, 90, Quality::Ultra};
    s.froxels.tile_px = 4;
    s.froxels.slices = 96;
    s.froxels.near = 0.25f;
    s.froxels.far = 80.0f;
    s.froxels.distribution = 2.5f;
    s.temporal = {false, 0.75f};
    s.ambient = {0.01f, 0.02f, 0.03f};
    Light sun = makeLight(LightType::Directional);
    sun.name = "sun \"key\"";
    sun.direction = glm::normalize(glm::vec3(0.3f, -0.9f, 0.1f));
    sun.color = {1.0f, 0.9f, 0.8f};
    sun.fog_scale = 2.0f;
    Light point = makeLight(LightType::Point);
    point.name = "lamp";
    point.position = {1e5f, -3.0f, 1e-3f};
    point.range = 12.0f;
    point.shadows = true;
    Light spot = makeLight(LightType::Spot);
    spot.name = "spot";
    spot.position = {0.0f, 4.0f, 0.0f};
    spot.direction = glm::normalize(glm::vec3(0.2f, -1.0f, 0.0f));
    spot.inner_deg = 10.0f;
    spot.outer_deg = 35.5f;
    s.lights = {sun, point, spot};

    Volume box;
    box.name = "box";
    box.transform = {{1, 2, 3}, {10, 20, 30}, {2, 0.5f, 4}};
    box.edge_fade = 0.3f;
    box.medium = {{0.5f, 0.25f, 0.125f}, {0.01f, 0.02f, 0.03f}, {0.0f, 0.1f, 0.0f}, -0.4f};
    Volume expo;
    expo.type = VolumeType::Height;
    expo.falloff = 0.7f;
    expo.transition_height = 5.0f;
    expo.base_height = -1.5f;
    Volume linear = expo;
    linear.profile = HeightProfile::Linear;
    linear.name = "linear";
    Volume depth;
    depth.type = VolumeType::Depth;
    depth.visibility_distance = 120.0f;
    depth.start_distance = 3.0f;
    Volume vdb;
    vdb.type = VolumeType::Vdb;
    vdb.file = "clouds/cloud.vdb";
    vdb.grid = "density";
    vdb.density_scale = 0.3f;
    vdb.transform.scale = {0.01f, 0.01f, 0.01f};
    s.volumes = {box, expo, linear, depth, vdb};

    Geometry plane;
    plane.height = -0.5f;
    Geometry cube;
    cube.type = GeometryType::Box;
    cube.transform.translation = {0, 0.5f, 0};
    cube.emission = {2, 2, 2};
    Geometry sphere;
    sphere.type = GeometryType::Sphere;
    sphere.center = {1, 1, 1};
    sphere.radius = 0.75f;
    sphere.albedo = {0.9f, 0.1f, 0.1f};
    s.geometry = {plane, cube, sphere};
    return s;
}

std::string parseError(const std::string& text) {
    Result<Scene> r = parseScene(text, "scene.json");
    return r ? std::string("(parsed without error)") : r.error().message;
}

}  // namespace
}  // namespace brume

namespace brume {
namespace {

TEST(SceneJson, MinimalFileGetsEveryDefaultFromSettings) {
    Result<Scene> r = parseScene(R"({"brume_scene": 1})", "min.json");
    ASSERT_TRUE(r) << r.error().message;
    const Scene& s = r.value();
    EXPECT_EQ(s, Scene{});
    EXPECT_EQ(s.camera.fov_y_deg, settings::camera_fov_y.f());
    EXPECT_EQ(s.camera.position, glm::vec3(0.0f, 1.5f, 6.0f));
    EXPECT_EQ(s.render.width, settings::render_width.i());
    EXPECT_EQ(s.render.quality, Quality::High);
    EXPECT_FALSE(s.froxels.slices.has_value());
    EXPECT_TRUE(s.lights.empty() && s.volumes.empty() && s.geometry.empty());
}

TEST(SceneJson, LightDefaultsDependOnType) {
    Result<Scene> r = parseScene(
        R"({"brume_scene": 1, "lights": [{"type": "directional"}, {"type": "point"}, {"type": "spot"}]})", "l.json");
    ASSERT_TRUE(r) << r.error().message;
    const auto& l = r.value().lights;
    ASSERT_EQ(l.size(), 3u);
    EXPECT_EQ(l[0].intensity, settings::light_intensity_directional.f());
    EXPECT_EQ(l[0].shadows, settings::light_shadows_directional.b());
    EXPECT_EQ(l[1].intensity, settings::light_intensity_local.f());
    EXPECT_EQ(l[1].shadows, settings::light_shadows_local.b());
    EXPECT_EQ(l[2], makeLight(LightType::Spot));
    EXPECT_NEAR(glm::length(l[0].direction), 1.0f, 1e-6f);
}

TEST(SceneJson, DirectionIsNormalizedOnLoad) {
    Result<Scene> r = parseScene(R"({"brume_scene": 1, "lights": [{"type": "spot", "direction": [0, -0.5, 0.5]}]})",
                                 "d.json");
    ASSERT_TRUE(r) << r.error().message;
    const glm::vec3 d = r.value().lights[0].direction;
    EXPECT_NEAR(d.y, -std::sqrt(0.5f), 1e-6f);
    EXPECT_NEAR(d.z, std::sqrt(0.5f), 1e-6f);
}

TEST(SceneJson, HeightVolumeKeepsBothProfileParameters) {
    const char* text = R"({"brume_scene": 1, "volumes": [
        {"type": "height", "profile": "linear", "falloff": 0.25, "transition_height": 7}]})";
    Result<Scene> r = parseScene(text, "h.json");
    ASSERT_TRUE(r) << r.error().message;
    const Volume& v = r.value().volumes[0];
    EXPECT_EQ(v.profile, HeightProfile::Linear);
    EXPECT_EQ(v.falloff, 0.25f);
    EXPECT_EQ(v.transition_height, 7.0f);
    const std::string out = sceneToJson(r.value());
    EXPECT_NE(out.find("\"falloff\": 0.25"), std::string::npos) << out;
    EXPECT_NE(out.find("\"transition_height\": 7"), std::string::npos) << out;
}

TEST(SceneJson, IntegralFloatIsAcceptedAsInteger) {
    Result<Scene> r = parseScene(R"({"brume_scene": 1.0, "render": {"width": 320.0}})", "i.json");
    ASSERT_TRUE(r) << r.error().message;
    EXPECT_EQ(r.value().render.width, 320);
}

TEST(SceneJson, RichSceneRoundTripsExactly) {
    const Scene s = richScene();
    const std::string text = sceneToJson(s);
    Result<Scene> r = parseScene(text, "rich.json");
    ASSERT_TRUE(r) << r.error().message << "\n" << text;
    EXPECT_EQ(r.value(), s) << text;
    EXPECT_EQ(sceneToJson(r.value()), text);  // stable: writing again changes no byte
}

TEST(SceneJson, FloatsSurviveRoundTripAtAwkwardValues) {
    // Bounds, values without short decimals and float neighbours of round numbers.
    const float values[] = {1e-4f, 0.1f, 1.0f / 3.0f, 123456.789f, std::nextafter(1.0f, 2.0f),
                            std::nextafter(0.1f, 0.0f), 9.99999e5f, 1e6f, 7.0e-4f};
    for (float v : values) {
        Scene s;
        s.camera.near = std::min(v, 1e4f);
        s.camera.far = 1e7f;
        s.ambient = glm::vec3(v);
        s.camera.position = glm::vec3(v, -v, 0.5f * v);
        Result<Scene> r = parseScene(sceneToJson(s), "f.json");
        ASSERT_TRUE(r) << v << ": " << r.error().message;
        EXPECT_EQ(r.value(), s) << v;
    }
}

// Random valid scenes: every float drawn from its setting's range, either uniformly or with random
// mantissa bits (log-uniform), so that most values have no short decimal form.
class RandomScene {
public:
    explicit RandomScene(unsigned seed) : rng_(seed) {}

    float value(const Setting& s) {
        const double lo = s.min, hi = s.max;
        double v = std::uniform_real_distribution<double>(lo, hi)(rng_);
        if (coin() && lo >= 0.0 && hi > 0.0) {
            const double l0 = std::log(std::max(lo, 1e-6)), l1 = std::log(hi);
            v = std::exp(std::uniform_real_distribution<double>(l0, l1)(rng_));
        }
        return std::clamp(static_cast<float>(v), static_cast<float>(lo), static_cast<float>(hi));
    }
    glm::vec3 vec(const Setting& s) { return {value(s), value(s), value(s)}; }
    glm::vec3 unit() { return glm::normalize(glm::vec3(value(settings::light_direction), -0.5f, value(settings::light_direction))); }
    bool coin() { return std::uniform_int_distribution<int>(0, 1)(rng_) == 1; }
    int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng_); }

    Scene scene() {
        Scene s;
        s.camera.position = 0.5f * vec(settings::camera_position);  // room for the target beside it
        s.camera.target = s.camera.position + glm::vec3(1.0f, value(settings::camera_up), 0.5f);
        s.camera.fov_y_deg = value(settings::camera_fov_y);
        s.camera.near = value(settings::camera_near);
        s.camera.far = std::max(value(settings::camera_far), s.camera.near * 2.0f);
        s.render = {pick(4096) + 1, pick(4096) + 1, static_cast<Quality>(pick(4))};
        if (coin()) s.froxels.distribution = value(settings::froxels_distribution);
        if (coin()) s.froxels.slices = pick(1024) + 1;
        s.temporal = {coin(), value(settings::temporal_history_weight)};
        s.ambient = vec(settings::ambient);
        for (int i = pick(4); i > 0; --i) s.lights.push_back(light());
        for (int i = pick(6); i > 0; --i) s.volumes.push_back(volume());
        for (int i = pick(4); i > 0; --i) s.geometry.push_back(geometry());
        return s;
    }

private:
    Light light() {
        Light l = makeLight(static_cast<LightType>(pick(3)));
        l.name = "light " + std::to_string(pick(100));
        l.color = vec(settings::light_color);
        l.intensity = value(settings::light_intensity_local);
        l.shadows = coin();
        l.fog_scale = value(settings::light_fog_scale);
        if (l.type != LightType::Directional) {
            l.position = vec(settings::light_position);
            l.range = value(settings::light_range);
        }
        if (l.type != LightType::Point) l.direction = unit();
        if (l.type == LightType::Spot) {
            l.outer_deg = value(settings::light_outer_deg);
            l.inner_deg = std::min(value(settings::light_inner_deg), l.outer_deg);
        }
        return l;
    }
    Transform transform() {
        return {vec(settings::transform_translation), vec(settings::transform_rotation), vec(settings::transform_scale)};
    }
    Volume volume() {
        Volume v;
        // Every type but mesh (its file is a mesh the reader would load: tests/test_mesh.cpp).
        constexpr VolumeType kTypes[] = {VolumeType::Box,       VolumeType::Height,   VolumeType::Depth,
                                         VolumeType::Vdb,       VolumeType::Ellipsoid, VolumeType::Cylinder};
        v.type = kTypes[pick(6)];
        v.medium = {vec(settings::medium_scattering), vec(settings::medium_absorption), vec(settings::medium_emission),
                    value(settings::medium_phase_g)};
        if (isLocalShape(v.type) || v.type == VolumeType::Vdb) v.transform = transform();
        if (isLocalShape(v.type)) {
            v.edge_fade = value(settings::volume_edge_fade);
            if (coin()) v.height_falloff = value(settings::volume_height_falloff);
        }
        if (v.type == VolumeType::Height) {
            v.profile = static_cast<HeightProfile>(pick(2));
            v.base_height = value(settings::volume_base_height);
            v.falloff = value(settings::volume_falloff);
            v.transition_height = value(settings::volume_transition_height);
        }
        if (v.type == VolumeType::Depth) {
            v.visibility_distance = value(settings::volume_visibility_distance);
            v.start_distance = value(settings::volume_start_distance);
        }
        if (v.type == VolumeType::Vdb) {
            v.file = "dir/f\\" + std::to_string(pick(100)) + ".vdb";
            v.density_scale = value(settings::volume_density_scale);
        }
        return v;
    }
    Geometry geometry() {
        Geometry g;
        g.type = static_cast<GeometryType>(pick(3));
        if (g.type == GeometryType::Plane) g.height = value(settings::geometry_height);
        if (g.type == GeometryType::Box) g.transform = transform();
        if (g.type == GeometryType::Sphere) {
            g.center = vec(settings::geometry_center);
            g.radius = value(settings::geometry_radius);
        }
        g.albedo = vec(settings::geometry_albedo);
        g.emission = vec(settings::geometry_emission);
        return g;
    }
    std::mt19937 rng_;
};

TEST(SceneJson, RandomValidScenesRoundTripExactly) {
    RandomScene gen(12345u);
    for (int i = 0; i < 300; ++i) {
        const Scene s = gen.scene();
        const std::string text = sceneToJson(s);
        Result<Scene> r = parseScene(text, "random.json");
        ASSERT_TRUE(r) << "scene " << i << ": " << r.error().message << "\n" << text;
        ASSERT_EQ(r.value(), s) << "scene " << i << "\n" << text;
    }
}

TEST(SceneJson, LoadSaveLoadIsIdenticalAndSetsBaseDir) {
    const TempDir tmp("load_save");
    const fs::path& dir = tmp.path;
    const fs::path a = dir / "a.json";
    ASSERT_TRUE(saveSceneFile(richScene(), a.string()));
    Result<Scene> first = loadSceneFile(a.string());
    ASSERT_TRUE(first) << first.error().message;
    EXPECT_EQ(first.value().baseDir, fs::absolute(dir).lexically_normal().string());
    const fs::path b = dir / "b.json";
    ASSERT_TRUE(saveSceneFile(first.value(), b.string()));
    Result<Scene> second = loadSceneFile(b.string());
    ASSERT_TRUE(second) << second.error().message;
    EXPECT_EQ(second.value(), first.value());
    EXPECT_EQ(first.value(), richScene());
    EXPECT_EQ(readAll(a), readAll(b));
    EXPECT_EQ(fileCount(dir), 2u);  // no temporaries left
}

TEST(SceneJson, FailedWriteLeavesOldFileAndNoTemporary) {
    const TempDir tmp("atomic");
    const fs::path& dir = tmp.path;
    const fs::path path = dir / "scene.json";
    ASSERT_TRUE(saveSceneFile(Scene{}, path.string()));
    const std::string before = readAll(path);
    Result<void> r = writeFileAtomic(path.string(), [](const std::string& tmp) -> Result<void> {
        std::ofstream(tmp) << "{\"brume_scene\": 1, \"cam";  // half written, then the writer fails
        return Error{"disk full"};
    });
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().message, "disk full");
    EXPECT_EQ(readAll(path), before);
    EXPECT_EQ(fileCount(dir), 1u);
}

TEST(SceneJson, SaveOverADirectoryFailsWithoutLeftovers) {
    const TempDir tmp("over_dir");
    const fs::path& dir = tmp.path;
    fs::create_directories(dir / "taken" / "inside");
    Result<void> r = saveSceneFile(Scene{}, (dir / "taken").string());
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find((dir / "taken").string()), std::string::npos) << r.error().message;
    EXPECT_TRUE(fs::is_directory(dir / "taken" / "inside"));
    EXPECT_EQ(fileCount(dir), 1u);
}

TEST(SceneJson, SaveIntoMissingFolderNamesPathAndReason) {
    const TempDir tmp("missing");
    const fs::path path = tmp.path / "no" / "such" / "scene.json";
    Result<void> r = saveSceneFile(Scene{}, path.string());
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().message, path.string() + ": cannot write: No such file or directory");
}

TEST(SceneJson, UnreadableFileNamesPathAndReason) {
    const TempDir tmp("unreadable");
    const fs::path& dir = tmp.path;
    const std::string missing = (dir / "nope.json").string();
    Result<Scene> r = loadSceneFile(missing);
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().message, missing + ": cannot read: No such file or directory");
    Result<Scene> d = loadSceneFile(dir.string());
    ASSERT_FALSE(d);
    EXPECT_EQ(d.error().message, dir.string() + ": cannot read: Is a directory");
}

}  // namespace
}  // namespace brume

namespace brume {
namespace {

struct ErrorCase {
    const char* text;
    const char* message;
};

// One case per class of error; the whole message is compared because its wording is the interface.
const ErrorCase kErrorCases[] = {
    {"{\"brume_scene\": 1,\n  \"camera\": {]\n}", "scene.json: line 2, column 14: JSON syntax error while parsing object key - unexpected ']'; expected string literal"},
    {"", "scene.json: line 1, column 1: JSON syntax error while parsing value - unexpected end of input; expected '[', '{', or a literal"},
    {"[1, 2]", "scene.json: expected a JSON object at the top level, got an array of 2 values"},
    {"{}", "scene.json: brume_scene: missing required key (the format version; this build reads 1)"},
    {R"({"brume_scene": 2})", "scene.json: brume_scene: unsupported version 2 (this build reads version 1)"},
    {R"({"brume_scene": "1"})", "scene.json: brume_scene: expected an integer, got \"1\""},
    {R"({"brume_scene": 1, "fog": {}})",
     "scene.json: fog: unknown key; allowed in a scene: brume_scene, camera, render, froxels, temporal, ambient, lights, volumes, geometry, influencers"},
    {R"({"brume_scene": 1, "volumes": [{"type": "box", "falloff": 1}]})",
     "scene.json: volumes[0].falloff: unknown key; allowed in a box volume: type, name, transform, edge_fade, height_falloff, density_texture, medium, keys"},
    {R"({"brume_scene": 1, "volumes": [{"type": "box", "medium": {"albedo": 1}}]})",
     "scene.json: volumes[0].medium.albedo: unknown key; allowed in a medium: scattering, absorption, emission, phase_g"},
    {R"({"brume_scene": 1, "camera": {"fov_y_deg": "wide"}})", "scene.json: camera.fov_y_deg: expected a number, got \"wide\""},
    {R"({"brume_scene": 1, "render": {"width": true}})", "scene.json: render.width: expected an integer, got true"},
    {R"({"brume_scene": 1, "render": {"width": 640.5}})", "scene.json: render.width: expected an integer, got 640.5"},
    {R"({"brume_scene": 1, "ambient": [1, 2]})", "scene.json: ambient: expected an array of 3 numbers, got an array of 2 values"},
    {R"({"brume_scene": 1, "ambient": [1, null, 2]})", "scene.json: ambient[1]: expected a number, got null"},
    {R"({"brume_scene": 1, "temporal": {"enabled": 1}})", "scene.json: temporal.enabled: expected true or false, got 1"},
    {R"({"brume_scene": 1, "lights": [{"type": "point", "name": 7}]})", "scene.json: lights[0].name: expected a string, got 7"},
    {R"({"brume_scene": 1, "camera": []})", "scene.json: camera: expected an object, got an array of 0 values"},
    {R"({"brume_scene": 1, "lights": {}})", "scene.json: lights: expected an array, got an object"},
    {R"({"brume_scene": 1, "camera": {"near": 1e999}})", "scene.json: line 1, column 39: number 1e999 is not finite (it overflows a double)"},
    {R"({"brume_scene": 1, "volumes": [{}, {"type": "box", "medium": {"phase_g": 1.5}}]})",
     "scene.json: volumes[0].type: missing required key; choices: box, height, depth, vdb, mesh, ellipsoid, cylinder"},
    {R"({"brume_scene": 1, "volumes": [{"type": "box"}, {"type": "box"}, {"type": "box", "medium": {"phase_g": 1.5}}]})",
     "scene.json: volumes[2].medium.phase_g: 1.5 is out of range [-1, 1]"},
    {R"({"brume_scene": 1, "camera": {"fov_y_deg": 180}})", "scene.json: camera.fov_y_deg: 180 deg is out of range [1, 179] deg"},
    {R"({"brume_scene": 1, "volumes": [{"type": "box", "medium": {"scattering": [0, -0.5, 0]}}]})",
     "scene.json: volumes[0].medium.scattering[1]: -0.5 1/m is out of range [0, 1e+09] 1/m"},
    {R"({"brume_scene": 1, "render": {"height": 0}})", "scene.json: render.height: 0 px is out of range [1, 16384] px"},
    {R"({"brume_scene": 1, "render": {"quality": "extreme"}})",
     "scene.json: render.quality: unknown choice \"extreme\"; choices: low, medium, high, ultra"},
    {R"({"brume_scene": 1, "volumes": [{"type": "fog"}]})", "scene.json: volumes[0].type: unknown choice \"fog\"; choices: box, height, depth, vdb, mesh, ellipsoid, cylinder"},
    {R"({"brume_scene": 1, "volumes": [{"type": "vdb"}]})", "scene.json: volumes[0].file: missing required key (the OpenVDB file of a vdb volume)"},
    {R"({"brume_scene": 1, "volumes": [{"type": "vdb", "file": ""}]})", "scene.json: volumes[0].file: must not be empty"},
    {R"({"brume_scene": 1, "camera": {"near": 5, "far": 5}})", "scene.json: camera.far: 5 m must exceed camera.near (5 m)"},
    {R"({"brume_scene": 1, "camera": {"position": [1, 2, 3], "target": [1, 2, 3]}})", "scene.json: camera.target: must differ from camera.position"},
    {R"({"brume_scene": 1, "camera": {"position": [0, 5, 0], "target": [0, 0, 0]}})",
     "scene.json: camera.up: must not be zero or parallel to the view direction (target - position)"},
    {R"({"brume_scene": 1, "camera": {"up": [0, 0, 0]}})",
     "scene.json: camera.up: must not be zero or parallel to the view direction (target - position)"},
    {R"({"brume_scene": 1, "lights": [{"type": "directional", "direction": [0, 0, 0]}]})", "scene.json: lights[0].direction: must not be zero"},
    {R"({"brume_scene": 1, "lights": [{"type": "spot", "inner_deg": 40, "outer_deg": 30}]})",
     "scene.json: lights[0].inner_deg: 40 deg must not exceed outer_deg (30 deg)"},
    {R"({"brume_scene": 1, "lights": [{"type": "point", "direction": [0, -1, 0]}]})",
     "scene.json: lights[0].direction: unknown key; allowed in a point light: type, name, position, color, intensity, range, shadows, fog_scale, keys"},
    {R"({"brume_scene": 1, "froxels": {"near": 10, "far": 2}})", "scene.json: froxels.far: 2 m must exceed froxels.near (10 m)"},
    {R"({"brume_scene": 1, "froxels": {"slices": 0}})", "scene.json: froxels.slices: 0 is out of range [1, 1024]"},
    {R"({"brume_scene": 1, "camera": {"fov_y_deg": 30, "fov_y_deg": 40}})", "scene.json: camera.fov_y_deg: duplicate key"},
    {R"({"brume_scene": 1, "geometry": [{"type": "plane"}, {"type": "sphere", "radius": 0}]})",
     "scene.json: geometry[1].radius: 0 m is out of range [0.0001, 1e+06] m"},
};

TEST(SceneJson, EveryErrorNamesFilePathAndProblem) {
    for (const ErrorCase& c : kErrorCases) EXPECT_EQ(parseError(c.text), c.message) << "input: " << c.text;
}

TEST(SceneJson, DuplicateKeyInsideListIsLocated) {
    EXPECT_EQ(parseError(R"({"brume_scene": 1, "lights": [{"type": "point"}, {"type": "spot", "name": "a", "name": "b"}]})"),
              "scene.json: lights[1].name: duplicate key");
}

TEST(SceneJson, DocsTableMatchesSettings) {
    const std::string doc = readAll(BRUME_SOURCE_DIR "/docs/scene-format.md");
    const std::string begin = "<!-- settings-table:begin -->\n";
    const std::string end = "<!-- settings-table:end -->";
    const size_t b = doc.find(begin);
    const size_t e = doc.find(end);
    ASSERT_NE(b, std::string::npos) << "docs/scene-format.md lacks the begin marker";
    ASSERT_NE(e, std::string::npos) << "docs/scene-format.md lacks the end marker";
    ASSERT_LT(b, e);
    EXPECT_EQ(doc.substr(b + begin.size(), e - b - begin.size()), settingsMarkdownTable())
        << "regenerate the table in docs/scene-format.md from settingsMarkdownTable()";
}

TEST(SceneJson, DocsTableListsEverySetting) {
    const std::string table = settingsMarkdownTable();
    for (const Setting* s : settings::kAll) {
        std::string key(s->path);
        for (size_t p = key.find('|'); p != std::string::npos; p = key.find('|', p + 2)) key.replace(p, 1, "\\|");
        EXPECT_NE(table.find("| `" + key + "` |"), std::string::npos) << s->path;
    }
}

}  // namespace
}  // namespace brume

// Keys are read once (io/scene_json.cpp, Obj): a key no reader looks up is an error at every level,
// with the keys that level knows and, for a near miss, the key meant.
namespace brume {
namespace {

TEST(SceneJsonKeys, UnknownKeyAtEveryNestingLevel) {
    const ErrorCase cases[] = {
        {R"({"brume_scene": 1, "camera": {"fov": 40}})",
         "scene.json: camera.fov: unknown key; allowed in camera: position, target, up, fov_y_deg, near, far"},
        {R"({"brume_scene": 1, "render": {"widht": 40}})",
         "scene.json: render.widht: unknown key (did you mean \"width\"?); allowed in render: width, height, quality, frames"},
        {R"({"brume_scene": 1, "froxels": {"tiles": 4}})",
         "scene.json: froxels.tiles: unknown key; allowed in froxels: tile_px, slices, near, far, distribution"},
        {R"({"brume_scene": 1, "temporal": {"weight": 0.5}})",
         "scene.json: temporal.weight: unknown key; allowed in temporal: enabled, history_weight"},
        {R"({"brume_scene": 1, "lights": [{"type": "spot", "fogscale": 2}]})",
         "scene.json: lights[0].fogscale: unknown key (did you mean \"fog_scale\"?); allowed in a spot light: type, name, "
         "position, direction, inner_deg, outer_deg, color, intensity, range, shadows, fog_scale, keys"},
        {R"({"brume_scene": 1, "lights": [{"type": "directional", "position": [0, 1, 0]}]})",
         "scene.json: lights[0].position: unknown key; allowed in a directional light: type, name, direction, color, "
         "intensity, shadows, fog_scale, keys"},
        {R"({"brume_scene": 1, "volumes": [{"type": "height", "fallof": 1}]})",
         "scene.json: volumes[0].fallof: unknown key (did you mean \"falloff\"?); allowed in a height volume: type, name, "
         "base_height, profile, falloff, transition_height, density_texture, medium, keys"},
        {R"({"brume_scene": 1, "volumes": [{"type": "depth", "medium": {}, "start": 1}]})",
         "scene.json: volumes[0].start: unknown key; allowed in a depth volume: type, name, visibility_distance, "
         "start_distance, density_texture, medium, keys"},
        {R"({"brume_scene": 1, "volumes": [{"type": "box", "transform": {"rotation": [0, 1, 0]}}]})",
         "scene.json: volumes[0].transform.rotation: unknown key; allowed in a transform: translation, rotation_deg, scale"},
        {R"({"brume_scene": 1, "volumes": [{"type": "vdb", "file": "a.vdb", "scale": 2}]})",
         "scene.json: volumes[0].scale: unknown key; allowed in a vdb volume: type, name, file, grid, encoding, transform, "
         "density_scale, height_falloff, density_texture, medium, keys"},
        {R"({"brume_scene": 1, "geometry": [{"type": "sphere", "centre": [0, 1, 0]}]})",
         "scene.json: geometry[0].centre: unknown key (did you mean \"center\"?); allowed in a sphere: type, name, center, "
         "radius, albedo, emission"},
        {R"({"brume_scene": 1, "geometry": [{"type": "box", "transform": {"scales": [1, 1, 1]}}]})",
         "scene.json: geometry[0].transform.scales: unknown key (did you mean \"scale\"?); allowed in a transform: "
         "translation, rotation_deg, scale"},
        {R"({"brume_scene": 1, "ambiant": [0, 0, 0]})",
         "scene.json: ambiant: unknown key (did you mean \"ambient\"?); allowed in a scene: brume_scene, camera, render, "
         "froxels, temporal, ambient, lights, volumes, geometry, influencers"},
    };
    for (const ErrorCase& c : cases) EXPECT_EQ(parseError(c.text), c.message) << "input: " << c.text;
}

// A misspelt key is named before the problems it causes: "fiel" leaves "file" missing, and the
// message is about "fiel".
TEST(SceneJsonKeys, MisspeltKeyInsideDensityTexture) {
    EXPECT_EQ(parseError(R"({"brume_scene": 1, "volumes": [{"type": "box", "density_texture": {"fiel": "noise.vdb"}}]})"),
              "scene.json: volumes[0].density_texture.fiel: unknown key (did you mean \"file\"?); allowed in "
              "density_texture: file, grid, tile_size_m, scroll_mps, strength, exponent, detail");
    EXPECT_EQ(parseError(R"({"brume_scene": 1, "volumes": [{"type": "box", "density_texture": {"file": "n.vdb", "strenght": 2}}]})"),
              "scene.json: volumes[0].density_texture.strenght: unknown key (did you mean \"strength\"?); allowed in "
              "density_texture: file, grid, tile_size_m, scroll_mps, strength, exponent, detail");
    // Without the typo the missing file is what is wrong.
    EXPECT_EQ(parseError(R"({"brume_scene": 1, "volumes": [{"type": "box", "density_texture": {"grid": "density"}}]})"),
              "scene.json: volumes[0].density_texture.file: missing required key (the OpenVDB file of the texture)");
    // The detail layer: its own keys, named with their full path.
    EXPECT_EQ(parseError(R"({"brume_scene": 1, "volumes": [{"type": "box", "density_texture": {"file": "n.vdb",
                            "detail": {"file": "d.vdb", "strenth": 1}}}]})"),
              "scene.json: volumes[0].density_texture.detail.strenth: unknown key (did you mean \"strength\"?); allowed in "
              "density_texture.detail: file, grid, tile_size_m, scroll_mps, strength, exponent");
}

// Every key written in a shipped scene is read: the strict reader accepts the file, and each of the
// file's values comes back, at the same JSON path, in what the writer makes of the scene it read.
void expectEveryLeafIn(const nlohmann::json& file, const nlohmann::json& written, const std::string& path,
                       const std::string& scene) {
    if (file.is_object()) {
        for (const auto& item : file.items()) {
            const std::string p = path.empty() ? item.key() : path + "." + item.key();
            ASSERT_TRUE(written.is_object() && written.contains(item.key())) << scene << ": " << p << " was not read";
            expectEveryLeafIn(item.value(), written[item.key()], p, scene);
        }
    } else if (path.ends_with("direction")) {
        EXPECT_TRUE(written.is_array()) << scene << ": " << path;  // directions are normalized on load
    } else if (file.is_array() && !file.empty() && (file[0].is_object() || file[0].is_array())) {
        ASSERT_TRUE(written.is_array() && written.size() == file.size()) << scene << ": " << path;
        for (size_t i = 0; i < file.size(); ++i)
            expectEveryLeafIn(file[i], written[i], path + "[" + std::to_string(i) + "]", scene);
    } else if (file.is_number()) {
        EXPECT_TRUE(written.is_number()) << scene << ": " << path;
        if (written.is_number()) {
            EXPECT_FLOAT_EQ(static_cast<float>(file.get<double>()), static_cast<float>(written.get<double>()))
                << scene << ": " << path;
        }
    } else if (file.is_array()) {
        ASSERT_TRUE(written.is_array() && written.size() == file.size()) << scene << ": " << path;
        for (size_t i = 0; i < file.size(); ++i)
            expectEveryLeafIn(file[i], written[i], path + "[" + std::to_string(i) + "]", scene);
    } else {
        EXPECT_EQ(file, written) << scene << ": " << path;
    }
}

TEST(SceneJsonKeys, EveryKeyOfEveryShippedSceneIsRead) {
    int scenes = 0;
    for (const fs::directory_entry& e : fs::directory_iterator(fs::path(BRUME_SOURCE_DIR) / "assets" / "scenes")) {
        if (e.path().extension() != ".json") continue;
        ++scenes;
        const std::string text = readAll(e.path());
        Result<Scene> r = parseScene(text, e.path().string());
        ASSERT_TRUE(r) << r.error().message;
        const nlohmann::json file = nlohmann::json::parse(text);
        const nlohmann::json written = nlohmann::json::parse(sceneToJson(r.value()));
        expectEveryLeafIn(file, written, "", e.path().filename().string());
    }
    EXPECT_GE(scenes, 6);
}

}  // namespace
}  // namespace brume

// Keyframes in the scene format: read, written back unchanged, and every bad input one sentence
// naming its JSON path.
namespace brume {
namespace {

constexpr const char* kKeyed = R"({"brume_scene": 1,
  "lights": [{"type": "spot", "keys": {"intensity": [{"time": 0, "value": 5}, {"time": 2.5, "value": 50}],
                                       "direction": {"interpolation": "smooth", "keys": [{"time": 1, "value": [0, -1, 0]}]}}}],
  "volumes": [{"type": "box", "density_texture": {"file": "n.vdb"},
               "keys": {"medium.scattering": [{"time": 0, "value": [0.1, 0.2, 0.3]}, {"time": 2.5, "value": [1, 1, 1]}],
                        "transform.translation": {"interpolation": "smooth", "keys": [{"time": -1, "value": [0, 0, 0]},
                                                  {"time": 0, "value": [1, 0, 0]}, {"time": 4, "value": [1, 2, 0]}]},
                        "density_texture.strength": [{"time": 3, "value": 2}]}}]})";

TEST(SceneJsonKeyframes, ReadAndWrittenLosslessly) {
    Result<Scene> r = parseScene(kKeyed, "k.json");
    ASSERT_TRUE(r) << r.error().message;
    const Scene& s = r.value();
    ASSERT_EQ(s.volumes[0].keys.size(), 3u);
    const KeyTrack& scat = s.volumes[0].keys[1];  // targets come in key order
    EXPECT_EQ(scat.target, "medium.scattering");
    EXPECT_EQ(scat.interpolation, Interpolation::Linear);
    ASSERT_EQ(scat.keys.size(), 2u);
    EXPECT_EQ(scat.keys[1].time, 2.5f);
    EXPECT_EQ(scat.keys[0].value, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(s.volumes[0].keys[2].interpolation, Interpolation::Smooth);
    ASSERT_EQ(s.lights[0].keys.size(), 2u);
    EXPECT_EQ(s.lights[0].keys[1].target, "intensity");
    EXPECT_EQ(s.lights[0].keys[1].keys[1].value.x, 50.0f);
    Result<Scene> again = parseScene(sceneToJson(s), "k2.json");
    ASSERT_TRUE(again) << again.error().message;
    EXPECT_EQ(again.value(), s);
}

TEST(SceneJsonKeyframes, BadKeysNameTheirPath) {
    const ErrorCase cases[] = {
        {R"({"brume_scene": 1, "volumes": [{"type": "box", "keys": {"medium.scattering": [{"time": 2, "value": [0, 0, 0]}, {"time": 1, "value": [1, 1, 1]}]}}]})",
         "scene.json: volumes[0].keys.medium.scattering[1].time: 1 s is not after the previous key's time (2 s); a list's keys "
         "must be in increasing time"},
        {R"({"brume_scene": 1, "volumes": [{"type": "box", "keys": {"medium.scatering": [{"time": 0, "value": [0, 0, 0]}]}}]})",
         "scene.json: volumes[0].keys.medium.scatering: not a keyable setting of a box volume (did you mean "
         "\"medium.scattering\"?); keyable: edge_fade, height_falloff, transform.translation, transform.rotation_deg, transform.scale, "
         "medium.scattering, medium.absorption, medium.emission, medium.phase_g"},
        {R"({"brume_scene": 1, "volumes": [{"type": "height", "keys": {"density_texture.strength": [{"time": 0, "value": 1}]}}]})",
         "scene.json: volumes[0].keys.density_texture.strength: not a keyable setting of a height volume; keyable: "
         "base_height, falloff, transition_height, medium.scattering, medium.absorption, medium.emission, medium.phase_g"},
        {R"({"brume_scene": 1, "lights": [{"type": "directional", "keys": {"position": [{"time": 0, "value": [0, 0, 0]}]}}]})",
         "scene.json: lights[0].keys.position: not a keyable setting of a directional light; keyable: direction, color, "
         "intensity, fog_scale"},
        {R"({"brume_scene": 1, "lights": [{"type": "point", "keys": {"intensity": [{"time": 0, "value": -1}]}}]})",
         "scene.json: lights[0].keys.intensity[0].value: -1 W/sr is out of range [0, 1e+06] W/sr"},
        {R"({"brume_scene": 1, "lights": [{"type": "point", "keys": {"color": [{"time": 0, "value": 1}]}}]})",
         "scene.json: lights[0].keys.color[0].value: expected an array of 3 numbers, got 1"},
        {R"({"brume_scene": 1, "lights": [{"type": "point", "keys": {"range": []}}]})",
         "scene.json: lights[0].keys.range: expected an array of at least one key {\"time\": s, \"value\": v}, got an array of 0 values"},
        {R"({"brume_scene": 1, "lights": [{"type": "point", "keys": {"range": [{"value": 3}]}}]})",
         "scene.json: lights[0].keys.range[0].time: missing required key (the key's scene time in s)"},
        {R"({"brume_scene": 1, "lights": [{"type": "point", "keys": {"range": [{"time": 0, "value": 3, "ease": 1}]}}]})",
         "scene.json: lights[0].keys.range[0].ease: unknown key; allowed in a key: time, value"},
        {R"({"brume_scene": 1, "lights": [{"type": "point", "keys": {"range": {"interpolation": "cubic", "keys": [{"time": 0, "value": 3}]}}}]})",
         "scene.json: lights[0].keys.range.interpolation: unknown choice \"cubic\"; choices: linear, smooth"},
        {R"({"brume_scene": 1, "lights": [{"type": "point", "keys": {"range": {"interpolation": "smooth"}}}]})",
         "scene.json: lights[0].keys.range.keys: missing required key (the list of keys {\"time\": s, \"value\": v})"},
        {R"({"brume_scene": 1, "lights": [{"type": "point", "keys": [1]}]})",
         "scene.json: lights[0].keys: expected an object, got an array of 1 value"},
    };
    for (const ErrorCase& c : cases) EXPECT_EQ(parseError(c.text), c.message) << "input: " << c.text;
}

}  // namespace
}  // namespace brume

// Found by tests/fuzz/fuzz_scene_json and fuzz_preset_json (inputs in tests/fuzz/corpus/*/
// key_with_newline.json): an unknown key holding a newline was echoed raw, so the error was two
// lines. Control characters in keys are now written escaped.
TEST(SceneJson, AnUnknownKeyWithControlCharactersIsNamedOnOneLine) {
    brume::Result<brume::Scene> r = brume::parseScene("{\"brume_scene\": 1, \"cam\\nt\\u0001\": 1}", "k.json");
    ASSERT_FALSE(r.ok());
    const std::string& m = r.error().message;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    EXPECT_EQ(m.rfind("k.json: cam\\nt\\x01: unknown key", 0), 0u) << m;
    brume::Result<brume::Preset> p = brume::parsePreset("{\"brume_preset\": 1, \"name\": \"n\", \"volumes\": [{\"type\": \"box\", \"a\\nb\": 1}]}",
                                   "p.json", "/tmp");
    ASSERT_FALSE(p.ok());
    EXPECT_EQ(p.error().message.find('\n'), std::string::npos) << p.error().message;
    EXPECT_NE(p.error().message.find("a\\nb"), std::string::npos) << p.error().message;
}
