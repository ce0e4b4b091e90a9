// The editor's timeline (issue 16): `key PATH SECONDS` records the setting's value at a scene time
// as one undo step, keys interpolate as the renderers see them (core/animate.h), `unkey` removes
// them, bad keys are one sentence; and under Xvfb a scripted session keys a volume's scattering at
// two times, scrubs, and the view follows time (with the Timeline and Presets panels drawn).
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/editor/document.h"
#include "app/editor/scene_time.h"
#include "core/animate.h"
#include "core/image.h"
#include "io/image_io.h"
#include "test_support.h"

namespace fs = std::filesystem;
using namespace brume;
using namespace brume::editor;
using brume::test::quoted;
using brume::test::TempDir;

namespace {

void run(Document& doc, const std::string& line) {
    Result<Action> a = parseAction(line);
    ASSERT_TRUE(a.ok()) << a.error().message;
    Result<void> r = doc.apply(a.value());
    ASSERT_TRUE(r.ok()) << line << ": " << r.error().message;
}

Result<void> tryRun(Document& doc, const std::string& line) {
    Result<Action> a = parseAction(line);
    if (!a) return a.error();
    return doc.apply(a.value());
}

Scene boxScene() {
    Scene s;
    s.camera.position = {0, 1, 5};
    s.camera.target = {0, 1, 0};
    s.lights.push_back(makeLight(LightType::Directional));
    s.volumes.push_back(test::boxFog({0, 1, 0}, {3, 2, 3}, 0.2f, 0.5f, 0.0f));
    return s;
}

std::string readBytes(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

double meanAbsDifference(const Image& a, const Image& b) {
    double sum = 0.0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        const glm::vec3 d = glm::abs(a.pixels[i] - b.pixels[i]);
        sum += static_cast<double>(d.x + d.y + d.z) / 3.0;
    }
    return sum / static_cast<double>(a.pixels.size());
}

}  // namespace

TEST(EditorTimeline, KeysAtTwoTimesInterpolateAndEachIsOneUndoStep) {
    Document doc(boxScene(), "");
    run(doc, "key volumes[0].medium.scattering 0");
    run(doc, "set volumes[0].medium.scattering 2.5 1.5 0.5");
    run(doc, "key volumes[0].medium.scattering 2");
    ASSERT_EQ(doc.scene().volumes[0].keys.size(), 1u);
    const KeyTrack& track = doc.scene().volumes[0].keys[0];
    EXPECT_EQ(track.target, "medium.scattering");
    ASSERT_EQ(track.keys.size(), 2u);
    const auto sigmaAt = [&](float t) { return bakeKeys(doc.scene(), t).volumes[0].medium.scattering; };
    EXPECT_EQ(sigmaAt(0.0f), glm::vec3(0.5f));
    EXPECT_EQ(sigmaAt(2.0f), glm::vec3(2.5f, 1.5f, 0.5f));
    const glm::vec3 mid = sigmaAt(1.0f);
    EXPECT_NEAR(mid.x, 1.5f, 1e-5f);
    EXPECT_NEAR(mid.y, 1.0f, 1e-5f);
    EXPECT_NEAR(mid.z, 0.5f, 1e-5f);
    EXPECT_EQ(sigmaAt(9.0f), glm::vec3(2.5f, 1.5f, 0.5f)) << "after the last key the value holds";
    EXPECT_TRUE(sceneScrolls(doc.scene())) << "a keyed scene plays";

    // A key earlier than the others goes first; a key at the same time replaces the value.
    run(doc, "set volumes[0].medium.scattering 1 1 1");
    run(doc, "key volumes[0].medium.scattering -1");
    EXPECT_EQ(doc.scene().volumes[0].keys[0].keys.front().time, -1.0f);
    run(doc, "key volumes[0].medium.scattering 2");
    EXPECT_EQ(doc.scene().volumes[0].keys[0].keys.size(), 3u);
    EXPECT_EQ(doc.scene().volumes[0].keys[0].keys.back().value, glm::vec3(1.0f));

    run(doc, "undo");
    run(doc, "undo");
    EXPECT_EQ(doc.scene().volumes[0].keys[0].keys.size(), 2u);
    EXPECT_EQ(sigmaAt(2.0f), glm::vec3(2.5f, 1.5f, 0.5f)) << "undo restores the replaced key";
    run(doc, "unkey volumes[0].medium.scattering 0");
    EXPECT_EQ(doc.scene().volumes[0].keys[0].keys.size(), 1u);
    run(doc, "unkey volumes[0].medium.scattering 2");
    EXPECT_TRUE(doc.scene().volumes[0].keys.empty()) << "the last key takes its track";
    run(doc, "undo");
    EXPECT_EQ(doc.scene().volumes[0].keys.size(), 1u);

    run(doc, "key lights[0].intensity 0.5");
    EXPECT_EQ(doc.scene().lights[0].keys.size(), 1u);
}

TEST(EditorTimeline, BadKeysAreOneSentenceAndChangeNothing) {
    Document doc(boxScene(), "");
    const uint64_t revision = doc.revision();
    for (const char* bad : {"key volumes[0].name 0", "key volumes[3].medium.scattering 0", "key volumes[0].medium.nothing 0",
                            "key volumes[0].density_texture.scroll_mps 0", "key camera.position 0",
                            "key volumes[0].medium.scattering soon", "key volumes[0].medium.scattering",
                            "unkey volumes[0].medium.scattering 0", "key volumes[x].medium.scattering 0"}) {
        Result<void> r = tryRun(doc, bad);
        ASSERT_FALSE(r.ok()) << bad;
        EXPECT_EQ(r.error().message.find('\n'), std::string::npos) << r.error().message;
    }
    EXPECT_EQ(doc.revision(), revision);
    EXPECT_FALSE(doc.canUndo());
}

TEST(EditorTimeline, ScriptedKeysAndScrubMoveTheView) {
    if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0)
        GTEST_SKIP() << "xvfb-run is missing (apt-get install xvfb xauth): windowed editor tests skipped";
    TempDir t("editor_timeline", "xvfb");
    ::setenv("XDG_CONFIG_HOME", (t.path / "config").c_str(), 1);
    ::setenv("XDG_DATA_HOME", (t.path / "data").c_str(), 1);
    fs::create_directories(t.path / "data" / "brume" / "presets");
    std::ofstream(t.path / "data" / "brume" / "presets" / "broken.json") << "{\"brume_preset\": 1,";
    // Temporal off: one frame per image, so equal scenes give byte-equal screenshots.
    std::ofstream(t.path / "scene.json") << R"({"brume_scene": 1,
        "camera": {"position": [0, 1, 5], "target": [0, 1, 0]}, "temporal": {"enabled": false},
        "lights": [{"type": "directional", "direction": [-0.5, -0.5, -0.7], "intensity": 3}],
        "volumes": [{"type": "box", "transform": {"translation": [0, 1, 0], "scale": [6, 3, 3]},
          "medium": {"scattering": [0.2, 0.2, 0.2]}}]})";
    auto shot = [&](const std::string& name) { return "screenshot " + (t.path / (name + ".png")).string() + "\n"; };
    // Keys 0.2 at t=0 and 2 at t=2; then, undoing them, the same values set without keys.
    const std::string script = "select volume 0\ntime 0\nkey volumes[0].medium.scattering 0\n"
                               "set volumes[0].medium.scattering 2 2 2\nkey volumes[0].medium.scattering 2\n"
                               "time 0\n" + shot("t0") + "time 2\n" + shot("t2") + "time 1\n" + shot("t1") +
                               "undo\ntime 2\n" + shot("undone") + "undo\nundo\n" + shot("plain") +
                               "set volumes[0].medium.scattering 1.1 1.1 1.1\n" + shot("mid") +
                               "set volumes[0].medium.scattering 2 2 2\n" + shot("two") + "quit\n";
    std::ofstream(t.path / "session.txt") << script;
    const std::string editor = "xvfb-run -a -s '-screen 0 640x480x24' " + std::string(BRUME_EDITOR_EXE) + " " +
                               quoted((t.path / "scene.json").string()) + " --width 160 --height 90 --quality low --validation";
    const fs::path logFile = t.path / "log.txt";
    int status = std::system((editor + " --hide-ui --script " + quoted((t.path / "session.txt").string()) + " > " +
                              quoted(logFile.string()) + " 2>&1").c_str());
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << readBytes(logFile);
    const auto png = [&](const char* name) { return readBytes(t.path / (std::string(name) + ".png")); };
    EXPECT_NE(png("t0"), png("t2")) << "the view follows the keys";
    EXPECT_EQ(png("t2"), png("two")) << "at its t=2 key the view shows the key's value";
    EXPECT_EQ(png("undone"), png("t0")) << "with the t=2 key undone, t=2 shows the t=0 value";
    EXPECT_EQ(png("plain"), png("t0")) << "with every key undone the value is the t=0 one again";
    Result<Image> t1 = readPngLinear((t.path / "t1.png").string()), mid = readPngLinear((t.path / "mid.png").string());
    Result<Image> t0 = readPngLinear((t.path / "t0.png").string()), t2 = readPngLinear((t.path / "t2.png").string());
    ASSERT_TRUE(t0.ok() && t1.ok() && t2.ok() && mid.ok());
    const double keyed = meanAbsDifference(t1.value(), mid.value()), span = meanAbsDifference(t0.value(), t2.value());
    std::printf("editor timeline: t=1 vs the midpoint value set by hand %.3g, t=0 vs t=2 %.3g (mean abs, linear)\n", keyed, span);
    EXPECT_LT(keyed, 0.01 * span) << "halfway between the keys the view shows the interpolated value";

    // The panels drawn (a bad file in the user's presets folder among them), a preset applied and
    // saved from a script, with the validation layer on: the editor runs and exits cleanly.
    std::ofstream(t.path / "panels.txt") << "select volume 0\ntime 1.5\nkey volumes[0].medium.scattering 1.5\n"
                                            "preset apply " + std::string(BRUME_SOURCE_DIR) +
                                                "/assets/presets/underwater_murk.json add\n"
                                            "preset save \"From the editor\" \"A test look.\" test\nwait 0\n" +
                                                shot("panels") + "quit\n";
    status = std::system((editor + " --script " + quoted((t.path / "panels.txt").string()) + " > " + quoted(logFile.string()) +
                          " 2>&1").c_str());
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << readBytes(logFile);
    EXPECT_TRUE(fs::exists(t.path / "data" / "brume" / "presets" / "from-the-editor.json"));
    EXPECT_TRUE(fs::exists(t.path / "data" / "brume" / "presets" / "from-the-editor.png"));
    ::unsetenv("XDG_DATA_HOME");
}
