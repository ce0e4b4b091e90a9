// `brume render --sequence`: frames of the scene time with keyframes, resumable, interruptible, and a
// range rendered in parts equal to the whole, bit for bit (core/sequence.h).
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "core/sequence.h"
#include "io/image_io.h"
#include "test_support.h"

namespace brume {
namespace {

namespace fs = std::filesystem;
using test::quoted;
using test::readText;

// Temporal accumulation on with a short memory (history_weight 0.5: 7 warm-up frames, blocks of 28),
// a box of fog lit by a point light whose intensity is keyed late (frames 0-7 at 24 fps lie before
// the keys, so the history carries; frames past 48 brighten).
constexpr const char* kScene = R"({"brume_scene": 1,
  "camera": {"position": [0, 1, 4], "target": [0, 1, 0]},
  "render": {"width": 40, "height": 24, "quality": "low"},
  "temporal": {"enabled": true, "history_weight": 0.5},
  "lights": [{"type": "point", "position": [0.5, 2, 0.5], "intensity": 20,
              "keys": {"intensity": {"interpolation": "smooth", "keys": [{"time": 2, "value": 20}, {"time": 3, "value": 80}]}}}],
  "volumes": [{"type": "box", "transform": {"translation": [0, 1, 0], "scale": [3, 2, 3]},
               "medium": {"scattering": [0.3, 0.3, 0.3]}}]})";

struct SeqRun {
    int exitCode = -1;
    std::string out;
    std::string err;
};

class Sequence : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("brume_sequence_" + std::to_string(getpid()) + "_" + info->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        std::ofstream(dir_ / "scene.json") << kScene;
    }
    void TearDown() override { fs::remove_all(dir_); }

    SeqRun brume(const std::string& args) const {
        const std::string cmd = "cd " + quoted(dir_.string()) + " && " + quoted(BRUME_EXE) + " render scene.json --cpu --threads 2 " +
                                args + " >out.log 2>err.log";
        const int status = std::system(cmd.c_str());
        return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, readText(dir_ / "out.log"), readText(dir_ / "err.log")};
    }
    std::string frame(const std::string& folder, int f) const {
        char name[32];
        std::snprintf(name, sizeof name, "f_%04d.exr", f);
        return readText(dir_ / folder / name);
    }
    fs::path dir_;
};

TEST(SequencePlan, FrameRangesAndHistoryChains) {
    EXPECT_TRUE(parseFrameRange("0-47"));
    EXPECT_EQ(parseFrameRange("12-12")->first, 12);
    for (const char* bad : {"", "5", "5-", "-5", "7-3", "a-b", "1-2-3", "1 - 2", "-1-4", "0-99999999"})
        EXPECT_FALSE(parseFrameRange(bad)) << bad;
    Temporal t;
    t.history_weight = 0.5f;
    EXPECT_EQ(temporalWarmupFrames(t), 7);  // 0.5^7 = 0.0078 <= 1% < 0.5^6
    EXPECT_EQ(historyChainStart(0, t), -7);
    EXPECT_EQ(historyChainStart(27, t), -7);
    EXPECT_EQ(historyChainStart(28, t), 21);
    t.enabled = false;
    EXPECT_EQ(historyChainStart(28, t), 28);
}

TEST_F(Sequence, RangeInTwoPartsEqualsTheWholeBitForBit) {
    fs::create_directories(dir_ / "whole");
    fs::create_directories(dir_ / "parts");
    // 26-33 crosses the block boundary at 28, where the history restarts after its warm-up.
    ASSERT_EQ(brume("--sequence 0-9 -o whole/f_####.exr").exitCode, 0);
    ASSERT_EQ(brume("--sequence 26-33 -o whole/f_####.exr").exitCode, 0);
    const SeqRun a = brume("--sequence 0-3 -o parts/f_####.exr");
    ASSERT_EQ(a.exitCode, 0) << a.err;
    EXPECT_NE(a.out.find("frame 2/4: wrote parts/f_0001.exr"), std::string::npos) << a.out;
    ASSERT_EQ(brume("--sequence 4-9 -o parts/f_####.exr").exitCode, 0);
    ASSERT_EQ(brume("--sequence 26-29 -o parts/f_####.exr").exitCode, 0);
    ASSERT_EQ(brume("--sequence 30-33 -o parts/f_####.exr").exitCode, 0);
    for (int f : {0, 1, 2, 3, 4, 5, 9, 26, 27, 28, 29, 30, 33}) {
        ASSERT_FALSE(frame("whole", f).empty()) << f;
        EXPECT_TRUE(frame("whole", f) == frame("parts", f)) << "frame " << f << " differs between the whole range and its parts";
    }
    // The history does accumulate: frames of the static scene differ (jitter), so equality is not trivial.
    EXPECT_FALSE(frame("whole", 4) == frame("whole", 5));
}

TEST_F(Sequence, KeyframesMoveWithTheFrames) {
    fs::create_directories(dir_ / "k");
    ASSERT_EQ(brume("--sequence 40-40 --fps 10 -o k/f_####.exr").exitCode, 0);  // t = 4 s, past every key
    const Result<Image> early = readExr((dir_ / "k" / "f_0040.exr").string());
    ASSERT_TRUE(early) << early.error().message;
    fs::create_directories(dir_ / "e");
    ASSERT_EQ(brume("--sequence 0-0 --fps 10 -o e/f_####.exr").exitCode, 0);  // t = 0, before the keys
    const Result<Image> first = readExr((dir_ / "e" / "f_0000.exr").string());
    ASSERT_TRUE(first);
    double before = 0.0, after = 0.0;
    for (size_t i = 0; i < first.value().pixels.size(); ++i) {
        before += first.value().pixels[i].x;
        after += early.value().pixels[i].x;
    }
    EXPECT_GT(after, 2.0 * before);  // intensity 20 -> 80: the in-scattered light grows
}

TEST_F(Sequence, ResumeSkipsFramesOnDiskAndOverwriteRendersThemAgain) {
    fs::create_directories(dir_ / "r");
    ASSERT_EQ(brume("--sequence 0-4 -o r/f_####.exr").exitCode, 0);
    const std::string third = frame("r", 3);
    fs::remove(dir_ / "r" / "f_0003.exr");
    std::ofstream(dir_ / "r" / "f_0001.exr", std::ios::binary) << "marker";
    const SeqRun resumed = brume("--sequence 0-4 -o r/f_####.exr");
    ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
    EXPECT_NE(resumed.out.find("1 written, 4 already on disk"), std::string::npos) << resumed.out;
    EXPECT_EQ(frame("r", 1), "marker");                 // skipped
    EXPECT_TRUE(frame("r", 3) == third);                // rendered alone, from the same history chain
    const SeqRun again = brume("--sequence 0-4 --overwrite -o r/f_####.exr");
    ASSERT_EQ(again.exitCode, 0) << again.err;
    EXPECT_NE(again.out.find("5 written, 0 already on disk"), std::string::npos) << again.out;
    EXPECT_NE(frame("r", 1), "marker");
}

// Ctrl-C stops after the frame being written: every frame on disk reads back whole, no temporary is
// left, the exit code is 130, and a second run completes the sequence.
TEST_F(Sequence, CtrlCLeavesNoHalfWrittenFrame) {
    fs::create_directories(dir_ / "c");
    const std::string cmd = "cd " + quoted(dir_.string()) + " && (" + quoted(BRUME_EXE) +
                            " render scene.json --cpu --threads 1 --width 160 --height 96 --sequence 0-400 -o c/f_####.exr"
                            " >out.log 2>err.log & pid=$!; while [ ! -e c/f_0001.exr ]; do sleep 0.02; done; kill -INT $pid; "
                            "wait $pid; echo $? >rc.txt)";
    ASSERT_EQ(std::system(cmd.c_str()), 0);
    EXPECT_EQ(readText(dir_ / "rc.txt"), "130\n") << readText(dir_ / "err.log");
    EXPECT_NE(readText(dir_ / "err.log").find("interrupted after frame"), std::string::npos) << readText(dir_ / "err.log");
    size_t frames = 0;
    for (const fs::directory_entry& e : fs::directory_iterator(dir_ / "c")) {
        const std::string name = e.path().filename().string();
        EXPECT_EQ(name.rfind("f_", 0), 0u) << "left behind: " << name;
        const Result<Image> img = readExr(e.path().string());
        EXPECT_TRUE(img) << name << ": " << (img ? "" : img.error().message);
        ++frames;
    }
    EXPECT_GE(frames, 2u);
    EXPECT_LT(frames, 401u);
}

// An influencer crossing the box with its wake (docs/scene-format.md, Influencers): the wake is a
// function of the scene time alone, so a frame rendered alone equals the same frame of a sequence, and
// the influencer does change the frame.
constexpr const char* kInfluencerScene = R"({"brume_scene": 1,
  "camera": {"position": [0, 1, 4], "target": [0, 1, 0]},
  "render": {"width": 40, "height": 24, "quality": "low"},
  "temporal": {"enabled": true, "history_weight": 0.5},
  "lights": [{"type": "point", "position": [0.5, 2, 0.5], "intensity": 20}],
  "volumes": [{"type": "box", "transform": {"translation": [0, 1, 0], "scale": [3, 2, 3]},
               "medium": {"scattering": [0.6, 0.6, 0.6]}}],
  "influencers": [{"type": "sphere", "radius": 0.7, "strength": 1, "wake_half_life_s": 0.5,
                   "path": [{"time": 0, "position": [-1.5, 1, 0]}, {"time": 1, "position": [1.5, 1, 0]}]}]})";

// Froxels small enough to see a 0.7 m sphere (at 40x24 low a froxel column is wider than it).
const std::string kInfluencerSize = "--width 160 --height 96 ";

TEST_F(Sequence, AnInfluencerFrameRenderedAloneEqualsItInsideASequence) {
    std::ofstream(dir_ / "scene.json") << kInfluencerScene;
    fs::create_directories(dir_ / "seq");
    fs::create_directories(dir_ / "one");
    const SeqRun whole = brume(kInfluencerSize + "--sequence 0-6 --fps 10 -o seq/f_####.exr");
    ASSERT_EQ(whole.exitCode, 0) << whole.err;
    const SeqRun alone = brume(kInfluencerSize + "--sequence 5-5 --fps 10 -o one/f_####.exr");
    ASSERT_EQ(alone.exitCode, 0) << alone.err;
    ASSERT_FALSE(frame("one", 5).empty());
    EXPECT_TRUE(frame("seq", 5) == frame("one", 5)) << "frame 5 alone differs from frame 5 of 0-6";
    // Without the influencer frame 5 is another image.
    std::string text = kInfluencerScene;
    text = text.substr(0, text.find(",\n  \"influencers\"")) + "}";
    std::ofstream(dir_ / "scene.json", std::ios::trunc) << text;
    fs::create_directories(dir_ / "plain");
    ASSERT_EQ(brume(kInfluencerSize + "--sequence 5-5 --fps 10 -o plain/f_####.exr").exitCode, 0);
    EXPECT_FALSE(frame("plain", 5) == frame("one", 5));
}

TEST_F(Sequence, ABadInfluencerIsOneSentenceNamingItsPathAndExit2) {
    std::string text = kInfluencerScene;
    const std::string second = ", {\"time\": 1, \"position\": [1.5, 1, 0]}";
    text.erase(text.find(second), second.size());  // a path of one point
    std::ofstream(dir_ / "scene.json", std::ios::trunc) << text;
    const SeqRun r = brume("-o bad.png");
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("influencers[0].path: expected an array of at least 2 points"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "bad.png"));
}

TEST_F(Sequence, BadOptionsAreOneSentenceAndExit2) {
    const std::pair<const char*, const char*> cases[] = {
        {"--sequence 5-2 -o f_####.png", "--sequence '5-2' is not a frame range A-B"},
        {"--sequence 12 -o f_####.png", "--sequence '12' is not a frame range A-B"},
        {"--sequence 0-3 -o f.png", "--sequence needs a run of # in the output's file name"},
        {"--sequence 0-3 --time 2 -o f_####.png", "--time cannot be combined with --sequence"},
        {"--overwrite -o f.png", "--overwrite only applies to --sequence"},
    };
    for (const auto& [args, message] : cases) {
        const SeqRun r = brume(args);
        EXPECT_EQ(r.exitCode, 2) << args << ": " << r.err;
        EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_NE(r.err.find(message), std::string::npos) << args << ": " << r.err;
    }
}

}  // namespace
}  // namespace brume
