// The editor's Quality panel (app/editor/quality_job.h) and the error heat map (core/tradeoff.h):
// the heat map's numbers and legend range; the panel's measurement, on a worker thread, gives the
// errors `brume tradeoff --json` gives and shares its reference cache; a cancelled reference leaves
// no cache entry; and under Xvfb a scripted session opens the panel, measures, applies a candidate
// and undoes it.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "app/editor/debug_view.h"
#include "app/editor/quality_job.h"
#include "app/tradeoff_measure.h"
#include "core/tradeoff.h"
#include "io/scene_json.h"
#include "test_support.h"

using namespace brume;
namespace fs = std::filesystem;

namespace {

const std::string kDefaultScene = std::string(BRUME_SOURCE_DIR) + "/assets/scenes/default.json";

size_t cacheEntries(const fs::path& dir) { return fs::exists(dir) ? test::fileCount(dir) : 0; }

int shell(const std::string& cmd) {
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

TEST(HeatMap, PerPixelErrorIsRelativeToTheReferenceMeanAndAveragesToTheRelMae) {
    Image ref(8, 4), img(8, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) ref.at(x, y) = glm::vec3(x < 4 ? 1.0f : 3.0f);  // mean |ref| = 2
    img = ref;
    img.at(0, 0) = glm::vec3(1.5f, 1.0f, 1.0f);  // off by 0.5 in one channel: 0.5 / 3 / 2
    img.at(7, 3) = glm::vec3(2.0f);              // off by 1 in every channel: 1 / 2
    const ErrorMap m = pixelErrorMap(img, ref);
    ASSERT_EQ(m.width, 8);
    ASSERT_EQ(m.height, 4);
    EXPECT_NEAR(m.values[0], 0.5 / 3.0 / 2.0, 1e-6);
    EXPECT_NEAR(m.values[3 * 8 + 7], 0.5, 1e-6);
    EXPECT_EQ(m.values[1], 0.0f);
    double mean = 0.0;
    for (float v : m.values) mean += v;
    mean /= static_cast<double>(m.values.size());
    EXPECT_NEAR(mean, relativeMeanAbsError(img, ref), 1e-7) << "the map's mean is the image's relMae";
    EXPECT_THROW(pixelErrorMap(Image(2, 2), ref), std::invalid_argument);
}

TEST(HeatMap, LegendRangeIsARoundNumberAtOrAboveThe99thPercentile) {
    // 1000 pixels: 990 at 3%, ten hot ones at 80%: the legend ends at 5%, not at the hot pixels.
    std::vector<float> v(1000, 0.03f);
    for (int i = 0; i < 10; ++i) v[static_cast<size_t>(i) * 97] = 0.8f;
    EXPECT_FLOAT_EQ(heatMapScale(v), 0.05f);
    EXPECT_FLOAT_EQ(heatMapScale(std::vector<float>(10, 0.01f)), 0.01f);  // exactly a round number
    EXPECT_FLOAT_EQ(heatMapScale(std::vector<float>(10, 0.011f)), 0.02f);
    EXPECT_FLOAT_EQ(heatMapScale(std::vector<float>(10, 0.3f)), 0.5f);
    EXPECT_FLOAT_EQ(heatMapScale(std::vector<float>(10, 7.0f)), 10.0f);
    EXPECT_FLOAT_EQ(heatMapScale(std::vector<float>(10, 0.0f)), 1e-4f);  // a perfect image still has a legend
    EXPECT_FLOAT_EQ(heatMapScale({}), 1e-4f);
    // The ramp: black at 0, brighter all the way up, clamped beyond its ends.
    EXPECT_EQ(heatMapColor(0.0f), glm::vec3(0.0f));
    float last = -1.0f;
    for (int i = 0; i <= 20; ++i) {
        const glm::vec3 c = heatMapColor(static_cast<float>(i) / 20.0f);
        const float luma = 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
        EXPECT_GT(luma, last) << i;
        last = luma;
    }
    EXPECT_EQ(heatMapColor(3.0f), heatMapColor(1.0f));
    EXPECT_EQ(heatMapColor(-1.0f), heatMapColor(0.0f));
}

TEST(QualityPanel, DebugErrorSelectsTheHeatMapAndOtherViewsLeaveIt) {
    editor::DebugViewState s;
    const FroxelSettings froxels{16, 32, 0.5f, 50.0f, 2.0f};
    auto run = [&](const std::string& line) { return editor::runDebugAction(s, editor::parseAction(line).value(), froxels); };
    ASSERT_TRUE(run("debug density 3").ok());
    ASSERT_TRUE(run("debug error").ok());
    EXPECT_TRUE(s.errorMap);
    EXPECT_EQ(s.view, shd::DEBUG_VIEW_FINAL) << "the heat map lies over the final image";
    EXPECT_FALSE(run("debug error 3").ok());
    EXPECT_TRUE(s.errorMap);
    ASSERT_TRUE(run("debug final").ok());
    EXPECT_FALSE(s.errorMap);
}

// The panel's measurement on a 64x36 view equals `brume tradeoff --json` on the same scene: the
// same candidates with the same errors, and the command line finds the panel's cached reference.
TEST(QualityPanel, MeasurementMatchesTheCommandLineAndSharesItsCache) {
    test::TempDir dir("quality_panel", "cli");
    Result<Scene> scene = loadSceneFile(kDefaultScene);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    editor::QualityJobSpec spec;
    spec.scene = scene.value();
    spec.width = 64;
    spec.height = 36;
    spec.plan = measure::parsePlan("low,medium", "1,4").value();
    spec.plan.repeats = 1;
    spec.plan.warmup = 0;
    spec.cacheDir = (dir.path / "cache").string();
    spec.threads = 2;
    spec.heatQuality = Quality::Medium;
    spec.heatFrames = 4;
    editor::QualityJob job;
    job.start(spec, editor::cpuRendererFactory(2));
    job.wait();
    const editor::JobProgress p = job.progress();
    const editor::JobResult r = job.result();
    ASSERT_EQ(p.phase, editor::JobPhase::Done) << r.message;
    EXPECT_FALSE(p.referenceCached);
    EXPECT_EQ(p.candidatesDone, 4u);
    ASSERT_EQ(r.candidates.size(), 4u);
    EXPECT_EQ(cacheEntries(dir.path / "cache"), 1u);

    const fs::path json = dir.path / "t.json";
    const std::string cmd = test::quoted(BRUME_EXE) + " tradeoff " + test::quoted(kDefaultScene) +
                            " --cpu --width 64 --height 36 --threads 2 --repeats 1 --warmup 0 --quality low,medium "
                            "--frames 1,4 --cache " + test::quoted((dir.path / "cache").string()) + " --json " +
                            test::quoted(json.string()) + " > " + test::quoted((dir.path / "out").string()) + " 2> " +
                            test::quoted((dir.path / "err").string());
    ASSERT_EQ(shell(cmd), 0) << test::readText(dir.path / "err");
    EXPECT_NE(test::readText(dir.path / "err").find("reference: cached"), std::string::npos)
        << "the command line reads the reference the panel cached";
    EXPECT_EQ(cacheEntries(dir.path / "cache"), 1u);
    const nlohmann::json j = nlohmann::json::parse(test::readText(json));
    ASSERT_EQ(j["candidates"].size(), r.candidates.size());
    for (size_t i = 0; i < r.candidates.size(); ++i) {
        const nlohmann::json& c = j["candidates"][i];
        const TradeoffCandidate& mine = r.candidates[i];
        EXPECT_EQ(c["label"].get<std::string>(), candidateLabel(mine));
        EXPECT_NEAR(c["rel_mae"].get<double>(), mine.error.relMae, 1e-9) << candidateLabel(mine);
        EXPECT_NEAR(c["p99_tile_error"].get<double>(), mine.error.p99TileError, 1e-9) << candidateLabel(mine);
        EXPECT_GT(mine.error.relMae, 0.0);
        std::printf("%-10s panel %.4f%%  brume tradeoff %.4f%%\n", candidateLabel(mine).c_str(), 100 * mine.error.relMae,
                    100 * c["rel_mae"].get<double>());
    }
    // The heat map: medium after 4 frames against the same reference, so its mean is medium x4's error.
    ASSERT_TRUE(r.hasHeatMap);
    EXPECT_EQ(r.heatMap.width, 64);
    double mean = 0.0;
    for (float v : r.heatMap.values) mean += v;
    mean /= static_cast<double>(r.heatMap.values.size());
    EXPECT_NEAR(mean, r.candidates[3].error.relMae, 1e-6) << "the heat map's mean is medium x4's error";
    EXPECT_GE(r.heatMap.scale, 1e-4f);
}

TEST(QualityPanel, ACancelledReferenceLeavesNoCacheEntry) {
    test::TempDir dir("quality_panel", "cancel");
    Result<Scene> scene = loadSceneFile(kDefaultScene);
    ASSERT_TRUE(scene.ok());
    editor::QualityJobSpec spec;
    spec.scene = scene.value();
    spec.width = 640;  // a reference of many seconds on one thread
    spec.height = 360;
    spec.plan = measure::parsePlan("low", "1").value();
    spec.cacheDir = (dir.path / "cache").string();
    spec.threads = 1;
    editor::QualityJob job;
    job.start(spec, editor::cpuRendererFactory(1));
    EXPECT_TRUE(job.running());
    for (int i = 0; i < 400 && job.progress().referenceFraction <= 0.0f; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    EXPECT_EQ(job.progress().phase, editor::JobPhase::Reference);
    job.cancel();
    job.wait();
    EXPECT_FALSE(job.running());
    EXPECT_EQ(job.progress().phase, editor::JobPhase::Cancelled);
    EXPECT_LT(job.progress().referenceFraction, 1.0f) << "the reference stopped before its end";
    EXPECT_TRUE(job.result().candidates.empty());
    EXPECT_EQ(cacheEntries(dir.path / "cache"), 0u);
}

#ifdef BRUME_EDITOR_EXE
// A scripted session: the panel opened, a measurement on the GPU (its own renderer on the worker
// thread, validation on), a candidate applied to the document and undone, the heat map shown.
TEST(QualityPanel, ScriptedSessionMeasuresAppliesAndUndoes) {
    if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0)
        GTEST_SKIP() << "xvfb-run is missing (apt-get install xvfb xauth): windowed editor tests skipped";
    test::TempDir t("quality_panel", "xvfb");
    ::setenv("XDG_CACHE_HOME", (t.path / "cache").c_str(), 1);
    ::setenv("XDG_CONFIG_HOME", (t.path / "config").c_str(), 1);
    fs::copy_file(kDefaultScene, t.path / "scene.json");
    const std::string applied = (t.path / "applied.json").string(), undone = (t.path / "undone.json").string();
    std::ofstream(t.path / "session.txt") << "tradeoff show\ntradeoff plan low,medium 1,4\ntradeoff run 64 36\n"
                                             "tradeoff wait\ntradeoff apply 1\nsave " + applied +
                                                 "\nundo\nsave " + undone + "\ndebug error\ntradeoff wait\nscreenshot " +
                                                 (t.path / "heat.png").string() + "\nquit\n";
    const fs::path log = t.path / "log.txt";
    const int code = shell("xvfb-run -a -s '-screen 0 640x480x24' " + std::string(BRUME_EDITOR_EXE) + " " +
                           test::quoted((t.path / "scene.json").string()) +
                           " --width 256 --height 144 --quality low --validation --script " +
                           test::quoted((t.path / "session.txt").string()) + " > " + test::quoted(log.string()) + " 2>&1");
    ::unsetenv("XDG_CACHE_HOME");
    ASSERT_EQ(code, 0) << test::readText(log);
    Result<Scene> a = loadSceneFile(applied), u = loadSceneFile(undone), original = loadSceneFile(kDefaultScene);
    ASSERT_TRUE(a.ok() && u.ok() && original.ok());
    // Row 1 of low,medium x 1,4 is low x4.
    EXPECT_EQ(a.value().render.quality, Quality::Low);
    EXPECT_EQ(a.value().render.frames, 4);
    EXPECT_EQ(u.value().render.quality, original.value().render.quality) << "undo restores the render block";
    EXPECT_EQ(u.value().render.frames, original.value().render.frames);
    EXPECT_EQ(cacheEntries(t.path / "cache" / "brume" / "references"), 1u) << "one reference, cached";
    EXPECT_TRUE(fs::exists(t.path / "heat.png"));
}
#endif
