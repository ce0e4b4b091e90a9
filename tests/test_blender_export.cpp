// `brume export --to blender`: the script, run by Debian's Blender headless, rebuilds the fog and
// renders it with Cycles at single scattering; its EXR is compared with `brume render --reference`
// (relative mean absolute error <= 5%). Skips, saying so, only where Blender is not installed
// (scripts/lib.sh installs it: see docs/export.md for its cost).
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "core/image.h"
#include "io/image_io.h"
#include "test_support.h"

namespace fs = std::filesystem;

namespace {

using brume::test::quoted;
using brume::test::readText;
using brume::test::TempDir;
using namespace brume;

bool haveBlender() { return std::system("command -v blender >/dev/null 2>&1") == 0; }

int sh(const fs::path& cwd, const std::string& cmd, const std::string& log) {
    const std::string full = "cd " + quoted(cwd.string()) + " && " + cmd + " >" + quoted(log) + " 2>&1";
    const int status = std::system(full.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

struct Renders {
    Image blender, reference;
};

// Exports `scene`, renders it with Blender and with brume --reference at 48x27.
std::optional<Renders> blenderAndReference(const std::string& name, const std::string& scene, int samples) {
    TempDir t("blender", name);
    std::ofstream(t.path / "s.json") << scene;
    const std::string brume = quoted(BRUME_EXE);
    const std::string log = (t.path / "log.txt").string();
    EXPECT_EQ(sh(t.path, brume + " export s.json --to blender -o s.py", log), 0) << readText(log);
    EXPECT_EQ(sh(t.path, brume + " render s.json -o ref.exr --reference --width 48 --height 27", log), 0) << readText(log);
    const int rc = sh(t.path,
                      "blender -b --factory-startup --python s.py -- --render " + quoted((t.path / "b.exr").string()) +
                          " --samples " + std::to_string(samples) + " --width 48 --height 27",
                      log);
    EXPECT_EQ(rc, 0) << readText(log);
    Result<Image> ref = readExr((t.path / "ref.exr").string());
    Result<Image> got = readExr((t.path / "b.exr").string());
    if (!ref || !got) {
        ADD_FAILURE() << "missing image; blender log:\n" << readText(log);
        return std::nullopt;
    }
    EXPECT_EQ(got.value().width, 48);
    return Renders{got.value(), ref.value()};
}

double blenderVsReference(const std::string& name, const std::string& scene, int samples) {
    const std::optional<Renders> r = blenderAndReference(name, scene, samples);
    return r ? relativeMeanAbsError(r->blender, r->reference) : 1.0;
}

Image referenceRender(const std::string& name, const std::string& scene) {
    TempDir t("blender", name);
    std::ofstream(t.path / "s.json") << scene;
    const std::string log = (t.path / "log.txt").string();
    EXPECT_EQ(sh(t.path, quoted(BRUME_EXE) + " render s.json -o ref.exr --reference --width 48 --height 27", log), 0) << readText(log);
    Result<Image> ref = readExr((t.path / "ref.exr").string());
    return ref ? ref.value() : Image(48, 27);
}

// A box of fog with coloured absorption and soft edges in front of an emissive wall, on a ground
// lit by a low sun (shadows) and a spot, and a glowing absorbing box: sigma_s, sigma_a, g, emission,
// edge fade, both light units. (Emission sits in a non-scattering medium: Cycles renders emission
// inside scattering media brighter than single scattering allows; docs/export.md.)
const char* kBoxScene = R"({"brume_scene": 1,
  "camera": {"position": [0, 1.5, 6], "target": [0, 1, 0], "fov_y_deg": 45, "near": 0.1, "far": 40},
  "render": {"width": 48, "height": 27},
  "lights": [
    {"type": "directional", "name": "sun", "direction": [0.5, -0.6, -0.6], "color": [1, 0.9, 0.8], "intensity": 3, "shadows": true},
    {"type": "spot", "name": "spot", "position": [-2, 3.5, 1.5], "direction": [0.5, -1, -0.4], "inner_deg": 15, "outer_deg": 30,
     "color": [0.6, 0.8, 1], "intensity": 30, "shadows": true}],
  "volumes": [
    {"type": "box", "name": "fog", "transform": {"translation": [0, 1, 0], "rotation_deg": [0, 25, 0], "scale": [3, 2, 2]},
     "edge_fade": 0.3, "medium": {"scattering": [0.8, 0.7, 0.6], "absorption": [0.1, 0.3, 0.5], "phase_g": 0.4}},
    {"type": "box", "name": "embers", "transform": {"translation": [1.8, 0.4, 1.2], "scale": [0.8, 0.8, 0.8]},
     "edge_fade": 0.5, "medium": {"scattering": [0, 0, 0], "absorption": [0.5, 1.0, 2.0], "emission": [0.6, 0.25, 0.05]}}],
  "geometry": [
    {"type": "plane", "name": "ground", "albedo": [0.5, 0.5, 0.5]},
    {"type": "box", "name": "wall", "transform": {"translation": [0, 2, -3], "scale": [10, 4, 0.2]}, "albedo": [0.3, 0.3, 0.3], "emission": [0.2, 0.2, 0.25]}]})";

// Exponential height fog under a point light, seen from above so that every ray ends on the ground.
const char* kHeightScene = R"({"brume_scene": 1,
  "camera": {"position": [0, 4, 5], "target": [0, 0, 0], "fov_y_deg": 40, "near": 0.1, "far": 30},
  "render": {"width": 48, "height": 27},
  "lights": [{"type": "point", "name": "bulb", "position": [0.5, 1.2, 0.5], "color": [1, 0.8, 0.6], "intensity": 6, "shadows": true}],
  "volumes": [{"type": "height", "name": "mist", "base_height": 0.3, "falloff": 1.5,
               "medium": {"scattering": [0.4, 0.4, 0.4], "absorption": [0.05, 0.05, 0.05], "phase_g": 0.2}}],
  "geometry": [{"type": "plane", "name": "ground", "albedo": [0.6, 0.6, 0.6]},
               {"type": "sphere", "name": "ball", "center": [-1, 0.6, -0.5], "radius": 0.6, "albedo": [0.7, 0.3, 0.3]}]})";

// kBoxScene with the fog box broken up by a density texture (assets/noise/mist.vdb, tiled every
// 1.5 m, scrolling): Blender gets it as a Volume object reading the bake of the textured box.
std::string texturedBoxScene() {
    std::string s = kBoxScene;
    const std::string fade = "\"edge_fade\": 0.3,";
    s.insert(s.find(fade) + fade.size(), R"( "density_texture": {"file": ")" + std::string(BRUME_SOURCE_DIR) +
                                            R"(/assets/noise/mist.vdb", "tile_size_m": 1.0, "strength": 4, "scroll_mps": [0.2, 0, 0]},)");
    return s;
}

// Without Blender: the data the script builds from carries Principled Volume values whose
// coefficients are Brume's (sigma_s = density color, sigma_a = density (1 - color)(1 - sqrt(absorption
// color))), lights in Cycles units, and one loss line per unmapped item.
TEST(BlenderExport, ScriptCarriesTheMapping) {
    TempDir t("blender", "mapping");
    std::ofstream(t.path / "s.json") << kBoxScene;
    const std::string log = (t.path / "log.txt").string();
    ASSERT_EQ(sh(t.path, quoted(BRUME_EXE) + " export s.json --to blender -o s.py", log), 0) << readText(log);
    const std::string out = readText(log);
    const std::string script = readText(t.path / "s.py");
    const std::string marker = "json.loads(r" + std::string(3, '\'');
    const size_t begin = script.find(marker);
    ASSERT_NE(begin, std::string::npos);
    const size_t end = script.find(std::string(3, '\'') + ")", begin);
    const nlohmann::json data = nlohmann::json::parse(script.substr(begin + marker.size(), end - begin - marker.size()));
    const nlohmann::json& fog = data["volumes"][0];
    const double sigmaS[3] = {0.8, 0.7, 0.6}, sigmaA[3] = {0.1, 0.3, 0.5};
    const double d = fog["density"].get<double>();
    EXPECT_NEAR(d, 1.1, 1e-6);
    for (int c = 0; c < 3; ++c) {
        const double color = fog["color"][c].get<double>(), ac = fog["absorption_color"][c].get<double>();
        EXPECT_NEAR(d * color, sigmaS[c], 1e-6);
        EXPECT_NEAR(d * (1.0 - color) * (1.0 - std::sqrt(ac)), sigmaA[c], 1e-6);
    }
    EXPECT_NEAR(fog["anisotropy"].get<double>(), 0.4, 1e-6);
    const nlohmann::json& embers = data["volumes"][1];
    EXPECT_NEAR(embers["emission_strength"].get<double>() * embers["emission_color"][1].get<double>(), 0.25, 1e-6);
    EXPECT_NEAR(data["lights"][0]["energy"].get<double>(), 3.0, 1e-6);                  // sun: W/m^2
    EXPECT_NEAR(data["lights"][1]["energy"].get<double>(), 4.0 * M_PI * 30.0, 1e-3);    // spot: P = 4 pi I
    EXPECT_NE(out.find("loss: lights[1] \"spot\": Cycles also scales a spot's cone"), std::string::npos) << out;
    EXPECT_NE(script.find("# loss: lights[1] \"spot\""), std::string::npos);
}

// The textured box becomes a Volume object reading its bake (density = sigma_t), scaled back by the
// medium's mean sigma_t; the scroll is reported as a loss, the texture no longer is.
TEST(BlenderExport, DensityTextureIsBakedBesideTheScript) {
    TempDir t("blender", "texture_data");
    std::ofstream(t.path / "s.json") << texturedBoxScene();
    const std::string log = (t.path / "log.txt").string();
    ASSERT_EQ(sh(t.path, quoted(BRUME_EXE) + " export s.json --to blender -o s.py", log), 0) << readText(log);
    const std::string out = readText(log);
    EXPECT_TRUE(fs::exists(t.path / "s_volume0.vdb")) << out;
    const std::string script = readText(t.path / "s.py");
    const std::string marker = "json.loads(r" + std::string(3, '\'');
    const size_t begin = script.find(marker);
    ASSERT_NE(begin, std::string::npos);
    const size_t end = script.find(std::string(3, '\'') + ")", begin);
    const nlohmann::json data = nlohmann::json::parse(script.substr(begin + marker.size(), end - begin - marker.size()));
    const nlohmann::json& v = data["volumes"][0];
    EXPECT_EQ(v["kind"], "vdb");
    EXPECT_EQ(v["grid"], "density");
    EXPECT_EQ(fs::path(v["file"].get<std::string>()).filename(), "s_volume0.vdb");
    EXPECT_NEAR(v["density_scale"].get<double>(), 3.0 / (0.9 + 1.0 + 1.1), 1e-6);
    EXPECT_NE(out.find("does not scroll in Blender"), std::string::npos) << out;
    EXPECT_EQ(out.find("is not exported"), std::string::npos) << out;
    // A texture that cannot be read: one sentence, exit 2, no script and no grid written.
    std::string broken = texturedBoxScene();
    broken.replace(broken.find("mist.vdb"), 8, "nothing.vdb");
    std::ofstream(t.path / "b.json") << broken;
    EXPECT_EQ(sh(t.path, quoted(BRUME_EXE) + " export b.json --to blender -o b.py", log), 2) << readText(log);
    EXPECT_NE(readText(log).find("nothing.vdb"), std::string::npos) << readText(log);
    EXPECT_FALSE(fs::exists(t.path / "b.py"));
    EXPECT_FALSE(fs::exists(t.path / "b_volume0.vdb"));
}

// The whole image within 5% of the reference, as for the other scenes; and, since the texture moves
// only part of the image, where it does (pixels where the references with and without it differ by
// over 5%) Blender's render is clearly nearer the textured reference than the plain one.
TEST(BlenderExport, DensityTexturedBoxRendersLikeTheReference) {
    if (!haveBlender()) GTEST_SKIP() << "Blender is not installed (apt-get install blender): the Blender export is not checked";
    const std::optional<Renders> r = blenderAndReference("texture", texturedBoxScene(), 512);
    ASSERT_TRUE(r.has_value());
    const double err = relativeMeanAbsError(r->blender, r->reference);
    const Image plain = referenceRender("plain", kBoxScene);
    double toTextured = 0.0, toPlain = 0.0, total = 0.0;
    for (size_t i = 0; i < plain.pixels.size(); ++i) {
        const glm::vec3 textured = r->reference.pixels[i];
        const glm::vec3 d = glm::abs(textured - plain.pixels[i]);
        if (d.x + d.y + d.z <= 0.05f * (textured.x + textured.y + textured.z)) continue;
        for (int c = 0; c < 3; ++c) {
            toTextured += std::abs(r->blender.pixels[i][c] - textured[c]);
            toPlain += std::abs(r->blender.pixels[i][c] - plain.pixels[i][c]);
            total += textured[c];
        }
    }
    std::printf("Blender (Cycles) vs brume --reference, density-textured box: %.4f; where the texture matters, "
                "%.3f from the textured reference, %.3f from the plain one\n", err, toTextured / total, toPlain / total);
    EXPECT_LE(err, 0.05);
    EXPECT_LT(toTextured, 0.75 * toPlain) << "Blender's fog should follow the texture";
}

TEST(BlenderExport, BoxFogRendersLikeTheReference) {
    if (!haveBlender()) GTEST_SKIP() << "Blender is not installed (apt-get install blender): the Blender export is not checked";
    const double err = blenderVsReference("box", kBoxScene, 512);
    std::printf("Blender (Cycles) vs brume --reference, box fog: %.4f\n", err);
    EXPECT_LE(err, 0.05);
}

TEST(BlenderExport, HeightFogRendersLikeTheReference) {
    if (!haveBlender()) GTEST_SKIP() << "Blender is not installed (apt-get install blender): the Blender export is not checked";
    const double err = blenderVsReference("height", kHeightScene, 256);
    std::printf("Blender (Cycles) vs brume --reference, height fog: %.4f\n", err);
    EXPECT_LE(err, 0.05);
}

}  // namespace
