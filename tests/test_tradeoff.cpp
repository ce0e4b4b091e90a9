// The speed/accuracy trade (`brume tradeoff`, core/tradeoff.h): the error measures, the Pareto
// front, the recommendations, the reference cache and bad input, on tiny images (seconds).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>

#include <nlohmann/json.hpp>

#include <sys/wait.h>

#include "core/tradeoff.h"
#include "test_support.h"

using namespace brume;
namespace fs = std::filesystem;

namespace {

Image filled(int w, int h, float v) {
    Image img(w, h);
    for (glm::vec3& p : img.pixels) p = glm::vec3(v);
    return img;
}

TradeoffCandidate cand(double ms, double err) {
    TradeoffCandidate c;
    c.ms = ms;
    c.error.relMae = err;
    return c;
}

}  // namespace

TEST(TradeoffError, MeanAndLocalErrorOfAKnownDifference) {
    const Image ref = filled(64, 64, 1.0f);
    EXPECT_EQ(measureImageError(ref, ref).relMae, 0.0);
    EXPECT_EQ(measureImageError(ref, ref).p99TileError, 0.0);
    // One 16 px tile of 16 is 50% too bright: the mean sees 1/16 of it, the p99 tile all of it.
    Image img = ref;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) img.at(x, y) = glm::vec3(1.5f);
    const ImageError e = measureImageError(img, ref);
    EXPECT_NEAR(e.relMae, 0.5 / 16.0, 1e-9);
    EXPECT_NEAR(e.p99TileError, 0.5, 1e-9);
}

TEST(TradeoffFront, DominatedCandidatesAreOffTheFront) {
    std::vector<TradeoffCandidate> c = {cand(1, 0.10), cand(2, 0.05), cand(3, 0.06), cand(4, 0.01), cand(2, 0.05),
                                        cand(5, 0.01)};
    markParetoFront(c);
    EXPECT_TRUE(c[0].pareto);   // fastest
    EXPECT_TRUE(c[1].pareto);   // a tie with c[4] dominates neither
    EXPECT_FALSE(c[2].pareto);  // slower and worse than c[1]
    EXPECT_TRUE(c[3].pareto);   // most accurate
    EXPECT_TRUE(c[4].pareto);
    EXPECT_FALSE(c[5].pareto);  // as accurate as c[3], slower
    EXPECT_EQ(fastestUnderError(c, 0.055), 1);
    EXPECT_EQ(fastestUnderError(c, 0.001), -1);
    EXPECT_EQ(mostAccurateUnderBudget(c, 3.5), 1);
    EXPECT_EQ(mostAccurateUnderBudget(c, 0.5), -1);
}

TEST(TradeoffGrid, ParsesTileBySlicesAndRejectsTheRest) {
    int tile = 0, slices = 0;
    EXPECT_TRUE(parseGrid("8x96", tile, slices));
    EXPECT_EQ(tile, 8);
    EXPECT_EQ(slices, 96);
    for (const char* bad : {"", "8", "8x", "x96", "8x96x2", "8*96", "0x96", "65x96", "8x0", "8x1025", "-8x96", "8 x96",
                            "99999999x1"})
        EXPECT_FALSE(parseGrid(bad, tile, slices)) << bad;
}

namespace {

struct CliResult {
    int exitCode = -1;
    std::string out, err;
};

class TradeoffCli : public ::testing::Test {
protected:
    test::TempDir dir{"tradeoff", ::testing::UnitTest::GetInstance()->current_test_info()->name()};
    std::string scene = std::string(BRUME_SOURCE_DIR) + "/assets/scenes/default.json";

    std::string command(const std::string& args) const {
        return test::quoted(BRUME_EXE) + " tradeoff " + test::quoted(scene) + " --cache " +
               test::quoted((dir.path / "cache").string()) + " " + args + " >" + test::quoted((dir.path / "out").string()) +
               " 2>" + test::quoted((dir.path / "err").string());
    }
    CliResult run(const std::string& args) const {
        const int status = std::system(command(args).c_str());
        CliResult r;
        r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        r.out = test::readText(dir.path / "out");
        r.err = test::readText(dir.path / "err");
        return r;
    }
    size_t cacheEntries() const {
        return fs::exists(dir.path / "cache") ? test::fileCount(dir.path / "cache") : 0;
    }
};

const std::string kTiny = "--cpu --width 32 --height 18 --threads 2 --repeats 1 --warmup 0";

}  // namespace

TEST_F(TradeoffCli, TableFrontChartJsonAndACachedReference) {
    const std::string outputs = " --json " + test::quoted((dir.path / "t.json").string()) + " --svg " +
                                test::quoted((dir.path / "t.svg").string());
    CliResult r = run(kTiny + " --quality low,medium --frames 1,4 --grid 16x24 --max-error 50 --budget-ms 100000" + outputs);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("rendering the reference"), std::string::npos) << r.err;
    EXPECT_NE(r.out.find("medium x4"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("grid 16x24 x1"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("fastest within 50.00%"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("most accurate within 100000.00 ms"), std::string::npos) << r.out;
    EXPECT_EQ(cacheEntries(), 1u);

    const nlohmann::json j = nlohmann::json::parse(test::readText(dir.path / "t.json"));
    ASSERT_EQ(j["candidates"].size(), 6u);
    int onFront = 0;
    for (const auto& c : j["candidates"]) {
        for (const char* key : {"quality", "frames", "ms", "rel_mae", "p99_tile_error", "pareto"})
            EXPECT_TRUE(c.contains(key)) << key;
        EXPECT_GT(c["rel_mae"].get<double>(), 0.0);
        EXPECT_LT(c["rel_mae"].get<double>(), 1.0);
        EXPECT_GE(c["p99_tile_error"].get<double>(), 0.0);
        onFront += c["pareto"].get<bool>();
    }
    EXPECT_GE(onFront, 1);
    const std::string svg = test::readText(dir.path / "t.svg");
    EXPECT_NE(svg.find("<svg"), std::string::npos);
    EXPECT_NE(svg.find("pareto-front"), std::string::npos);
    EXPECT_NE(svg.find(">low x1<"), std::string::npos);
    EXPECT_NE(svg.find("(log)"), std::string::npos);

    // The second run reads the reference from the cache; another size is another entry.
    r = run(kTiny + " --quality low --frames 1");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("reference: cached"), std::string::npos) << r.err;
    EXPECT_EQ(cacheEntries(), 1u);
}

TEST_F(TradeoffCli, BadInputIsOneSentenceAndExitTwo) {
    struct Case {
        std::string args, expect;
    };
    const std::vector<Case> cases = {
        {"--quality low,superb", "--quality 'superb'"},
        {"--grid 8by96", "--grid '8by96'"},
        {"--grid 0x96", "--grid '0x96'"},
        {"--frames 1,0", "--frames '0'"},
        {"--svg " + test::quoted((dir.path / "missing" / "t.svg").string()), "cannot be written"},
        {"--json " + test::quoted(dir.path.string()), "cannot be written"},
    };
    for (const Case& c : cases) {
        const CliResult r = run(kTiny + " " + c.args);
        EXPECT_EQ(r.exitCode, 2) << c.args;
        EXPECT_NE(r.err.find(c.expect), std::string::npos) << c.args << ": " << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
    EXPECT_EQ(cacheEntries(), 0u) << "bad input is found before the reference is rendered";
}

TEST_F(TradeoffCli, AnInterruptedReferenceLeavesNoCacheEntry) {
    // A reference that takes seconds, interrupted as soon as it has started.
    const std::string cmd = command("--cpu --width 320 --height 180 --threads 1") + " & echo $! > " +
                            test::quoted((dir.path / "pid").string());
    ASSERT_EQ(std::system(cmd.c_str()), 0);
    for (int i = 0; i < 200 && test::readText(dir.path / "err").find("rendering") == std::string::npos; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    const pid_t pid = static_cast<pid_t>(std::stol(test::readText(dir.path / "pid")));
    ASSERT_EQ(::kill(pid, SIGTERM), 0);  // a background job of sh ignores SIGINT
    for (int i = 0; i < 100 && ::kill(pid, 0) == 0; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    EXPECT_NE(::kill(pid, 0), 0) << "still running";
    EXPECT_EQ(cacheEntries(), 0u);
}
