// `brume render --sequence` on the GPU renderer (lavapipe, validation on): a range rendered in two
// parts gives the same files as the whole range, bit for bit, across a block boundary where the
// history restarts after its warm-up (core/sequence.h), as tests/test_sequence.cpp checks on the CPU.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "test_support.h"

namespace brume {
namespace {

namespace fs = std::filesystem;
using test::quoted;
using test::readText;

// Temporal on with a short memory (history_weight 0.5: 7 warm-up frames, blocks of 28) and a keyed
// light, so frames differ by jitter and by time.
constexpr const char* kScene = R"({"brume_scene": 1,
  "camera": {"position": [0, 1, 4], "target": [0, 1, 0]},
  "render": {"width": 40, "height": 24, "quality": "low"},
  "temporal": {"enabled": true, "history_weight": 0.5},
  "lights": [{"type": "point", "position": [0.5, 2, 0.5], "intensity": 20,
              "keys": {"intensity": [{"time": 0.5, "value": 20}, {"time": 1.5, "value": 60}]}}],
  "volumes": [{"type": "box", "transform": {"translation": [0, 1, 0], "scale": [3, 2, 3]},
               "medium": {"scattering": [0.3, 0.3, 0.3]}}]})";

struct CliRun {
    int exitCode = -1;
    std::string err;
};

class GpuSequence : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("brume_gpu_sequence_" + std::to_string(getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_ / "whole");
        fs::create_directories(dir_ / "parts");
        std::ofstream(dir_ / "scene.json") << kScene;
    }
    void TearDown() override { fs::remove_all(dir_); }
    CliRun brume(const std::string& args) const {
        const std::string cmd = "cd " + quoted(dir_.string()) + " && BRUME_VALIDATION=1 " + quoted(BRUME_EXE) +
                                " render scene.json " + args + " >out.log 2>err.log";
        const int status = std::system(cmd.c_str());
        return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, readText(dir_ / "err.log")};
    }
    std::string frame(const std::string& folder, int f) const {
        char name[32];
        std::snprintf(name, sizeof name, "f_%04d.exr", f);
        return readText(dir_ / folder / name);
    }
    fs::path dir_;
};

TEST_F(GpuSequence, RangeInTwoPartsEqualsTheWholeBitForBit) {
    for (const char* args : {"--sequence 24-33 -o whole/f_####.exr", "--sequence 24-28 -o parts/f_####.exr",
                             "--sequence 29-33 -o parts/f_####.exr"}) {
        const CliRun r = brume(args);
        ASSERT_EQ(r.exitCode, 0) << args << ": " << r.err;
        EXPECT_EQ(r.err.find("validation"), std::string::npos) << args << ": " << r.err;
    }
    for (int f = 24; f <= 33; ++f) {
        ASSERT_FALSE(frame("whole", f).empty()) << f;
        EXPECT_TRUE(frame("whole", f) == frame("parts", f)) << "frame " << f << " differs between the whole range and its parts";
    }
    EXPECT_FALSE(frame("whole", 25) == frame("whole", 26)) << "frames differ (jitter, keys): equality is not trivial";
}

}  // namespace
}  // namespace brume
