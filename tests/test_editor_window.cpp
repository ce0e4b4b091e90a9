// brume-editor end to end, in a real window under Xvfb (xvfb-run): the viewport matches the headless
// renderer, a scripted session edits and saves through the same actions as the UI, and a kill -9
// mid-session is recovered from the autosave. Windows are 160x90 at low quality: each run is ~1 s.
// Every run has the Vulkan validation layer on (--validation exits 1 on any message).
#include <gtest/gtest.h>

#include "test_support.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "core/image.h"
#include "io/image_io.h"
#include "io/scene_json.h"
#include "shaders/shared/tonemap.h"
#include "mesh_test_util.h"
#include "vdb_test_util.h"

namespace fs = std::filesystem;
using namespace brume;

namespace {

using brume::test::quoted;
using brume::test::readText;

const std::string kDefaultScene = std::string(BRUME_SOURCE_DIR) + "/assets/scenes/default.json";
const std::string kXvfb = "xvfb-run -a -s '-screen 0 640x480x24' ";
const std::string kSmall = " --width 160 --height 90 --quality low --validation";

bool haveXvfb() { return std::system("command -v xvfb-run > /dev/null 2>&1") == 0; }

#define REQUIRE_XVFB()                                                          \
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is missing (apt-get install xvfb xauth): windowed editor tests skipped"

// Runs a shell command; returns its exit code, with stdout+stderr in `log`.
int sh(const std::string& cmd, std::string* log = nullptr) {
    const fs::path out = fs::temp_directory_path() / ("brume_editor_log_" + std::to_string(::getpid()));
    const int status = std::system((cmd + " > " + quoted(out.string()) + " 2>&1").c_str());
    if (log) *log = readText(out);
    fs::remove(out);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

fs::path tempDir(const std::string& name) {
    fs::path d = fs::temp_directory_path() / ("brume_editor_win_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    fs::copy_file(kDefaultScene, d / "scene.json");
    // The editor keeps its recent-files list there: keep the tests off the user's.
    ::setenv("XDG_CONFIG_HOME", (d / "config").c_str(), 1);
    return d;
}

std::string editor(const fs::path& scene) { return std::string(BRUME_EDITOR_EXE) + " " + quoted(scene.string()); }

}  // namespace

TEST(EditorWindow, ScreenshotOfTheViewportMatchesTheHeadlessRender) {
    REQUIRE_XVFB();
    const fs::path dir = tempDir("shot");
    std::string log;
    // The viewport accumulates while the view rests: its 3rd frame is `brume render --frames 3`.
    ASSERT_EQ(sh(kXvfb + editor(dir / "scene.json") + kSmall + " --hide-ui --frames 3 --screenshot " +
                 quoted((dir / "editor.png").string()), &log), 0) << log;
    for (const char* frames : {"1", "3"})
        ASSERT_EQ(sh(std::string(BRUME_EXE) + " render " + quoted((dir / "scene.json").string()) + " -o " +
                     quoted((dir / ("cli" + std::string(frames) + ".png")).string()) +
                     " --width 160 --height 90 --quality low --frames " + frames, &log), 0) << log;
    Result<Image> a = readPngLinear((dir / "editor.png").string());
    Result<Image> b = readPngLinear((dir / "cli3.png").string());
    Result<Image> one = readPngLinear((dir / "cli1.png").string());
    ASSERT_TRUE(a.ok() && b.ok() && one.ok());
    ASSERT_EQ(a.value().width, 160);
    ASSERT_EQ(a.value().height, 90);
    // Same renderer, same display transform and 8-bit rounding: the bytes agree; 0.5% leaves room
    // for a different device behind the two processes.
    const double err = relativeMeanAbsError(a.value(), b.value());
    const double unaccumulated = relativeMeanAbsError(one.value(), b.value());
    std::printf("editor viewport vs brume render --frames 3: relative mean abs error %.3g "
                "(1 frame vs 3: %.3g)\n", err, unaccumulated);
    EXPECT_LT(err, 0.005);
    // The accumulation shows: a viewport restarting the history every frame would be `--frames 1`.
    EXPECT_GT(unaccumulated, 2.0 * err);
    fs::remove_all(dir);
}

// Scale while interacting (app/editor/accumulation.h Interaction): the frames of a drag render
// coarse (low, at most half size, smaller when the frames miss the budget: here 1 ms, which every
// frame misses, so the scale must shrink), and once the drag ends the view restarts at its preset
// and full size, so its Nth frame at rest is `brume render --frames N` of the moved scene, whatever
// size and froxel grid the coarse frames had.
TEST(EditorWindow, CoarseWhileDraggingThenAtRestEqualsTheHeadlessRender) {
    REQUIRE_XVFB();
    const fs::path dir = tempDir("interactive");
    // One action per frame: frames 1-5 are inside the drag (coarse), 6-9 rest (save changes nothing).
    std::ofstream(dir / "drag.txt") << "begin\n"
                                       "set volumes[0].transform.translation 1.5 1.2 -1.2\n"
                                       "set volumes[0].transform.translation 1.3 1.2 -1.1\n"
                                       "set volumes[0].transform.translation 1.2 1.3 -1.1\n"
                                       "set volumes[0].transform.translation 1.0 1.3 -1.0\n"
                                       "end\n"
                                       "save \"" << (dir / "moved.json").string() << "\"\n";
    std::string log;
    ASSERT_EQ(sh(kXvfb + editor(dir / "scene.json") + " --width 160 --height 90 --quality medium --validation" +
                 " --frame-budget-ms 1 --hide-ui --bench --frames 9 --script " + quoted((dir / "drag.txt").string()) +
                 " --screenshot " + quoted((dir / "editor.png").string()), &log), 0) << log;
    // --bench counts the kinds of frames after the first: frames 2-5 were coarse, 6-9 at rest.
    EXPECT_NE(log.find("coarse     4 frames"), std::string::npos) << log;
    EXPECT_NE(log.find("rest       4 frames"), std::string::npos) << log;
    // The scale adapted: frame 3 measured itself over budget, so frame 4 (or 5) was smaller.
    double first = 0.0, last = 0.0;
    const size_t at = log.find("coarse scale: first");
    ASSERT_NE(at, std::string::npos) << log;
    ASSERT_EQ(std::sscanf(log.c_str() + at, "coarse scale: first %lf, last %lf", &first, &last), 2) << log;
    EXPECT_DOUBLE_EQ(first, 0.5);
    EXPECT_LT(last, first);
    EXPECT_NE(log.find("settle     1 times"), std::string::npos) << log;
    ASSERT_EQ(sh(std::string(BRUME_EXE) + " render " + quoted((dir / "moved.json").string()) + " -o " +
                 quoted((dir / "cli.png").string()) + " --width 160 --height 90 --quality medium --frames 4", &log), 0)
        << log;
    Result<Image> a = readPngLinear((dir / "editor.png").string());
    Result<Image> b = readPngLinear((dir / "cli.png").string());
    ASSERT_TRUE(a.ok() && b.ok());
    const double err = relativeMeanAbsError(a.value(), b.value());
    std::printf("editor at rest after a drag vs brume render --frames 4: relative mean abs error %.3g\n", err);
    EXPECT_LT(err, 0.01);
    fs::remove_all(dir);
}

// A coarse frame's display (app/editor/present_path.h, PresentPath::Upscale): the source is tone
// mapped at its own size and its display bytes are scaled up bilinearly by the device's blit. With
// the scale fixed at 0.5 (budget 0), the coarse frames of a 160x90 window are the `low` preset at
// 80x45 (the froxel tile of `low` at 0.5), so the window is `brume render` at 80x45 scaled up:
// computed here on the CPU from the PNG's bytes, with the blit's texel centres and edge clamp.
TEST(EditorWindow, CoarseFrameIsTheToneMappedSourceScaledUp) {
    REQUIRE_XVFB();
    const fs::path dir = tempDir("upscale");
    // Frame 1 opens a group (coarse, 80x45, history restarted by the new size); frame 2 takes the
    // screenshot while the group is open: the view rests, so it accumulates its second frame.
    std::ofstream(dir / "coarse.txt") << "begin\nscreenshot \"" << (dir / "editor.png").string() << "\"\nend\nquit\n";
    std::string log;
    ASSERT_EQ(sh(kXvfb + editor(dir / "scene.json") + kSmall + " --hide-ui --bench --interactive-scale 0.5" +
                 " --frame-budget-ms 0 --script " + quoted((dir / "coarse.txt").string()), &log), 0) << log;
    EXPECT_NE(log.find("present: upscale (gpu)"), std::string::npos) << log;  // lavapipe blits BGRA8 linearly
    ASSERT_EQ(sh(std::string(BRUME_EXE) + " render " + quoted((dir / "scene.json").string()) + " -o " +
                 quoted((dir / "cli.png").string()) + " --width 80 --height 45 --quality low --frames 2", &log), 0) << log;
    Result<Image> shot = readPngLinear((dir / "editor.png").string());
    Result<Image> small = readPngLinear((dir / "cli.png").string());
    ASSERT_TRUE(shot.ok() && small.ok());
    ASSERT_EQ(shot.value().width, 160);
    ASSERT_EQ(small.value().width, 80);
    auto byte = [](float linear) { return std::lround(shd::srgbEncode(linear) * 255.0f); };  // the PNG's byte again
    const Image& a = shot.value();
    const Image& s = small.value();
    auto texel = [&](int x, int y, int c) {
        x = std::clamp(x, 0, s.width - 1);
        y = std::clamp(y, 0, s.height - 1);
        return static_cast<double>(byte(s.pixels[static_cast<size_t>(y) * s.width + x][c]));
    };
    double sumDiff = 0.0;
    long maxDiff = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            const double u = (x + 0.5) * s.width / a.width - 0.5, v = (y + 0.5) * s.height / a.height - 0.5;
            const int x0 = static_cast<int>(std::floor(u)), y0 = static_cast<int>(std::floor(v));
            const double wx = u - x0, wy = v - y0;
            for (int c = 0; c < 3; ++c) {
                const double top = texel(x0, y0, c) * (1 - wx) + texel(x0 + 1, y0, c) * wx;
                const double bottom = texel(x0, y0 + 1, c) * (1 - wx) + texel(x0 + 1, y0 + 1, c) * wx;
                const long want = std::lround(top * (1 - wy) + bottom * wy);
                const long diff = std::labs(byte(a.pixels[static_cast<size_t>(y) * a.width + x][c]) - want);
                sumDiff += static_cast<double>(diff);
                maxDiff = std::max(maxDiff, diff);
            }
        }
    const double meanDiff = sumDiff / (3.0 * a.width * a.height);
    std::printf("coarse window vs brume render 80x45 scaled up on the CPU: mean %.3f, max %ld (8-bit steps)\n",
                meanDiff, maxDiff);
    // The blit filters 8-bit values with its own weight precision: a step of rounding apart.
    EXPECT_LE(maxDiff, 2);
    EXPECT_LT(meanDiff, 0.5);
    fs::remove_all(dir);
}

// The idle editor sleeps (app/editor/frame_pacing.h): once the view has converged and nothing moves,
// it draws ~2 frames a second instead of redrawing the same UI without end (which took ~1.2 of this
// machine's 2 cores; a 160x90 window drew 842 UI-only frames in 3 s). The count of UI-only frames is
// bounded by the run's wall time over the pacer's sleep, whatever the machine's speed: on a busy
// machine the first frames (compiling) take longer and leave fewer idle seconds, never more frames.
TEST(EditorWindow, AnIdleEditorSleepsBetweenFrames) {
    REQUIRE_XVFB();
    const fs::path dir = tempDir("idle");
    std::ofstream(dir / "idle.txt") << "wait 6\nquit\n";
    std::string log;
    const auto start = std::chrono::steady_clock::now();
    ASSERT_EQ(sh(kXvfb + editor(dir / "scene.json") + kSmall + " --bench --script " + quoted((dir / "idle.txt").string()),
                 &log),
              0)
        << log;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    auto framesOf = [&log](const char* kind) {
        size_t n = 0;
        const std::string label = std::string("  ") + kind + " ";
        const size_t at = log.find(label);
        if (at != std::string::npos) std::sscanf(log.c_str() + at + label.size(), "%zu frames", &n);
        return n;
    };
    const size_t uiFrames = framesOf("ui"), restFrames = framesOf("rest");
    std::printf("%.1f s: %zu frames rendered, %zu UI-only\n", seconds, restFrames, uiFrames);
    // <= 2 a second, plus the settling frames after the last render and a few early wakes (the
    // window's first events).
    EXPECT_LE(static_cast<double>(uiFrames), 2.0 * seconds + 12.0) << log;
    // Converged (20 frames at low's history weight; the report skips the first): it drew its settling
    // frames and kept drawing.
    if (restFrames >= 19) {
        EXPECT_GE(uiFrames, 3u) << log;
    }
    fs::remove_all(dir);
}

// Hiding or deleting a volume changes the volume list the renderer specializes its pipelines for
// (0.4-1 s of compiling at 1280x720 on lavapipe). The frames after it render the missing volume as a
// dark stand-in on the pipelines of before (app/editor/view.h withStandIns, the same image) until the
// preparation at rest has made the new list's: no frame's render compiles.
TEST(EditorWindow, HidingOrDeletingAVolumeRendersStandInsInsteadOfCompiling) {
    REQUIRE_XVFB();
    const fs::path dir = tempDir("hide");
    std::ofstream(dir / "hide.txt") << "wait 0\nwait 0\nhide volume 0\nwait 0\nwait 0\nwait 0\n"
                                       "show volume 0\nwait 0\nwait 0\ndelete volume 1\nwait 0\nwait 0\nquit\n";
    std::string log;
    ASSERT_EQ(sh(kXvfb + editor(dir / "scene.json") + kSmall + " --hide-ui --bench --script " +
                     quoted((dir / "hide.txt").string()),
                 &log),
              0)
        << log;
    EXPECT_NE(log.find("compiled 0 frames"), std::string::npos) << log;
    EXPECT_NE(log.find("settle     3 times"), std::string::npos) << log;  // the hide, the show, the delete
    fs::remove_all(dir);
}

TEST(EditorWindow, ScriptedSessionAddsMovesRetunesSavesAndUndoes) {
    REQUIRE_XVFB();
    const fs::path dir = tempDir("script");
    std::ofstream(dir / "session.txt") << "# as a user: add a fog box, drag it, change its density, save, undo\n"
                                          "add volume box \"test fog\"\n"
                                          "select volume 3\n"
                                          "begin\n"
                                          "set volumes[3].transform.translation 0.5 1 0\n"
                                          "set volumes[3].transform.translation 1 1.5 -0.5\n"
                                          "end\n"
                                          "set volumes[3].medium.scattering 0.9 0.8 0.7\n"
                                          "save\n"
                                          "undo\n"
                                          "undo\n"
                                          "save " + (dir / "undone.json").string() + "\n"
                                          "# click the box at the centre of the view, frame it (F)\n"
                                          "set volumes[3].transform.translation 0 1.1 0\n"
                                          "select none\n"
                                          "pick 0.5 0.5\n"
                                          "frame\n"
                                          "save " + (dir / "framed.json").string() + "\n"
                                          "quit\n";
    std::string log;
    ASSERT_EQ(sh(kXvfb + editor(dir / "scene.json") + kSmall + " --script " + quoted((dir / "session.txt").string()) +
                 " --record " + quoted((dir / "recorded.txt").string()), &log), 0) << log;
    Result<Scene> saved = loadSceneFile((dir / "scene.json").string());
    ASSERT_TRUE(saved.ok()) << saved.error().message;
    ASSERT_EQ(saved.value().volumes.size(), 4u);
    const Volume& v = saved.value().volumes[3];
    EXPECT_EQ(v.name, "test fog");
    EXPECT_EQ(v.transform.translation, glm::vec3(1.0f, 1.5f, -0.5f));
    EXPECT_EQ(v.medium.scattering, glm::vec3(0.9f, 0.8f, 0.7f));
    // Two undos: the density, then the whole drag (one step); the box itself stays.
    Result<Scene> undone = loadSceneFile((dir / "undone.json").string());
    ASSERT_TRUE(undone.ok()) << undone.error().message;
    ASSERT_EQ(undone.value().volumes.size(), 4u);
    EXPECT_EQ(undone.value().volumes[3].transform.translation, glm::vec3(0.0f));
    EXPECT_EQ(undone.value().volumes[3].medium.scattering, Medium{}.scattering);
    // The pick selected the unit box (framing anything else, or nothing, fails or aims elsewhere):
    // its bounding sphere (radius sqrt(3)/2) fills the 50 degree view with a 20% margin.
    Result<Scene> framed = loadSceneFile((dir / "framed.json").string());
    ASSERT_TRUE(framed.ok()) << framed.error().message;
    const Camera& c = framed.value().camera;
    EXPECT_LT(glm::distance(c.target, glm::vec3(0.0f, 1.1f, 0.0f)), 1e-4f);
    const float want = 1.2f * 0.5f * std::sqrt(3.0f) / std::sin(glm::radians(25.0f));
    EXPECT_NEAR(glm::distance(c.position, c.target), want, 1e-3f);
    // The recording replays the session (comments dropped, every action kept).
    const std::string recorded = readText(dir / "recorded.txt");
    EXPECT_NE(recorded.find("set volumes[3].medium.scattering 0.9 0.8 0.7"), std::string::npos) << recorded;
    EXPECT_EQ(recorded.find('#'), std::string::npos);
    EXPECT_NE(recorded.find("pick 0.5 0.5"), std::string::npos) << recorded;
    fs::remove_all(dir);
}

TEST(EditorWindow, KillNineMidEditThenRestartRecoversTheAutosave) {
    REQUIRE_XVFB();
    const fs::path dir = tempDir("kill");
    const fs::path scene = dir / "scene.json";
    const std::string original = readText(scene);
    std::ofstream(dir / "edit.txt") << "set volumes[0].medium.phase_g -0.4\nadd light spot lamp\nwait 120\n";
    const fs::path pidFile = dir / "editor.pid";
    const std::string inner = editor(scene) + kSmall + " --autosave-seconds 0.5 --script " +
                              quoted((dir / "edit.txt").string());
    // sh inside xvfb-run knows the editor's own pid, so the kill hits the editor, not the wrapper.
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        const std::string cmd = kXvfb + "sh -c " + quoted(inner + " & echo $! > " + pidFile.string() + "; wait") +
                                " > /dev/null 2>&1";
        execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
        _exit(127);
    }
    const fs::path recovery = dir / "scene.json.recovery.json";
    bool recovered = false;
    for (int i = 0; i < 600 && !recovered; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
        Result<Scene> s = fs::exists(recovery) ? loadSceneFile(recovery.string()) : Result<Scene>(Error{""});
        recovered = s.ok() && s.value().lights.size() == 4;
    }
    const pid_t editorPid = static_cast<pid_t>(std::atoi(readText(pidFile).c_str()));
    ASSERT_GT(editorPid, 0);
    ::kill(editorPid, SIGKILL);
    int status = 0;
    waitpid(child, &status, 0);
    ASSERT_TRUE(recovered) << "no autosave with the edits appeared within 60 s";
    EXPECT_EQ(readText(scene), original);  // the autosave never touches the scene file

    std::ofstream(dir / "after.txt") << "save\nquit\n";
    std::string log;
    ASSERT_EQ(sh(kXvfb + editor(scene) + kSmall + " --recover --script " + quoted((dir / "after.txt").string()), &log), 0)
        << log;
    Result<Scene> s = loadSceneFile(scene.string());
    ASSERT_TRUE(s.ok()) << s.error().message;
    EXPECT_FLOAT_EQ(s.value().volumes[0].medium.phase_g, -0.4f);
    ASSERT_EQ(s.value().lights.size(), 4u);
    EXPECT_EQ(s.value().lights[3].name, "lamp");
    EXPECT_FALSE(fs::exists(recovery));  // an orderly exit removes it
    fs::remove_all(dir);
}

// Files dropped on the window become `drop PATH` actions (main.cpp's GLFW drop callback); a script
// drives the same path. A dropped VDB is imported in front of the camera, loaded and rendered; a
// file that is not a VDB only notifies (the session goes on); the saved scene keeps the VDB's path
// relative to it, and the recent-files list (a temporary XDG_CONFIG_HOME) records the scene.
TEST(EditorWindow, DroppedVdbIsImportedAndRenderedAndABadDropOnlyNotifies) {
    REQUIRE_XVFB();
    const fs::path dir = tempDir("drop");
    // A 1.5 m cube of dense fog (sigma_t ~ 2.2/m at the default medium): plainly visible.
    test::writeGrids(dir / "cube.vdb", {test::makeGrid("density", 0, 15, [](openvdb::Coord) { return 20.0f; },
                                                       openvdb::math::Transform::createLinearTransform(0.1))});
    std::ofstream(dir / "notes.vdb") << "not an OpenVDB file\n";
    std::ofstream(dir / "session.txt") << "screenshot " + (dir / "before.png").string() + "\n"
                                          "drop " + (dir / "notes.vdb").string() + "\n"
                                          "drop " + (dir / "cube.vdb").string() + "\n"
                                          "screenshot " + (dir / "after.png").string() + "\n"
                                          "save\n"
                                          "quit\n";
    std::string log;
    ASSERT_EQ(sh("XDG_CONFIG_HOME=" + quoted((dir / "config").string()) + " " + kXvfb + editor(dir / "scene.json") +
                 kSmall + " --hide-ui --script " + quoted((dir / "session.txt").string()), &log), 0) << log;
    Result<Scene> saved = loadSceneFile((dir / "scene.json").string());
    ASSERT_TRUE(saved.ok()) << saved.error().message;
    ASSERT_EQ(saved.value().volumes.size(), 4u);  // the three of the default scene and the cube only
    EXPECT_EQ(saved.value().volumes[3].type, VolumeType::Vdb);
    EXPECT_EQ(saved.value().volumes[3].file, "cube.vdb");
    Result<Image> before = readPngLinear((dir / "before.png").string());
    Result<Image> after = readPngLinear((dir / "after.png").string());
    ASSERT_TRUE(before.ok() && after.ok());
    const double change = relativeMeanAbsError(after.value(), before.value());
    std::printf("dropped VDB cube: image changed by %.3g (relative mean abs)\n", change);
    EXPECT_GT(change, 0.02);  // an unloaded (empty) vdb volume would change nothing
    const std::string recent = readText(dir / "config" / "brume" / "recent.json");
    EXPECT_NE(recent.find((dir / "scene.json").string()), std::string::npos) << recent;
    fs::remove_all(dir);
}

// A dropped closed OBJ mesh becomes a fog hull (a mesh volume) in front of the camera and renders; a
// mesh with a hole only notifies.
TEST(EditorWindow, DroppedObjBecomesAHullAndAnOpenMeshOnlyNotifies) {
    REQUIRE_XVFB();
    const fs::path dir = tempDir("drop_obj");
    test::writeText(dir / "hull.obj", test::cubeObj(0.75f));
    test::writeText(dir / "open.obj", test::cubeObj(0.75f, 1));
    std::ofstream(dir / "session.txt") << "screenshot " + (dir / "before.png").string() + "\n"
                                          "drop " + (dir / "open.obj").string() + "\n"
                                          "drop " + (dir / "hull.obj").string() + "\n"
                                          "set volumes[3].medium.scattering 2 2 2\n"
                                          "screenshot " + (dir / "after.png").string() + "\n"
                                          "save\n"
                                          "quit\n";
    std::string log;
    ASSERT_EQ(sh(kXvfb + editor(dir / "scene.json") + kSmall + " --hide-ui --script " +
                 quoted((dir / "session.txt").string()), &log), 0) << log;
    Result<Scene> saved = loadSceneFile((dir / "scene.json").string());
    ASSERT_TRUE(saved.ok()) << saved.error().message;
    ASSERT_EQ(saved.value().volumes.size(), 4u);  // the three of the default scene and the hull only
    EXPECT_EQ(saved.value().volumes[3].type, VolumeType::Mesh);
    EXPECT_EQ(saved.value().volumes[3].file, "hull.obj");
    Result<Image> before = readPngLinear((dir / "before.png").string());
    Result<Image> after = readPngLinear((dir / "after.png").string());
    ASSERT_TRUE(before.ok() && after.ok());
    const double change = relativeMeanAbsError(after.value(), before.value());
    std::printf("dropped OBJ hull: image changed by %.3g (relative mean abs)\n", change);
    EXPECT_GT(change, 0.02);  // an empty hull would change nothing
    fs::remove_all(dir);
}

// The gizmo's three modes (`gizmo MODE`, what W / E / R run) each draw their own handles at the
// selection: a box moved to the view's centre, with the render held still (temporal off), is
// captured with nothing selected, then in each mode; around the centre the four images differ.
// 960x540, where the centre lies between the outliner and the inspector; the scene renders twice.
TEST(EditorWindow, EachGizmoModeDrawsItsHandles) {
    REQUIRE_XVFB();
    const fs::path dir = tempDir("gizmo");
    auto shot = [&](const std::string& name) { return "screenshot " + (dir / (name + ".png")).string() + "\n"; };
    std::ofstream(dir / "session.txt") << "set temporal.enabled false\n"
                                          "set volumes[0].transform.translation 0 1.1 0\n" + shot("none") +
                                          "select volume 0\n" + shot("translate") +
                                          "gizmo rotate\n" + shot("rotate") +
                                          "gizmo scale\n" + shot("scale") +
                                          "add light spot\nselect light 3\ngizmo rotate\nquit\n";
    std::string log;
    ASSERT_EQ(sh("xvfb-run -a -s '-screen 0 960x540x24' " + editor(dir / "scene.json") +
                 " --width 960 --height 540 --quality low --validation --script " +
                 quoted((dir / "session.txt").string()), &log), 0) << log;
    std::vector<Image> img;
    for (const char* name : {"none", "translate", "rotate", "scale"}) {
        Result<Image> r = readPngLinear((dir / (std::string(name) + ".png")).string());
        ASSERT_TRUE(r.ok()) << name;
        img.push_back(r.value());
    }
    // Mean abs difference over the 160x160 px around the centre, where the handles are drawn.
    auto centreDiff = [](const Image& a, const Image& b) {
        double sum = 0.0;
        for (int y = 270 - 80; y < 270 + 80; ++y)
            for (int x = 480 - 80; x < 480 + 80; ++x) {
                const glm::vec3 d = glm::abs(a.at(x, y) - b.at(x, y));
                sum += static_cast<double>(d.x + d.y + d.z) / 3.0;
            }
        return sum / (160.0 * 160.0);
    };
    for (size_t i = 0; i < img.size(); ++i)
        for (size_t j = i + 1; j < img.size(); ++j) {
            const double d = centreDiff(img[i], img[j]);
            std::printf("gizmo images %zu vs %zu: mean abs difference %.4g\n", i, j, d);
            EXPECT_GT(d, 1e-3) << i << " vs " << j;
        }
    fs::remove_all(dir);
}
