// The editor's scene time (app/editor/scene_time.h) under Xvfb: a scripted session on a scene with a
// scrolling density texture. `time 2` shows the texture moved; `time 0` again shows exactly the first
// image (temporal off, so each image is one frame and byte-comparable); `play on` moves time by the
// fixed 1/24 s per frame of scripted runs. 160x90 at low quality, validation on.
#include <gtest/gtest.h>

#include "test_support.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/image.h"
#include "io/image_io.h"

namespace fs = std::filesystem;
using namespace brume;

namespace {

using brume::test::quoted;

std::string readBytes(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

int sh(const std::string& cmd, std::string& log) {
    const fs::path out = fs::temp_directory_path() / ("brume_editor_time_log_" + std::to_string(::getpid()));
    const int status = std::system((cmd + " > " + quoted(out.string()) + " 2>&1").c_str());
    log = readBytes(out);
    fs::remove(out);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
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

TEST(EditorTime, ScriptedTimeMovesTheTextureAndComesBack) {
    if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0)
        GTEST_SKIP() << "xvfb-run is missing (apt-get install xvfb xauth): windowed editor tests skipped";
    const fs::path dir = fs::temp_directory_path() / ("brume_editor_time_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    ::setenv("XDG_CONFIG_HOME", (dir / "config").c_str(), 1);
    const std::string mist = std::string(BRUME_SOURCE_DIR) + "/assets/noise/mist.vdb";
    // A dense textured box filling the view, wind along x; temporal off: one frame per image.
    std::ofstream(dir / "scene.json") << R"({"brume_scene": 1,
        "camera": {"position": [0, 1, 5], "target": [0, 1, 0]}, "temporal": {"enabled": false},
        "lights": [{"type": "directional", "direction": [-0.5, -0.5, -0.7], "intensity": 3}],
        "volumes": [{"type": "box", "transform": {"translation": [0, 1, 0], "scale": [6, 3, 3]},
          "medium": {"scattering": [1.5, 1.5, 1.5]},
          "density_texture": {"file": ")" + mist + R"(", "tile_size_m": 2, "scroll_mps": [0.5, 0, 0], "strength": 2}}]})";
    auto shot = [&](const std::string& name) { return "screenshot " + (dir / (name + ".png")).string() + "\n"; };
    std::ofstream(dir / "session.txt") << "time 0\n" + shot("t0") + "time 2\n" + shot("t2") + "time 0\n" + shot("again") +
                                              "play on\nwait 0\nwait 0\nwait 0\n" + shot("played") + "quit\n";
    std::string log;
    ASSERT_EQ(sh("xvfb-run -a -s '-screen 0 640x480x24' " + std::string(BRUME_EDITOR_EXE) + " " +
                     quoted((dir / "scene.json").string()) + " --width 160 --height 90 --quality low --validation" +
                     " --hide-ui --script " + quoted((dir / "session.txt").string()), log), 0) << log;
    EXPECT_EQ(readBytes(dir / "again.png"), readBytes(dir / "t0.png")) << "time 0 again must give the same image";
    Result<Image> t0 = readPngLinear((dir / "t0.png").string()), t2 = readPngLinear((dir / "t2.png").string());
    Result<Image> played = readPngLinear((dir / "played.png").string());
    ASSERT_TRUE(t0.ok() && t2.ok() && played.ok());
    const double moved = meanAbsDifference(t0.value(), t2.value());
    const double playedMove = meanAbsDifference(t0.value(), played.value());
    std::printf("editor time: time 0 vs 2 differ by %.4g, vs 4 played frames by %.4g (mean abs, linear)\n", moved,
                playedMove);
    EXPECT_GT(moved, 1e-3) << "the texture should have scrolled 1 m";
    EXPECT_GT(playedMove, 1e-4) << "play on should advance time by 1/24 s per frame";
    fs::remove_all(dir);
}
