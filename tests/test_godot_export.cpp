// `brume export --to godot`: the written .tscn is parsed back and every value checked against the
// conversion formulas of docs/export.md, computed here from the scene; every unmapped item is
// reported; and the transmittance Godot computes from the exported density (Beer-Lambert) through a
// homogeneous box equals Brume's reference render of it.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <regex>
#include <sstream>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "core/render.h"
#include "io/scene_json.h"
#include "test_support.h"

namespace fs = std::filesystem;

namespace {

using brume::test::quoted;
using brume::test::readText;
using brume::test::TempDir;
using namespace brume;

struct Section {
    std::string kind;                           // gd_scene, sub_resource, node
    std::map<std::string, std::string> header;  // type, id, name, parent
    std::map<std::string, std::string> props;
};

std::vector<Section> parseTscn(const std::string& text) {
    std::vector<Section> out;
    std::istringstream in(text);
    std::string line;
    const std::regex attr(R"((\w+)=\"([^\"]*)\")");
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == ';') continue;
        if (line[0] == '[') {
            Section s;
            s.kind = line.substr(1, line.find_first_of(" ]") - 1);
            for (std::sregex_iterator it(line.begin(), line.end(), attr), end; it != end; ++it)
                s.header[(*it)[1]] = (*it)[2];
            out.push_back(s);
            continue;
        }
        const size_t eq = line.find(" = ");
        if (eq != std::string::npos && !out.empty()) out.back().props[line.substr(0, eq)] = line.substr(eq + 3);
    }
    return out;
}

// The numbers of "Color(1, 2, 3, 1)", "Vector3(...)", "Transform3D(...)" or a plain number.
std::vector<double> numbers(const std::string& v) {
    std::vector<double> out;
    const std::regex n(R"([-+]?[0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)");
    const size_t open = v.find('(');
    const std::string body = open == std::string::npos ? v : v.substr(open);
    for (std::sregex_iterator it(body.begin(), body.end(), n), end; it != end; ++it) out.push_back(std::stod(it->str()));
    return out;
}

const Section& node(const std::vector<Section>& s, const std::string& name) {
    for (const Section& x : s)
        if (x.kind == "node" && x.header.count("name") && x.header.at("name") == name) return x;
    throw std::runtime_error("no node " + name);
}

const Section& resource(const std::vector<Section>& s, const std::string& subResourceRef) {
    const std::string id = subResourceRef.substr(subResourceRef.find('"') + 1, subResourceRef.rfind('"') - subResourceRef.find('"') - 1);
    for (const Section& x : s)
        if (x.kind == "sub_resource" && x.header.at("id") == id) return x;
    throw std::runtime_error("no resource " + id);
}

void expectVec(const std::string& value, glm::vec3 want, const std::string& what, double tol = 1e-5) {
    const std::vector<double> n = numbers(value);
    ASSERT_GE(n.size(), 3u) << what << ": " << value;
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(n[static_cast<size_t>(i)], want[i], tol * std::max(1.0f, std::abs(want[i]))) << what << "[" << i << "]";
}

double num(const Section& s, const std::string& key) {
    EXPECT_TRUE(s.props.count(key)) << key;
    return s.props.count(key) ? numbers(s.props.at(key)).at(0) : std::nan("");
}

// Godot writes Transform3D's basis row by row: element (row, col) is numbers[row * 3 + col].
glm::mat3 basisOf(const std::string& transform) {
    const std::vector<double> n = numbers(transform);
    glm::mat3 m;
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col) m[col][row] = static_cast<float>(n.at(static_cast<size_t>(row * 3 + col)));
    return m;
}
glm::vec3 originOf(const std::string& transform) {
    const std::vector<double> n = numbers(transform);
    return {float(n.at(9)), float(n.at(10)), float(n.at(11))};
}

// A line of `text` that starts with `prefix` and contains `part`.
bool hasLine(const std::string& text, const std::string& prefix, const std::string& part) {
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line))
        if (line.rfind(prefix, 0) == 0 && line.find(part) != std::string::npos) return true;
    return false;
}

struct CliRun {
    int exitCode;
    std::string out, err;
};

CliRun brumeIn(const fs::path& cwd, const std::string& args) {
    const std::string cmd = "cd " + quoted(cwd.string()) + " && " + quoted(BRUME_EXE) + " " + args + " >.out 2>.err";
    const int status = std::system(cmd.c_str());
    CliRun r{WIFEXITED(status) ? WEXITSTATUS(status) : -1, readText(cwd / ".out"), readText(cwd / ".err")};
    fs::remove(cwd / ".out");
    fs::remove(cwd / ".err");
    return r;
}

const char* kScene = R"({"brume_scene": 1,
  "camera": {"position": [1, 2, 9], "target": [0, 1, 0], "fov_y_deg": 50, "near": 0.2, "far": 70},
  "ambient": [0.1, 0.2, 0.4],
  "lights": [
    {"type": "directional", "name": "sun", "direction": [0.3, -1, 0.2], "color": [1, 0.5, 0.25], "intensity": 3, "fog_scale": 0.5},
    {"type": "point", "name": "bulb", "position": [1, 2, 3], "color": [0.5, 1, 1], "intensity": 40, "range": 12},
    {"type": "spot", "name": "lamp", "position": [0, 4, 0], "direction": [0, -1, 0.1], "inner_deg": 10, "outer_deg": 35, "intensity": 90}],
  "volumes": [
    {"type": "box", "name": "bank", "transform": {"translation": [1, 2, -3], "rotation_deg": [10, 30, -20], "scale": [4, 2, 3]},
     "edge_fade": 0.2, "medium": {"scattering": [0.5, 0.4, 0.3], "absorption": [0.1, 0.3, 0.5], "emission": [0.01, 0.02, 0.03], "phase_g": 0.6}},
    {"type": "height", "name": "mist", "base_height": 0.5, "falloff": 1.3, "medium": {"scattering": [0.2, 0.2, 0.2], "absorption": [0.01, 0.01, 0.01], "phase_g": 0.6}},
    {"type": "depth", "name": "haze", "visibility_distance": 40, "start_distance": 5, "medium": {"scattering": [0.03, 0.03, 0.03], "absorption": [0.01, 0.01, 0.01], "phase_g": 0.2}},
    {"type": "vdb", "name": "puff", "file": "puff.vdb", "medium": {"phase_g": 0.6}}],
  "geometry": [{"type": "plane", "name": "ground"}]})";

TEST(GodotExport, EveryValueFollowsTheMapping) {
    TempDir t("godot", "mapping");
    std::ofstream(t.path / "s.json") << kScene;
    const CliRun r = brumeIn(t.path, "export s.json --to godot -o s.tscn");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string text = readText(t.path / "s.tscn");
    const std::vector<Section> s = parseTscn(text);
    Result<Scene> scene = parseScene(kScene, "s.json");
    ASSERT_TRUE(scene);
    const Scene& sc = scene.value();

    // Box: density = mean sigma_t, albedo = sigma_s / sigma_t, emission, size = scale, basis = R.
    const Section& bank = node(s, "bank");
    EXPECT_EQ(bank.header.at("type"), "FogVolume");
    EXPECT_EQ(num(bank, "shape"), 3);
    const Volume& box = sc.volumes[0];
    const Section& bankMat = resource(s, bank.props.at("material"));
    const glm::vec3 sigmaT = box.medium.scattering + box.medium.absorption;
    EXPECT_NEAR(num(bankMat, "density"), (sigmaT.x + sigmaT.y + sigmaT.z) / 3.0, 1e-6);
    expectVec(bankMat.props.at("albedo"), box.medium.scattering / sigmaT, "albedo");
    expectVec(bankMat.props.at("emission"), box.medium.emission, "emission");
    EXPECT_NEAR(num(bankMat, "edge_fade"), 0.2, 1e-6);
    EXPECT_EQ(num(bankMat, "height_falloff"), 0.0);
    expectVec(bank.props.at("size"), box.transform.scale, "size");
    EXPECT_NEAR(glm::length(originOf(bank.props.at("transform")) - box.transform.translation), 0.0f, 1e-5f);
    const glm::vec3 rad = glm::radians(box.transform.rotation_deg);
    glm::mat4 R(1.0f);
    R = glm::rotate(R, rad.z, glm::vec3(0, 0, 1));
    R = glm::rotate(R, rad.y, glm::vec3(0, 1, 0));
    R = glm::rotate(R, rad.x, glm::vec3(1, 0, 0));
    const glm::mat3 basis = basisOf(bank.props.at("transform"));
    for (int c = 0; c < 3; ++c)
        for (int row = 0; row < 3; ++row) EXPECT_NEAR(basis[c][row], R[c][row], 1e-5) << c << "," << row;

    // Height fog: world shape at y = base_height, height_falloff = k / ln 2.
    const Section& mist = node(s, "mist");
    EXPECT_EQ(num(mist, "shape"), 4);
    EXPECT_NEAR(originOf(mist.props.at("transform")).y, 0.5, 1e-6);
    const Section& mistMat = resource(s, mist.props.at("material"));
    EXPECT_NEAR(num(mistMat, "height_falloff"), 1.3 / std::numbers::ln2, 1e-5);
    EXPECT_NEAR(num(mistMat, "density"), 0.21, 1e-6);

    // Environment: depth fog as the global fog, the scattering-weighted g, the ambient.
    const Section* env = nullptr;
    for (const Section& x : s)
        if (x.kind == "sub_resource" && x.header.at("type") == "Environment") env = &x;
    ASSERT_TRUE(env);
    EXPECT_EQ(env->props.at("volumetric_fog_enabled"), "true");
    EXPECT_NEAR(num(*env, "volumetric_fog_density"), 0.04, 1e-6);
    double gSum = 0, w = 0;
    for (const Volume& v : sc.volumes) {
        const double ss = (v.medium.scattering.x + v.medium.scattering.y + v.medium.scattering.z) / 3.0;
        gSum += ss * v.medium.phase_g;
        w += ss;
    }
    EXPECT_NEAR(num(*env, "volumetric_fog_anisotropy"), gSum / w, 1e-5);
    const double ambientEnergy = num(*env, "ambient_light_energy");
    const std::vector<double> ambientColor = numbers(env->props.at("ambient_light_color"));
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(ambientColor[size_t(i)] * ambientEnergy, sc.ambient[i], 1e-6);

    // Lights: colour x energy = colour x intensity, -Z = direction, inverse square within the range.
    for (const Light& l : sc.lights) {
        const Section& n = node(s, l.name);
        const std::vector<double> c = numbers(n.props.at("light_color"));
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(c[size_t(i)] * num(n, "light_energy"), l.color[i] * l.intensity, 1e-4) << l.name;
        EXPECT_NEAR(num(n, "light_volumetric_fog_energy"), l.fog_scale, 1e-6);
        const glm::mat3 b = basisOf(n.props.at("transform"));
        if (l.type != LightType::Point) {
            EXPECT_NEAR(glm::length(-b[2] - l.direction), 0.0f, 1e-5f) << l.name;
        }
        if (l.type != LightType::Directional) {
            EXPECT_NEAR(glm::length(originOf(n.props.at("transform")) - l.position), 0.0f, 1e-5f) << l.name;
        }
    }
    EXPECT_EQ(num(node(s, "bulb"), "omni_range"), 12);
    EXPECT_EQ(num(node(s, "bulb"), "omni_attenuation"), 2);
    EXPECT_EQ(num(node(s, "lamp"), "spot_angle"), 35);
    EXPECT_EQ(num(node(s, "lamp"), "spot_attenuation"), 2);

    // Camera: at the position, -Z toward the target, vertical fov.
    const Section& cam = node(s, "Camera");
    EXPECT_NEAR(glm::length(originOf(cam.props.at("transform")) - sc.camera.position), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(-basisOf(cam.props.at("transform"))[2] - glm::normalize(sc.camera.target - sc.camera.position)), 0.0f, 1e-5f);
    EXPECT_EQ(num(cam, "fov"), 50);
    EXPECT_NEAR(num(cam, "far"), 70, 1e-6);

    // Every unmapped item is reported, one line each, on stdout and in the file.
    for (const char* loss : {"volumes[0] \"bank\" (box): sigma_t differs per channel", "volumes[0] \"bank\" (box): edge_fade",
                             "volumes[2] \"haze\" (depth): start_distance 5 m", "volumes[2] \"haze\" (depth): Godot's global fog is uniform",
                             "volumes[3] \"puff\" (vdb): Godot has no VDB grids", "phase_g 0.6 is per volume",
                             "lights[2] \"lamp\": Godot's spot cone", "geometry[0] \"ground\": preview geometry"})
        EXPECT_TRUE(hasLine(r.out, "loss: ", loss)) << loss << "\n" << r.out;
    size_t outLosses = 0, fileLosses = 0;
    for (size_t p = 0; (p = r.out.find("loss: ", p)) != std::string::npos; ++p) ++outLosses;
    for (size_t p = 0; (p = text.find("; loss: ", p)) != std::string::npos; ++p) ++fileLosses;
    EXPECT_EQ(outLosses, fileLosses);
}

// Godot's fog extinction is the FogMaterial density (Beer-Lambert, e^(-density L)); with the exported
// density, the transmittance through a homogeneous box equals Brume's reference render of it.
// Ellipsoid and cylinder volumes are Godot's shapes 0 and 2 with the box's size rule; height_falloff k
// becomes FogMaterial.height_falloff = k / ln 2 with the density scaled by e^(-k (centre - bottom)),
// so that above the centre Godot's min(1, 2^(-h (y - centre))) x density is Brume's density.
TEST(GodotExport, EllipsoidAndCylinderAreGodotShapesWithHeightFalloff) {
    TempDir t("godot", "shapes");
    std::ofstream(t.path / "s.json") << R"({"brume_scene": 1, "volumes": [
        {"type": "ellipsoid", "name": "e", "transform": {"translation": [0, 3, 0], "scale": [2, 4, 3]},
         "height_falloff": 0.5, "medium": {"scattering": [0.2, 0.2, 0.2], "absorption": [0, 0, 0]}},
        {"type": "cylinder", "name": "c", "transform": {"scale": [1, 2, 1]}, "edge_fade": 0}]})";
    const CliRun r = brumeIn(t.path, "export s.json --to godot -o s.tscn");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string text = readText(t.path / "s.tscn");
    const std::vector<Section> s = parseTscn(text);
    const Section& e = node(s, "e");
    EXPECT_EQ(num(e, "shape"), 0);
    expectVec(e.props.at("size"), glm::vec3(2, 4, 3), "size");
    const Section& eMat = resource(s, e.props.at("material"));
    EXPECT_NEAR(num(eMat, "height_falloff"), 0.5 / std::numbers::ln2, 1e-5);
    EXPECT_NEAR(num(eMat, "density"), 0.2 * std::exp(-0.5 * 2.0), 1e-6);  // the bottom is 2 m below the centre
    EXPECT_NE(text.find("; loss: volumes[0] \"e\" (ellipsoid): height_falloff"), std::string::npos) << text;  // reported
    const Section& c = node(s, "c");
    EXPECT_EQ(num(c, "shape"), 2);
    EXPECT_EQ(num(resource(s, c.props.at("material")), "height_falloff"), 0.0);
}

TEST(GodotExport, HomogeneousBoxTransmittanceMatchesBrume) {
    TempDir t("godot", "transmittance");
    const std::string sceneText = R"({"brume_scene": 1,
      "camera": {"position": [0, 0, 6], "target": [0, 0, 0], "fov_y_deg": 10, "near": 0.1, "far": 50},
      "render": {"width": 9, "height": 9},
      "volumes": [{"type": "box", "name": "slab", "transform": {"scale": [4, 4, 1.5]}, "edge_fade": 0,
                   "medium": {"scattering": [0, 0, 0], "absorption": [0.8, 0.8, 0.8]}}],
      "geometry": [{"type": "box", "name": "backdrop", "transform": {"translation": [0, 0, -3], "scale": [20, 20, 0.1]},
                    "albedo": [0, 0, 0], "emission": [1, 1, 1]}]})";
    std::ofstream(t.path / "s.json") << sceneText;
    ASSERT_EQ(brumeIn(t.path, "export s.json --to godot -o s.tscn").exitCode, 0);
    const std::vector<Section> s = parseTscn(readText(t.path / "s.tscn"));
    const Section& slab = node(s, "slab");
    const double density = num(resource(s, slab.props.at("material")), "density");
    const double depth = numbers(slab.props.at("size")).at(2);
    const double godotT = std::exp(-density * depth);

    Result<Scene> scene = parseScene(sceneText, "s.json");
    ASSERT_TRUE(scene);
    RenderRequest req = requestFromScene(scene.value());
    req.threads = 2;
    const Image img = renderReference(scene.value(), req);
    const double brumeT = img.at(4, 4).g;  // backdrop radiance 1 seen through the slab
    EXPECT_NEAR(godotT, std::exp(-0.8 * 1.5), 1e-6);
    EXPECT_NEAR(brumeT, godotT, 0.005 * godotT);
}

TEST(GodotExport, PresetExportsWithoutCameraAndBadInputIsOneSentence) {
    TempDir t("godot", "preset");
    std::ofstream(t.path / "p.json") << R"({"brume_preset": 1, "name": "Look", "volumes": [{"type": "box"}]})";
    CliRun r = brumeIn(t.path, "export p.json --to godot -o p.tscn");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::vector<Section> s = parseTscn(readText(t.path / "p.tscn"));
    EXPECT_EQ(node(s, "Look").header.at("type"), "Node3D");
    EXPECT_THROW(node(s, "Camera"), std::runtime_error);
    for (const std::string bad : {"export p.json --to unity -o p.tscn", "export p.json --to godot -o p.txt",
                                  "export p.json --to godot -o nofolder/p.tscn", "export missing.json --to godot -o q.tscn"}) {
        r = brumeIn(t.path, bad);
        EXPECT_EQ(r.exitCode, 2) << bad;
        EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
    EXPECT_FALSE(fs::exists(t.path / "q.tscn"));
}

}  // namespace
