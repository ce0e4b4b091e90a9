// The editor's debug views: the `debug` action (no window), and under Xvfb (xvfb-run) the viewport
// after `debug density 12` equals `brume render --debug-view density --debug-slice 12`.
#include <gtest/gtest.h>

#include "test_support.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/editor/debug_view.h"
#include "core/debug_view.h"
#include "io/image_io.h"

namespace fs = std::filesystem;
using namespace brume;

namespace {

using brume::test::quoted;

Result<void> debugAction(editor::DebugViewState& s, const std::string& line) {
    Result<editor::Action> a = editor::parseAction(line);
    if (!a) return a.error();
    const FroxelSettings froxels{16, 32, 0.5f, 50.0f, 2.0f};
    return editor::runDebugAction(s, a.value(), froxels);
}

const std::string kDefaultScene = std::string(BRUME_SOURCE_DIR) + "/assets/scenes/default.json";

// Runs a shell command; returns its exit code, with stdout+stderr in `log`.
int sh(const std::string& cmd, std::string& log) {
    const fs::path out = fs::temp_directory_path() / ("brume_editor_debug_log_" + std::to_string(::getpid()));
    const int status = std::system((cmd + " > " + quoted(out.string()) + " 2>&1").c_str());
    std::ifstream f(out);
    std::stringstream ss;
    ss << f.rdbuf();
    log = ss.str();
    fs::remove(out);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

TEST(EditorDebug, DebugActionSetsViewSliceAndGridAndRejectsBadInput) {
    editor::DebugViewState s;
    ASSERT_TRUE(debugAction(s, "debug density 12").ok());
    EXPECT_EQ(s.view, shd::DEBUG_VIEW_DENSITY);
    EXPECT_EQ(s.slice, 12);
    ASSERT_TRUE(debugAction(s, "debug transmittance").ok());  // the slice stays
    EXPECT_EQ(s.view, shd::DEBUG_VIEW_TRANSMITTANCE);
    EXPECT_EQ(s.slice, 12);
    ASSERT_TRUE(debugAction(s, "debug slice 3").ok());
    EXPECT_EQ(s.slice, 3);
    // By depth: the slice whose depth range holds it, at every depth of the grid.
    for (float z : {0.0f, 0.3f, 0.5f, 1.0f, 7.25f, 20.0f, 49.9f}) {
        ASSERT_TRUE(debugAction(s, "debug depth " + std::to_string(z)).ok()) << z;
        const float n = 32.0f;
        const float z1 = shd::viewDepthFromSliceT(static_cast<float>(s.slice + 1) / n, 0.5f, 50.0f, 2.0f);
        const float z0 = s.slice == 0 ? 0.0f : shd::viewDepthFromSliceT(static_cast<float>(s.slice) / n, 0.5f, 50.0f, 2.0f);
        EXPECT_LE(z0, z + 1e-4f) << z;
        EXPECT_LT(z, z1 + 1e-4f) << z;
    }
    ASSERT_TRUE(debugAction(s, "debug depth 1000").ok());  // past the grid: its last slice
    EXPECT_EQ(s.slice, 31);
    ASSERT_TRUE(debugAction(s, "debug slice 3").ok());
    ASSERT_TRUE(debugAction(s, "debug grid on").ok());
    EXPECT_TRUE(s.grid);
    for (const char* bad : {"debug", "debug fog", "debug density -1", "debug density 5000", "debug slice x",
                            "debug grid maybe", "debug density 1 2", "debug depth -2", "debug depth x"}) {
        const editor::DebugViewState before = s;
        EXPECT_FALSE(debugAction(s, bad).ok()) << bad;
        EXPECT_EQ(s.view, before.view) << bad;
        EXPECT_EQ(s.slice, before.slice) << bad;
    }
    ASSERT_TRUE(debugAction(s, "debug final").ok());
    EXPECT_EQ(s.view, shd::DEBUG_VIEW_FINAL);
}

#ifdef BRUME_EDITOR_EXE
TEST(EditorDebug, DensitySliceScreenshotEqualsTheCommandLine) {
    if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0)
        GTEST_SKIP() << "xvfb-run is missing (apt-get install xvfb xauth): windowed editor tests skipped";
    const fs::path dir = fs::temp_directory_path() / ("brume_editor_debug_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ofstream(dir / "debug.txt") << "debug density 12\n";
    std::string log;
    // The viewport keeps accumulating while it rests: its 3rd frame is `--frames 3`.
    ASSERT_EQ(sh("xvfb-run -a -s '-screen 0 640x480x24' " + std::string(BRUME_EDITOR_EXE) + " " +
                     quoted(kDefaultScene) + " --width 160 --height 90 --quality low --validation --hide-ui "
                     "--frames 3 --script " + quoted((dir / "debug.txt").string()) + " --screenshot " +
                     quoted((dir / "editor.png").string()), log), 0) << log;
    for (const char* view : {"density", "final"})
        ASSERT_EQ(sh(std::string(BRUME_EXE) + " render " + quoted(kDefaultScene) + " -o " +
                         quoted((dir / (std::string(view) + ".png")).string()) +
                         " --width 160 --height 90 --quality low --frames 3 --debug-view " + view + " --debug-slice 12",
                     log), 0) << log;
    Result<Image> shot = readPngLinear((dir / "editor.png").string());
    Result<Image> cli = readPngLinear((dir / "density.png").string());
    Result<Image> final = readPngLinear((dir / "final.png").string());
    ASSERT_TRUE(shot.ok() && cli.ok() && final.ok());
    const double err = relativeMeanAbsError(shot.value(), cli.value());
    const double vsFinal = relativeMeanAbsError(final.value(), cli.value());
    std::printf("editor 'debug density 12' vs brume render --debug-view density: %.3g (vs the final image: %.3g)\n",
                err, vsFinal);
    EXPECT_LT(err, 0.005);    // same renderer, same bytes: measured 0
    EXPECT_GT(vsFinal, 0.2);  // the debug view did replace the image
    fs::remove_all(dir);
}
#endif
