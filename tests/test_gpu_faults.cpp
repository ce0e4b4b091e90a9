// GPU faults by injection (gpu/vk_check.h, docs/reliability.md "GPU faults"): lavapipe never runs
// out of memory or loses the device on demand, so the renderer's allocations and submissions fail
// on purpose, one at a time. Each failure must be one sentence marked as a GPU fault; the renderer
// must stay usable (the next render is the same image as before, the validation layer silent);
// `brume render` prints the sentence and exits 1 without writing the image; the editor says so and
// falls back to the preset below.
#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "test_support.h"

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>

#include "core/image.h"
#include "gpu/vk_check.h"
#include "io/scene_json.h"

namespace fs = std::filesystem;
using namespace brume;

namespace {

const std::string kDefaultScene = std::string(BRUME_SOURCE_DIR) + "/assets/scenes/default.json";

RenderRequest request(int width, int height, Quality q) {
    RenderRequest r;
    r.width = width;
    r.height = height;
    r.quality = q;
    r.threads = 2;
    return r;
}

void expectOneSentence(const std::string& m) {
    EXPECT_EQ(m.rfind("Vulkan could not ", 0), 0u) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    EXPECT_EQ(m.back(), '.') << m;
}

class GpuFaults : public test::ValidatedGpuTest {
protected:
    void TearDown() override {
        gpu::setFaultInjection(gpu::FaultSite::Allocate, 0);
        gpu::setFaultInjection(gpu::FaultSite::Submit, 0);
        ValidatedGpuTest::TearDown();
    }
};

// Every allocation of a resize (screen images, froxel volumes, history, buffers) fails in turn.
TEST_F(GpuFaults, EachAllocationFailingInTurnIsOneSentenceAndTheRendererRecovers) {
    Result<Scene> scene = loadSceneFile(kDefaultScene);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const RenderRequest a = request(96, 54, Quality::Low);
    const RenderRequest b = request(160, 90, Quality::Medium);
    Result<gpu::GpuRender> want = renderer->render(scene.value(), a);
    ASSERT_TRUE(want.ok()) << want.error().message;
    int faults = 0;
    for (uint64_t n = 1; n < 200; ++n) {
        gpu::setFaultInjection(gpu::FaultSite::Allocate, n);
        Result<gpu::GpuRender> big = renderer->render(scene.value(), b);  // reallocates what depends on size
        gpu::setFaultInjection(gpu::FaultSite::Allocate, 0);
        if (big.ok()) break;  // fewer than n allocations: every one has failed once
        ++faults;
        expectOneSentence(big.error().message);
        EXPECT_TRUE(gpu::isGpuFault(big.error())) << big.error().message;
        EXPECT_NE(big.error().message.find("ran out of memory"), std::string::npos) << big.error().message;
        Result<gpu::GpuRender> again = renderer->render(scene.value(), a);
        ASSERT_TRUE(again.ok()) << "after allocation " << n << " failed: " << again.error().message;
        EXPECT_LT(relativeMeanAbsError(again.value().image, want.value().image), 1e-6) << "after allocation " << n;
    }
    std::printf("a resize made %d allocations; each failed once\n", faults);
    EXPECT_GT(faults, 5);
}

TEST_F(GpuFaults, ALostDeviceAtSubmitIsOneSentenceAndTheNextFrameRenders) {
    Result<Scene> scene = loadSceneFile(kDefaultScene);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const RenderRequest a = request(96, 54, Quality::Low);
    Result<gpu::GpuRender> want = renderer->render(scene.value(), a);
    ASSERT_TRUE(want.ok()) << want.error().message;
    gpu::setFaultInjection(gpu::FaultSite::Submit, 1);
    Result<gpu::GpuRender> lost = renderer->render(scene.value(), a);
    ASSERT_FALSE(lost.ok());
    expectOneSentence(lost.error().message);
    EXPECT_TRUE(gpu::isGpuFault(lost.error()));
    EXPECT_NE(lost.error().message.find("device lost"), std::string::npos) << lost.error().message;
    Result<gpu::GpuRender> again = renderer->render(scene.value(), a);
    ASSERT_TRUE(again.ok()) << again.error().message;
    EXPECT_LT(relativeMeanAbsError(again.value().image, want.value().image), 1e-6);
}

TEST(GpuFaultsEndToEnd, BrumeRenderPrintsOneSentenceAndExitsOneWithoutAnImage) {
    test::TempDir dir("gpu_faults", "cli");
    // The first allocation (at start) and one during the frame's resources; the first submission.
    for (const std::string fault : {"oom@1", "oom@12", "lost@1"}) {
        const fs::path out = dir.path / "fog.png";
        const fs::path err = dir.path / "err.txt";
        const std::string cmd = "BRUME_GPU_FAULT=" + fault + " " + test::quoted(BRUME_EXE) + " render " +
                                test::quoted(kDefaultScene) + " -o " + test::quoted(out.string()) +
                                " --width 64 --height 36 --quality low > /dev/null 2> " + test::quoted(err.string());
        const int status = std::system(cmd.c_str());
        const std::string text = test::readText(err);
        EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 1) << fault << ": " << text;
        EXPECT_EQ(text.rfind("error: Vulkan could not ", 0), 0u) << fault << ": " << text;
        EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << fault << ": " << text;
        EXPECT_NE(text.find(fault[0] == 'o' ? "ran out of memory" : "device lost"), std::string::npos) << text;
        EXPECT_FALSE(fs::exists(out)) << fault;
    }
}

}  // namespace
