// The editor's display pass (gpu/display_pass.h) on lavapipe with validation on: its two builds,
// display.comp for a source of the viewport's size and display_scaled.comp for a scaled one, against
// the PNG's display transform computed on the CPU from the same render's image.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "gpu/display_pass.h"
#include "gpu/resources.h"
#include "gpu/pipeline.h"
#include "gpu/vk_check.h"
#include "gpu/vk_owner.h"
#include "gpu_test_support.h"
#include "test_support.h"

namespace brume {
namespace {

// Runs the display pass over the renderer's output into a host-visible buffer and returns its words.
std::vector<uint32_t> runDisplay(const gpu::GpuRenderer& renderer, const gpu::DisplayPass& pass,
                                 const shd::DisplayParams& params) {
    const gpu::Device& device = renderer.device();
    const VkDevice vk = device.vk();
    const VkDeviceSize bytes = static_cast<VkDeviceSize>(params.windowSize.x) * params.windowSize.y * 4;
    Result<gpu::Buffer> window = gpu::createBuffer(device, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                   gpu::Memory::Readback, "display test window");
    EXPECT_TRUE(window.ok()) << window.error().message;
    if (!window) return {};
    VkCommandPoolCreateInfo poolInfo = gpu::vkStruct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    poolInfo.queueFamilyIndex = device.queueFamily();
    VkCommandPool pool = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateCommandPool(vk, &poolInfo, nullptr, &pool), VK_SUCCESS);
    const gpu::CommandPoolOwner poolOwner(vk, pool);
    VkCommandBufferAllocateInfo alloc = gpu::vkStruct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
    alloc.commandPool = pool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    EXPECT_EQ(vkAllocateCommandBuffers(vk, &alloc, &cmd), VK_SUCCESS);
    VkCommandBufferBeginInfo begin = gpu::vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkBeginCommandBuffer(cmd, &begin);
    pass.record(device, cmd, renderer.outputImage(), window.value().buffer.get(), params);
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                       VK_ACCESS_HOST_READ_BIT);
    vkEndCommandBuffer(cmd);
    VkFenceCreateInfo fenceInfo = gpu::vkStruct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
    VkFence fence = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateFence(vk, &fenceInfo, nullptr, &fence), VK_SUCCESS);
    const gpu::FenceOwner fenceOwner(vk, fence);
    VkSubmitInfo submit = gpu::vkStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    EXPECT_EQ(vkQueueSubmit(device.queue(), 1, &submit, fence), VK_SUCCESS);
    EXPECT_EQ(vkWaitForFences(vk, 1, &fence, VK_TRUE, UINT64_MAX), VK_SUCCESS);
    VkMappedMemoryRange range = gpu::vkStruct<VkMappedMemoryRange>(VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE);
    range.memory = window.value().memory.get();
    range.size = VK_WHOLE_SIZE;
    vkInvalidateMappedMemoryRanges(vk, 1, &range);
    const auto* words = static_cast<const uint32_t*>(window.value().mapped);
    return std::vector<uint32_t>(words, words + bytes / 4);
}

// Channel c (0 = the low byte) of a packed pixel.
int channel(uint32_t packed, int c) { return static_cast<int>((packed >> (8 * c)) & 0xFFu); }

TEST(GpuDisplay, ExactAndScaledBuildsShowTheRenderThroughThePngTransform) {
    gpu::GpuOptions options;
    options.validation = true;
    auto created = gpu::GpuRenderer::create(options);
    ASSERT_TRUE(created.ok()) << created.error().message;
    const gpu::GpuRenderer& renderer = *created.value();
    Scene scene = test::sceneWithTestView();
    scene.volumes.push_back(test::boxFog({0.0f, 1.0f, 0.0f}, {4.0f, 2.4f, 3.0f}, 0.2f, 0.4f, 0.2f));
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, -0.2f));
    sun.intensity = 3.0f;
    scene.lights.push_back(sun);
    scene.geometry.push_back(test::groundPlane(glm::vec3(0.5f)));
    RenderRequest request;
    request.width = 40;
    request.height = 22;
    request.quality = Quality::Low;
    auto g = created.value()->render(scene, request);
    ASSERT_TRUE(g.ok()) << g.error().message;
    const Image& image = g.value().image;
    // The same frame again, left on the device as the editor's is (render() leaves its output laid out
    // for the readback copy): a restarted history renders the same image.
    auto onDevice = created.value()->renderOnDevice(scene, request);
    ASSERT_TRUE(onDevice.ok()) << onDevice.error().message;
    Result<gpu::DisplayPass> pass = gpu::DisplayPass::create(renderer.device());
    ASSERT_TRUE(pass.ok()) << pass.error().message;

    // The PNG's byte of a radiance (io/image_io.cpp: displayFromRadiance, round(clamp(v) * 255)).
    auto expected = [](glm::vec3 radiance, int bgra) {
        return shd::packDisplayPixel(shd::displayFromRadiance(radiance, 1.0f), bgra);
    };
    auto radianceAt = [&](int x, int y) {
        x = std::clamp(x, 0, image.width - 1);
        y = std::clamp(y, 0, image.height - 1);
        return image.pixels[static_cast<size_t>(y) * image.width + x];
    };
    // lavapipe's pow and the C++ one may round a value on either side of a byte's edge: one step.
    auto compare = [](uint32_t got, uint32_t want, int& maxDiff, int& differing) {
        int d = 0;
        for (int c = 0; c < 4; ++c) d = std::max(d, std::abs(channel(got, c) - channel(want, c)));
        maxDiff = std::max(maxDiff, d);
        differing += d > 0 ? 1 : 0;
    };

    // Exact texels (display.comp), BGRA order, and a window wider and taller than the view.
    shd::DisplayParams exact{};
    exact.sourceSize = exact.viewSize = glm::ivec2(image.width, image.height);
    exact.windowSize = exact.viewSize + glm::ivec2(3, 2);
    exact.toneMap = 1;
    exact.bgra = 1;
    const std::vector<uint32_t> a = runDisplay(renderer, pass.value(), exact);
    ASSERT_EQ(a.size(), static_cast<size_t>(exact.windowSize.x * exact.windowSize.y));
    int maxDiff = 0, differing = 0, lit = 0;
    const uint32_t background = shd::DISPLAY_BACKGROUND * 0x010101u | (255u << 24u);
    for (int y = 0; y < exact.windowSize.y; ++y)
        for (int x = 0; x < exact.windowSize.x; ++x) {
            const uint32_t got = a[static_cast<size_t>(y) * exact.windowSize.x + x];
            if (x >= image.width || y >= image.height) {
                EXPECT_EQ(got, background) << x << "," << y;
                continue;
            }
            const uint32_t want = expected(radianceAt(x, y), 1);
            compare(got, want, maxDiff, differing);
            lit += channel(want, 0) > 0 ? 1 : 0;
        }
    EXPECT_LE(maxDiff, 1);
    EXPECT_LT(differing, image.width * image.height / 50);
    EXPECT_GT(lit, image.width * image.height / 2);  // not a black image
    std::printf("display.comp vs the PNG's bytes: %d of %d pixels a step apart\n", differing, image.width * image.height);

    // Scaled (display_scaled.comp): the view 2.5x the source, RGBA order; bilinear in radiance with
    // texel centres aligned and the edges clamped, then the transform.
    shd::DisplayParams scaled{};
    scaled.sourceSize = glm::ivec2(image.width, image.height);
    scaled.viewSize = glm::ivec2(image.width * 5 / 2, image.height * 5 / 2);
    scaled.windowSize = scaled.viewSize + glm::ivec2(1, 4);
    scaled.toneMap = 1;
    scaled.bgra = 0;
    const std::vector<uint32_t> b = runDisplay(renderer, pass.value(), scaled);
    ASSERT_EQ(b.size(), static_cast<size_t>(scaled.windowSize.x * scaled.windowSize.y));
    maxDiff = 0;
    differing = 0;
    for (int y = 0; y < scaled.windowSize.y; ++y)
        for (int x = 0; x < scaled.windowSize.x; ++x) {
            const uint32_t got = b[static_cast<size_t>(y) * scaled.windowSize.x + x];
            if (x >= scaled.viewSize.x || y >= scaled.viewSize.y) {
                EXPECT_EQ(got, background) << x << "," << y;
                continue;
            }
            const glm::vec2 p = (glm::vec2(x, y) + 0.5f) * glm::vec2(scaled.sourceSize) / glm::vec2(scaled.viewSize) - 0.5f;
            const glm::ivec2 p0(static_cast<int>(std::floor(p.x)), static_cast<int>(std::floor(p.y)));
            const glm::vec2 w = p - glm::vec2(p0);
            const glm::vec3 top = glm::mix(radianceAt(p0.x, p0.y), radianceAt(p0.x + 1, p0.y), w.x);
            const glm::vec3 bottom = glm::mix(radianceAt(p0.x, p0.y + 1), radianceAt(p0.x + 1, p0.y + 1), w.x);
            compare(got, expected(glm::mix(top, bottom, w.y), 0), maxDiff, differing);
        }
    EXPECT_LE(maxDiff, 1);
    EXPECT_LT(differing, scaled.viewSize.x * scaled.viewSize.y / 50);
    std::printf("display_scaled.comp vs the CPU's bilinear: %d of %d pixels a step apart\n", differing,
                scaled.viewSize.x * scaled.viewSize.y);
    const std::vector<std::string> messages = renderer.validationMessages();
    EXPECT_TRUE(messages.empty()) << messages.size() << " validation messages, first: " << messages.front();
}

}  // namespace
}  // namespace brume
