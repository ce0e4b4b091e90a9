// End-to-end tests of the `brume` command line: runs the built binary as a user would, checking
// exit codes, the one-line error contract, the files it writes (and does not leave behind) and the
// help text. Images are 64x36 at low quality to keep each test well under a second or two.
#include <gtest/gtest.h>

#include "test_support.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "core/image.h"
#include "core/settings.h"
#include "core/render.h"
#include "io/image_io.h"
#include "io/scene_json.h"

namespace fs = std::filesystem;

namespace {

using brume::test::quoted;
using brume::test::readText;

const std::string kDefaultScene = std::string(BRUME_SOURCE_DIR) + "/assets/scenes/default.json";
const std::string kSmall = " --width 64 --height 36 --quality low";

struct CliRun {
    int exitCode = -1;
    std::string out;
    std::string err;
};

void writeText(const fs::path& p, const std::string& text) {
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
}

std::set<std::string> listFolder(const fs::path& dir) {
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
    return names;
}

int countLines(const std::string& s) {
    int n = 0;
    for (char c : s) n += c == '\n';
    return n;
}

class Cli : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("brume_cli_" + std::to_string(getpid()) + "_" + info->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_ / "work");
        logs_ = dir_ / "logs";
        fs::create_directories(logs_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    // Runs `brume ARGS` in `cwd` (default: the test's work folder), capturing stdout and stderr.
    CliRun brume(const std::string& args, const fs::path& cwd = {}) const {
        const fs::path where = cwd.empty() ? dir_ / "work" : cwd;
        const std::string cmd = "cd " + quoted(where.string()) + " && " + quoted(BRUME_EXE) + " " + args + " >" +
                                quoted((logs_ / "out").string()) + " 2>" + quoted((logs_ / "err").string());
        const int status = std::system(cmd.c_str());
        CliRun r;
        r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        r.out = readText(logs_ / "out");
        r.err = readText(logs_ / "err");
        return r;
    }

    // The error contract for bad input: exit 2 and exactly one stderr line "error: ...".
    static void expectOneLineError(const CliRun& r, const std::string& mustMention) {
        EXPECT_EQ(r.exitCode, 2) << r.err;
        EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << r.err;
        EXPECT_EQ(countLines(r.err), 1) << r.err;
        EXPECT_NE(r.err.find(mustMention), std::string::npos) << "stderr should mention '" << mustMention << "': " << r.err;
    }

    fs::path dir_;
    fs::path logs_;
};

TEST_F(Cli, RenderPngWithEachRenderer) {
    for (const std::string renderer : {"", " --cpu", " --reference"}) {
        if (renderer.empty() && !brume::test::kGpuBuilt) continue;  // the GPU renderer's half
        const fs::path out = dir_ / "work" / "fog.png";
        fs::remove(out);
        const CliRun r = brume("render " + quoted(kDefaultScene) + " -o fog.png" + kSmall + renderer);
        ASSERT_EQ(r.exitCode, 0) << renderer << ": " << r.err;
        EXPECT_NE(r.out.find("fog.png"), std::string::npos) << r.out;
        EXPECT_NE(r.err.find("100%"), std::string::npos) << "progress should end at 100%: " << r.err;
        brume::Result<brume::Image> img = brume::readPngLinear(out.string());
        ASSERT_TRUE(img.ok()) << renderer << ": " << img.error().message;
        EXPECT_EQ(img.value().width, 64);
        EXPECT_EQ(img.value().height, 36);
        EXPECT_EQ(listFolder(dir_ / "work"), std::set<std::string>{"fog.png"}) << "no temporary files left";
    }
}

// BRUME_SPV_DIR (gpu/pipeline.cpp, docs/performance.md "How to measure") swaps a shader for profiling:
// every swap is said on stderr, an unchanged copy renders the same image, and a file that is not
// SPIR-V (a partial word, or whole words without SPIR-V's magic number) is one sentence naming it,
// with no image written.
TEST_F(Cli, ReplacedShadersAreSaidAndABrokenOneNamesItsFile) {
    if (!brume::test::kGpuBuilt) GTEST_SKIP() << "the GPU renderer is not built";
    // Set for one render only: a failed assertion must not leave it to the other tests.
    struct SpvDir {
        explicit SpvDir(const fs::path& dir) { ::setenv("BRUME_SPV_DIR", dir.string().c_str(), 1); }
        ~SpvDir() { ::unsetenv("BRUME_SPV_DIR"); }
    };
    const fs::path built = fs::path(BRUME_BINARY_DIR) / "shaders" / "geometry.frag.spv";
    ASSERT_TRUE(fs::exists(built)) << built;
    fs::create_directories(dir_ / "same");
    fs::copy_file(built, dir_ / "same" / "geometry.frag.spv");
    writeText(dir_ / "bad" / "geometry.frag.spv", "abc");
    writeText(dir_ / "words" / "geometry.frag.spv", "abcdefgh");
    const std::string render = "render " + quoted(kDefaultScene) + kSmall;
    const CliRun plain = brume(render + " -o plain.exr");
    ASSERT_EQ(plain.exitCode, 0) << plain.err;
    EXPECT_EQ(plain.err.find("BRUME_SPV_DIR"), std::string::npos) << plain.err;
    CliRun same;
    {
        const SpvDir env(dir_ / "same");
        same = brume(render + " -o same.exr");
    }
    ASSERT_EQ(same.exitCode, 0) << same.err;
    EXPECT_NE(same.err.find("shader geometry.frag replaced by"), std::string::npos) << same.err;
    EXPECT_EQ(readText(dir_ / "work" / "plain.exr"), readText(dir_ / "work" / "same.exr"));
    for (const char* broken : {"bad", "words"}) {
        CliRun bad;
        {
            const SpvDir env(dir_ / broken);
            bad = brume(render + " -o bad.exr");
        }
        EXPECT_NE(bad.exitCode, 0) << broken;
        EXPECT_NE(bad.err.find((dir_ / broken / "geometry.frag.spv").string() + ": not SPIR-V"), std::string::npos)
            << bad.err;
        EXPECT_FALSE(fs::exists(dir_ / "work" / "bad.exr")) << broken;
    }
}

TEST_F(Cli, RenderExrIsFiniteAndNotBlack) {
    for (const std::string renderer : {" --cpu", " --reference"}) {
        const CliRun r = brume("render " + quoted(kDefaultScene) + " -o fog.EXR" + kSmall + renderer);
        ASSERT_EQ(r.exitCode, 0) << renderer << ": " << r.err;
        brume::Result<brume::Image> img = brume::readExr((dir_ / "work" / "fog.EXR").string());
        ASSERT_TRUE(img.ok()) << img.error().message;
        EXPECT_EQ(img.value().width, 64);
        EXPECT_EQ(img.value().height, 36);
        EXPECT_TRUE(brume::allFinite(img.value()));
        double sum = 0.0;
        for (const glm::vec3& p : img.value().pixels) sum += p.x + p.y + p.z;
        EXPECT_GT(sum, 0.0) << renderer << ": the lit default scene rendered black";
    }
}

TEST_F(Cli, WidthAndHeightOverrideTheSceneAndExposureBrightensPng) {
    auto meanOf = [&](const std::string& extra) {
        const CliRun r = brume("render " + quoted(kDefaultScene) + " -o e.png --width 48 --height 20 --quality low" + extra +
                             brume::test::defaultRendererFlag());
        EXPECT_EQ(r.exitCode, 0) << r.err;
        brume::Result<brume::Image> img = brume::readPngLinear((dir_ / "work" / "e.png").string());
        EXPECT_TRUE(img.ok());
        if (!img.ok()) return 0.0;
        EXPECT_EQ(img.value().width, 48);
        EXPECT_EQ(img.value().height, 20);
        double sum = 0.0;
        for (const glm::vec3& p : img.value().pixels) sum += p.x + p.y + p.z;
        return sum;
    };
    EXPECT_GT(meanOf(" --exposure 4"), meanOf(" --exposure 0.25"));
}

TEST_F(Cli, ValidatePrintsOkAndSummary) {
    const CliRun r = brume("validate " + quoted(kDefaultScene));
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.out.rfind(kDefaultScene + ": ok\n", 0), 0u) << r.out;
    EXPECT_EQ(countLines(r.out), 2) << r.out;
    EXPECT_NE(r.out.find("3 lights"), std::string::npos) << r.out;
    EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST_F(Cli, EveryShippedSceneValidates) {
    for (const auto& e : fs::directory_iterator(fs::path(BRUME_SOURCE_DIR) / "assets" / "scenes")) {
        if (e.path().extension() != ".json") continue;
        const CliRun r = brume("validate " + quoted(e.path().string()));
        EXPECT_EQ(r.exitCode, 0) << e.path() << ": " << r.err;
    }
}

// Bad scenes: the message names the file and the JSON path of the problem.
TEST_F(Cli, BadScenesGiveOneLineNamingFileAndPath) {
    struct Case {
        const char* file;
        const char* json;
        const char* pathPart;
    };
    const Case cases[] = {
        {"syntax.json", "{\"camera\": {\"fov_y_deg\": 50,, }}", "syntax.json"},
        {"unknown_key.json", "{\"brume_scene\": 1, \"camera\": {\"fov_y_degs\": 50}}", "camera.fov_y_degs"},
        {"out_of_range.json", "{\"brume_scene\": 1, \"camera\": {\"fov_y_deg\": 500}}", "fov_y_deg"},
        {"bad_light.json", "{\"brume_scene\": 1, \"lights\": [{\"type\": \"point\", \"intensity\": -3}]}", "lights[0].intensity"},
    };
    for (const Case& c : cases) {
        const fs::path scene = dir_ / "scenes" / c.file;
        writeText(scene, c.json);
        for (const std::string command : {"validate ", "render "}) {
            const std::string extra = command == "render " ? " -o out.png" + kSmall : "";
            const CliRun r = brume(command + quoted(scene.string()) + extra);
            SCOPED_TRACE(command + c.file);
            expectOneLineError(r, c.file);
            EXPECT_NE(r.err.find(c.pathPart), std::string::npos) << r.err;
            EXPECT_TRUE(r.out.empty()) << r.out;
        }
    }
    EXPECT_TRUE(listFolder(dir_ / "work").empty()) << "a failed render must leave no file behind";
}

TEST_F(Cli, BadArgumentsGiveOneLine) {
    const std::string scene = quoted(kDefaultScene);
    expectOneLineError(brume("render " + scene + " -o out.png --bogus"), "--bogus");
    expectOneLineError(brume("render " + scene + " -o out.png --width"), "width");
    expectOneLineError(brume("render " + scene), "output");
    expectOneLineError(brume("render " + scene + " -o out.png --width 0"), "--width");
    expectOneLineError(brume("render " + scene + " -o out.png --height 100000"), "--height");
    expectOneLineError(brume("render " + scene + " -o out.png --width abc"), "abc");
    expectOneLineError(brume("render " + scene + " -o out.png --quality extreme"), "extreme");
    expectOneLineError(brume("render " + scene + " -o out.png --exposure -1"), "--exposure");
    expectOneLineError(brume("render " + scene + " -o out.png --frames 0"), "--frames");
    expectOneLineError(brume("render " + scene + " -o out.png --cpu --reference"), "--reference");
    expectOneLineError(brume("render missing_scene.json -o out.png"), "missing_scene.json");
    expectOneLineError(brume("validate missing_scene.json"), "missing_scene.json");
    expectOneLineError(brume("render " + scene + " -o out.jpg"), "out.jpg");
    expectOneLineError(brume("render " + scene + " -o no_such_folder/out.png"), "no_such_folder");
    expectOneLineError(brume("frobnicate"), "frobnicate");
    expectOneLineError(brume(""), "render, validate, settings, bench, tradeoff, info, noise, preset, export or bake");
    expectOneLineError(brume("--threads 2"), "");
    EXPECT_TRUE(listFolder(dir_ / "work").empty()) << "failed commands must leave no file behind";
}

TEST_F(Cli, OutputBelowAFileIsRejected) {
    writeText(dir_ / "work" / "afile", "x");
    expectOneLineError(brume("render " + quoted(kDefaultScene) + " -o afile/out.png" + kSmall), "afile");
    EXPECT_EQ(listFolder(dir_ / "work"), std::set<std::string>{"afile"});
}

TEST_F(Cli, FailedRenderKeepsThePreviousOutput) {
    writeText(dir_ / "work" / "keep.png", "previous");
    writeText(dir_ / "scenes" / "bad.json", "{\"brume_scene\": 1, \"camera\": {\"near\": -1}}");
    expectOneLineError(brume("render " + quoted((dir_ / "scenes" / "bad.json").string()) + " -o keep.png" + kSmall),
                       "bad.json");
    EXPECT_EQ(readText(dir_ / "work" / "keep.png"), "previous");
    EXPECT_EQ(listFolder(dir_ / "work"), std::set<std::string>{"keep.png"});
}

TEST_F(Cli, HelpOfEveryCommandMentionsEveryOption) {
    struct Case {
        std::string command;
        std::vector<std::string> mentions;
    };
    const std::vector<Case> cases = {
        {"--help", {"render", "validate", "settings"}},
        {"render --help",
         {"--output", "-o", "--width", "--height", "--quality", "--frames", "--reference", "--cpu", "--exposure",
          "--threads", "px", "1..16384", "low|medium|high|ultra", "Default:", "Range:"}},
        {"validate --help", {"scene"}},
        {"settings --help", {"--markdown"}},
        {"bench --help", {"--frames", "--warmup", "--cpu", "--orbit", "--json", "--baseline", "--device"}},
    };
    for (const Case& c : cases) {
        const CliRun r = brume(c.command);
        EXPECT_EQ(r.exitCode, 0) << c.command << ": " << r.err;
        for (const std::string& m : c.mentions) {
            EXPECT_NE(r.out.find(m), std::string::npos) << c.command << " should mention " << m << ":\n" << r.out;
        }
    }
}

TEST_F(Cli, SettingsListEverySetting) {
    const CliRun plain = brume("settings");
    const CliRun markdown = brume("settings --markdown");
    ASSERT_EQ(plain.exitCode, 0) << plain.err;
    ASSERT_EQ(markdown.exitCode, 0) << markdown.err;
    for (const brume::Setting* s : brume::settings::kAll) {
        EXPECT_NE(plain.out.find(std::string(s->path)), std::string::npos) << s->path;
        std::string escaped;  // a '|' inside a Markdown table cell is written "\|"
        for (char c : s->path) escaped += c == '|' ? std::string("\\|") : std::string(1, c);
        EXPECT_NE(markdown.out.find(escaped), std::string::npos) << escaped;
    }
    EXPECT_NE(plain.out.find("16384"), std::string::npos) << "ranges are listed";
    EXPECT_NE(markdown.out.find("|"), std::string::npos);
}

// bench --json writes the medians; --baseline reads them back and prints this run's ratios to them.
// A baseline that is missing, not JSON or lacks the medians: one sentence naming it, exit 2, and
// no benchmark run.
TEST_F(Cli, BenchJsonAndBaselineRatios) {
    const std::string bench = "bench " + quoted(kDefaultScene) + kSmall + " --cpu --frames 1 --warmup 0";
    const CliRun first = brume(bench + " --json base.json");
    ASSERT_EQ(first.exitCode, 0) << first.err;
    const std::string json = readText(dir_ / "work" / "base.json");
    for (const char* key : {"\"wall_ms\"", "\"pass_ms\"", "\"renderer\": \"cpu\"", "\"quality\": \"low\""})
        EXPECT_NE(json.find(key), std::string::npos) << key << " missing from " << json;
    const CliRun again = brume(bench + " --baseline base.json");
    ASSERT_EQ(again.exitCode, 0) << again.err;
    EXPECT_NE(again.out.find("this run / baseline"), std::string::npos) << again.out;

    writeText(dir_ / "work" / "broken.json", "{\"wall_ms\": 3");
    writeText(dir_ / "work" / "nopasses.json", "{\"wall_ms\": 3}");
    writeText(dir_ / "work" / "negative.json", "{\"wall_ms\": 3, \"pass_ms\": {\"light\": -1}}");
    expectOneLineError(brume(bench + " --baseline missing.json"), "missing.json");
    expectOneLineError(brume(bench + " --baseline broken.json"), "broken.json: the baseline is not a JSON object");
    expectOneLineError(brume(bench + " --baseline nopasses.json"), "\"pass_ms\"");
    expectOneLineError(brume(bench + " --baseline negative.json"), "\"pass_ms\".light");
    expectOneLineError(brume(bench + " --json nowhere/b.json"), "nowhere");
}

// bench --orbit turns the camera by n x the angle at render n (warm-ups included), as render --orbit does,
// so that the timed frames are in motion. The small box's lit froxels depend on the view: after 2
// warm-ups at 60 deg a render the timed frame looks from 120 deg and lights fewer froxels than the
// static one; at 180 deg it has come round to the start (360 deg) and lights the same ones.
TEST_F(Cli, BenchOrbitTurnsTheCameraEveryRender) {
    const std::string scene = quoted(std::string(BRUME_SOURCE_DIR) + "/bench/scenes/small_box.json");
    const std::string bench = "bench " + scene + " --width 320 --height 180 --quality low --cpu --frames 1 --warmup 2";
    auto litLine = [](const CliRun& r) {
        const size_t at = r.out.find("lit froxels");
        return at == std::string::npos ? std::string("(none)") : r.out.substr(at, r.out.find(',', at) - at);
    };
    const CliRun still = brume(bench);
    const CliRun turned = brume(bench + " --orbit 60 --json orbit.json");
    const CliRun round = brume(bench + " --orbit 180");
    ASSERT_EQ(still.exitCode, 0) << still.err;
    ASSERT_EQ(turned.exitCode, 0) << turned.err;
    ASSERT_EQ(round.exitCode, 0) << round.err;
    EXPECT_NE(litLine(still), "(none)") << still.out;
    EXPECT_NE(litLine(turned), litLine(still)) << turned.out;
    EXPECT_EQ(litLine(round), litLine(still)) << round.out;
    EXPECT_NE(turned.out.find("camera orbiting 60 deg per frame"), std::string::npos) << turned.out;
    EXPECT_EQ(still.out.find("orbiting"), std::string::npos) << still.out;
    EXPECT_NE(readText(dir_ / "work" / "orbit.json").find("\"orbit_deg\": 60"), std::string::npos);
    expectOneLineError(brume(bench + " --orbit 500"), "--orbit 500 is out of range: expected -180..180 deg.");
}

TEST_F(Cli, RelativeScenePathFromAnotherFolder) {
    fs::create_directories(dir_ / "scenes");
    fs::copy_file(kDefaultScene, dir_ / "scenes" / "copy.json", fs::copy_options::overwrite_existing);
    const CliRun v = brume("validate ../scenes/copy.json");
    EXPECT_EQ(v.exitCode, 0) << v.err;
    const std::string flags = kSmall + brume::test::defaultRendererFlag();
    const CliRun r = brume("render ../scenes/copy.json -o ../out/fog.png" + flags, dir_ / "work");
    EXPECT_EQ(r.exitCode, 2) << "the output folder does not exist yet";
    fs::create_directories(dir_ / "out");
    const CliRun r2 = brume("render ../scenes/copy.json -o ../out/fog.png" + flags, dir_ / "work");
    EXPECT_EQ(r2.exitCode, 0) << r2.err;
    EXPECT_TRUE(fs::exists(dir_ / "out" / "fog.png"));
}

}  // namespace

namespace {

class CliGpu : public Cli {
protected:
    void SetUp() override {
        Cli::SetUp();
        BRUME_REQUIRE_GPU_BUILD();
    }
};

// A machine without any Vulkan driver: one sentence and exit 2 (the user can pass --cpu), never a
// crash or a raw VkResult; --cpu still works there. --stats carries per-pass GPU milliseconds.
TEST_F(CliGpu, NoVulkanDeviceGivesOneSentenceAndExitTwo) {
    const std::string env = "VK_ICD_FILENAMES=/nonexistent VK_DRIVER_FILES=/nonexistent ";
    const fs::path work = dir_ / "work";
    const std::string cmd = "cd " + quoted(work.string()) + " && " + env + quoted(BRUME_EXE) + " render " +
                            quoted(kDefaultScene) + " -o fog.png" + kSmall + " >" + quoted((logs_ / "out").string()) +
                            " 2>" + quoted((logs_ / "err").string());
    const int status = std::system(cmd.c_str());
    CliRun noDevice;
    noDevice.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    noDevice.err = readText(logs_ / "err");
    expectOneLineError(noDevice, "Vulkan");
    EXPECT_EQ(noDevice.err.find("VK_ERROR"), std::string::npos) << noDevice.err;
    EXPECT_FALSE(fs::exists(work / "fog.png"));
}

TEST_F(CliGpu, StatsJsonHasEveryPassAndTheFroxelCounts) {
    const CliRun r = brume("render " + quoted(kDefaultScene) + " -o fog.png --stats stats.json" + kSmall);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string stats = readText(dir_ / "work" / "stats.json");
    for (const char* key : {"\"renderer\": \"gpu\"", "\"device\"", "\"wall_ms\"", "\"gpu_pass_ms\"", "\"voxelize\"",
                            "\"light\"", "\"integrate\"", "\"composite\"", "\"froxels\"", "\"lit_froxels\"",
                            "\"skipped_froxels\""}) {
        EXPECT_NE(stats.find(key), std::string::npos) << key << " missing from " << stats;
    }
    const CliRun bad = brume("render " + quoted(kDefaultScene) + " -o fog.png --stats nowhere/stats.json" + kSmall);
    expectOneLineError(bad, "nowhere");
}

}  // namespace

namespace {

// The last frame of the CPU froxel renderer's sequence on the default scene at kSmall's size: a
// static camera, or one turned by `orbit` degrees per frame about its target.
brume::Image cpuSequence(int frames, float orbit) {
    brume::Result<brume::Scene> scene = brume::loadSceneFile(kDefaultScene);
    EXPECT_TRUE(scene.ok());
    brume::RenderRequest r = brume::requestFromScene(scene.value());
    r.width = 64;
    r.height = 36;
    r.quality = brume::Quality::Low;
    brume::FroxelCpuRenderer renderer;
    brume::Image last;
    brume::Scene s = scene.value();
    for (int n = 0; n < frames; ++n) {
        s.camera = brume::orbitCamera(scene.value().camera, orbit * static_cast<float>(n));
        r.history = n == 0 ? brume::HistoryMode::Restart : brume::HistoryMode::Continue;
        last = renderer.render(s, r).image;
    }
    return last;
}

// --frames N writes the N-th frame of the temporal sequence, --orbit moves the camera along it:
// the EXR equals the CPU froxel renderer's own sequence, and differs from a single frame.
TEST_F(Cli, FramesAndOrbitWriteTheLastFrameOfTheSequence) {
    for (const std::string orbit : {"", " --orbit 3"}) {
        const CliRun r = brume("render " + quoted(kDefaultScene) + " -o seq.exr --cpu --frames 6" + orbit + kSmall);
        ASSERT_EQ(r.exitCode, 0) << orbit << ": " << r.err;
        brume::Result<brume::Image> img = brume::readExr((dir_ / "work" / "seq.exr").string());
        ASSERT_TRUE(img.ok()) << img.error().message;
        const brume::Image expected = cpuSequence(6, orbit.empty() ? 0.0f : 3.0f);
        EXPECT_LT(brume::relativeMeanAbsError(img.value(), expected), 1e-6) << orbit;
        // Jittered along depth only (docs/temporal.md): 6 still frames differ from 1 by ~7e-4.
        EXPECT_GT(brume::relativeMeanAbsError(img.value(), cpuSequence(1, 0.0f)), 1e-4) << orbit;
    }
    const CliRun help = brume("render --help");
    EXPECT_NE(help.out.find("--orbit"), std::string::npos) << help.out;
    expectOneLineError(brume("render " + quoted(kDefaultScene) + " -o out.png --orbit 500"), "--orbit");
}

// The GPU renderer follows the same sequence (history kept across its render calls).
TEST_F(CliGpu, FramesAndOrbitMatchTheCpuSequence) {
    const CliRun r = brume("render " + quoted(kDefaultScene) + " -o seq.exr --frames 6 --orbit 3" + kSmall);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    brume::Result<brume::Image> img = brume::readExr((dir_ / "work" / "seq.exr").string());
    ASSERT_TRUE(img.ok()) << img.error().message;
    EXPECT_LT(brume::relativeMeanAbsError(img.value(), cpuSequence(6, 3.0f)), 0.01);
}

}  // namespace

// More lights reach a cluster than it lists: the image is still rendered (unculled there) and
// stderr says how many clusters, the limit and what to do; a scene within the limit gets no warning.
TEST_F(Cli, OverfullLightClustersWarn) {
    auto scene = [](int lights) {
        std::string s = R"({"brume_scene": 1, "camera": {"position": [0, 1.5, 6], "target": [0, 0.5, 0]},
            "volumes": [{"type": "height", "base_height": 0.5, "falloff": 0.5}], "lights": [)";
        for (int i = 0; i < lights; ++i) {
            s += std::string(i ? "," : "") + R"({"type": "point", "intensity": 0.1, "position": [)" +
                 std::to_string(0.1 * i - 3.0) + ", 1, -2]}";
        }
        return s + "]}";
    };
    writeText(dir_ / "work" / "many.json", scene(64));
    writeText(dir_ / "work" / "few.json", scene(4));
    const CliRun many = brume("render many.json -o many.png --cpu" + kSmall);
    ASSERT_EQ(many.exitCode, 0) << many.err;
    EXPECT_NE(many.err.find("warning: many.json: "), std::string::npos) << many.err;
    EXPECT_NE(many.err.find("reached by more than 63 lights"), std::string::npos) << many.err;
    const CliRun few = brume("render few.json -o few.png --cpu" + kSmall);
    ASSERT_EQ(few.exitCode, 0) << few.err;
    EXPECT_EQ(few.err.find("warning"), std::string::npos) << few.err;
}
