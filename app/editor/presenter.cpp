#include "presenter.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <utility>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

#include "gpu/display_pass.h"
#include "present_path.h"
#include "gpu/resources.h"
#include "gpu/vk_check.h"
#include "gpu/vk_owner.h"

namespace brume::editor {

using gpu::vkStruct;

namespace {

double nowMs() {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// ImGui's backend reports Vulkan failures through a C callback; the next present() turns the
// latest one into an Error.
VkResult gImGuiResult = VK_SUCCESS;
void onImGuiVkResult(VkResult r) {
    if (r != VK_SUCCESS) gImGuiResult = r;
}

}  // namespace

Result<gpu::PresentTarget> windowPresentTarget(GLFWwindow* window) {
    uint32_t n = 0;
    const char** required = glfwGetRequiredInstanceExtensions(&n);
    if (!required) return Error{"This display has no Vulkan presentation support (GLFW found no Vulkan surface extensions)."};
    gpu::PresentTarget t;
    t.instanceExtensions.assign(required, required + n);
    t.createSurface = [window](VkInstance instance, VkSurfaceKHR* surface) {
        return glfwCreateWindowSurface(instance, window, nullptr, surface);
    };
    return t;
}

// Members die in reverse order, all before the device (which outlives the presenter).
struct Presenter::State {
    const gpu::Device& device;
    GLFWwindow* window = nullptr;
    VkSurfaceFormatKHR format{};
    bool bgra = false;  // B8G8R8A8 swapchain
    gpu::RenderPassOwner renderPass;
    gpu::SwapchainOwner swapchain;
    VkExtent2D extent{};
    uint32_t minImages = 2;
    std::vector<VkImage> images;  // owned by the swapchain
    std::vector<gpu::ImageViewOwner> views;
    std::vector<gpu::FramebufferOwner> framebuffers;
    gpu::CommandPoolOwner pool;
    VkCommandBuffer cmd = VK_NULL_HANDLE;  // freed with the pool
    gpu::FenceOwner fence;
    gpu::SemaphoreOwner acquired, rendered;
    gpu::DescriptorPoolOwner descriptorPool;
    gpu::DisplayPass display;
    gpu::Buffer windowPixels;  // the display pass's output, copied into the swapchain image
    // Coarse frames (PresentPath::Upscale): the display pass's bytes at the source's size, in an
    // image of the window's format that a linear blit scales to the view.
    bool canBlit = false;
    gpu::Buffer sourcePixels;
    gpu::GpuImage sourceDisplay;
    gpu::Buffer readback;      // screenshots
    bool imguiReady = false;
    gpu::PassTimer timer;                    // the device's parts of a window frame (--bench)
    std::vector<gpu::PassTiming> hostParts;  // the host's parts of the last present()
    bool measureParts = false;
    // What the display pass's output (windowPixels, or sourceDisplay for Upscale) holds, so that a
    // frame with the same source skips the pass.
    struct Shown {
        VkImageView view = VK_NULL_HANDLE;
        glm::ivec2 sourceSize{0}, viewSize{0}, window{0};
        uint64_t generation = 0;
        PresentPath path = PresentPath::Background;
        bool operator==(const Shown&) const = default;
    };
    std::optional<Shown> shown;

    State(const gpu::Device& d, GLFWwindow* w) : device(d), window(w) {}
    ~State();
    Result<void> chooseFormat();
    Result<void> createRenderPass();
    Result<void> createSwapchain();
    Result<void> createCommands();
    Result<void> initImGui();
    Result<void> warmUpscale();
    // Ends `cmd`, submits it alone and waits for the queue (one-off work at start); what: what it does,
    // for the error ("upload the UI font").
    Result<void> submitOnce(const std::string& what);
    Result<void> ensureSourceDisplay(glm::ivec2 size);
    Result<void> ensureBuffer(gpu::Buffer& b, VkDeviceSize size, VkBufferUsageFlags usage, gpu::Memory memory,
                              const char* name);
    void record(uint32_t image, const gpu::OutputImage& source, PresentPath path, glm::ivec2 viewSize,
                uint64_t generation, ImDrawData* ui, bool capture);
};

Result<void> Presenter::State::chooseFormat() {
    uint32_t fn = 0;
    vkGetPhysicalDeviceSurfaceFormatsKHR(device.physical(), device.surface(), &fn, nullptr);
    std::vector<VkSurfaceFormatKHR> formats(fn);
    vkGetPhysicalDeviceSurfaceFormatsKHR(device.physical(), device.surface(), &fn, formats.data());
    if (formats.empty()) return Error{"The window surface offers no pixel formats."};
    // UNORM, not SRGB: the display pass writes display-encoded bytes (the PNG's bytes).
    format = formats[0];
    for (const VkSurfaceFormatKHR& f : formats)
        if (f.format == VK_FORMAT_B8G8R8A8_UNORM || f.format == VK_FORMAT_R8G8B8A8_UNORM) format = f;
    if (format.format != VK_FORMAT_B8G8R8A8_UNORM && format.format != VK_FORMAT_R8G8B8A8_UNORM)
        return Error{"The window surface offers no 8-bit UNORM RGBA format, which the editor needs."};
    bgra = format.format == VK_FORMAT_B8G8R8A8_UNORM;
    canBlit = device.supportsFormat(format.format, VK_FORMAT_FEATURE_BLIT_SRC_BIT | VK_FORMAT_FEATURE_BLIT_DST_BIT |
                                                       VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT);
    return {};
}

Result<void> Presenter::State::createRenderPass() {
    // The viewport pixels are copied in first (transfer), so the pass loads them and ImGui draws over.
    VkAttachmentDescription color{};
    color.format = format.format;
    color.samples = VK_SAMPLE_COUNT_1_BIT;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    color.initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    color.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub{};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub.colorAttachmentCount = 1;
    sub.pColorAttachments = &ref;
    VkSubpassDependency deps[2]{};
    deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
    deps[0].dstSubpass = 0;
    deps[0].srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    deps[0].srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    deps[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    deps[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    // Out to the screenshot copy (and presentation, which needs no access).
    deps[1].srcSubpass = 0;
    deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
    deps[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    deps[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    deps[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    deps[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    VkRenderPassCreateInfo info = vkStruct<VkRenderPassCreateInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO);
    info.attachmentCount = 1;
    info.pAttachments = &color;
    info.subpassCount = 1;
    info.pSubpasses = &sub;
    info.dependencyCount = 2;
    info.pDependencies = deps;
    VkRenderPass rp = VK_NULL_HANDLE;
    BRUME_VK(vkCreateRenderPass(device.vk(), &info, nullptr, &rp), "create the window's render pass");
    renderPass = gpu::RenderPassOwner(device.vk(), rp);
    return {};
}

Result<void> Presenter::State::createSwapchain() {
    VkSurfaceCapabilitiesKHR caps;
    BRUME_VK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(device.physical(), device.surface(), &caps),
             "query the window surface");
    const VkImageUsageFlags usage =
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    if ((caps.supportedUsageFlags & usage) != usage)
        return Error{"The window surface cannot be copied to and from, which the editor needs."};
    int w = 0, h = 0;
    glfwGetFramebufferSize(window, &w, &h);
    extent = caps.currentExtent;
    if (extent.width == 0xFFFFFFFFu) extent = {static_cast<uint32_t>(w), static_cast<uint32_t>(h)};
    extent.width = std::clamp(extent.width, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent.height = std::clamp(extent.height, caps.minImageExtent.height, caps.maxImageExtent.height);
    minImages = std::max(2u, caps.minImageCount);
    if (caps.maxImageCount) minImages = std::min(minImages, caps.maxImageCount);
    VkSwapchainCreateInfoKHR info = vkStruct<VkSwapchainCreateInfoKHR>(VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR);
    info.surface = device.surface();
    info.minImageCount = minImages;
    info.imageFormat = format.format;
    info.imageColorSpace = format.colorSpace;
    info.imageExtent = extent;
    info.imageArrayLayers = 1;
    info.imageUsage = usage;
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = caps.currentTransform;
    info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    info.presentMode = VK_PRESENT_MODE_FIFO_KHR;  // always supported
    info.clipped = VK_TRUE;
    info.oldSwapchain = swapchain.get();
    VkSwapchainKHR next = VK_NULL_HANDLE;
    BRUME_VK(vkCreateSwapchainKHR(device.vk(), &info, nullptr, &next), "create the window's swapchain");
    framebuffers.clear();
    views.clear();
    swapchain = gpu::SwapchainOwner(device.vk(), next);
    uint32_t n = 0;
    BRUME_VK(vkGetSwapchainImagesKHR(device.vk(), next, &n, nullptr), "list the swapchain images");
    images.resize(n);
    BRUME_VK(vkGetSwapchainImagesKHR(device.vk(), next, &n, images.data()), "list the swapchain images");
    for (VkImage image : images) {
        VkImageViewCreateInfo v = vkStruct<VkImageViewCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO);
        v.image = image;
        v.viewType = VK_IMAGE_VIEW_TYPE_2D;
        v.format = format.format;
        v.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkImageView view = VK_NULL_HANDLE;
        BRUME_VK(vkCreateImageView(device.vk(), &v, nullptr, &view), "create a swapchain image view");
        views.emplace_back(device.vk(), view);
        VkFramebufferCreateInfo f = vkStruct<VkFramebufferCreateInfo>(VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO);
        f.renderPass = renderPass.get();
        f.attachmentCount = 1;
        f.pAttachments = &view;
        f.width = extent.width;
        f.height = extent.height;
        f.layers = 1;
        VkFramebuffer fb = VK_NULL_HANDLE;
        BRUME_VK(vkCreateFramebuffer(device.vk(), &f, nullptr, &fb), "create a framebuffer");
        framebuffers.emplace_back(device.vk(), fb);
    }
    return {};
}

Result<void> Presenter::State::createCommands() {
    VkCommandPoolCreateInfo p = vkStruct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    p.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    p.queueFamilyIndex = device.queueFamily();
    VkCommandPool cp = VK_NULL_HANDLE;
    BRUME_VK(vkCreateCommandPool(device.vk(), &p, nullptr, &cp), "create the window's command pool");
    pool = gpu::CommandPoolOwner(device.vk(), cp);
    VkCommandBufferAllocateInfo a = vkStruct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
    a.commandPool = cp;
    a.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    a.commandBufferCount = 1;
    BRUME_VK(vkAllocateCommandBuffers(device.vk(), &a, &cmd), "allocate the window's command buffer");
    device.name(cmd, VK_OBJECT_TYPE_COMMAND_BUFFER, "window frame");
    VkFenceCreateInfo f = vkStruct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
    f.flags = VK_FENCE_CREATE_SIGNALED_BIT;
    VkFence fh = VK_NULL_HANDLE;
    BRUME_VK(vkCreateFence(device.vk(), &f, nullptr, &fh), "create a fence");
    fence = gpu::FenceOwner(device.vk(), fh);
    VkSemaphoreCreateInfo s = vkStruct<VkSemaphoreCreateInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO);
    for (gpu::SemaphoreOwner* owner : {&acquired, &rendered}) {
        VkSemaphore sem = VK_NULL_HANDLE;
        BRUME_VK(vkCreateSemaphore(device.vk(), &s, nullptr, &sem), "create a semaphore");
        *owner = gpu::SemaphoreOwner(device.vk(), sem);
    }
    Result<gpu::PassTimer> t = gpu::PassTimer::create(device, 4);
    if (!t) return t.error();
    timer = std::move(t.value());
    Result<gpu::DisplayPass> d = gpu::DisplayPass::create(device);
    if (!d) return d.error();
    display = std::move(d.value());
    return {};
}

Result<void> Presenter::State::initImGui() {
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16};
    VkDescriptorPoolCreateInfo d = vkStruct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
    d.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    d.maxSets = 16;
    d.poolSizeCount = 1;
    d.pPoolSizes = &size;
    VkDescriptorPool dp = VK_NULL_HANDLE;
    BRUME_VK(vkCreateDescriptorPool(device.vk(), &d, nullptr, &dp), "create the UI's descriptor pool");
    descriptorPool = gpu::DescriptorPoolOwner(device.vk(), dp);
    ImGui_ImplVulkan_InitInfo info{};
    info.Instance = device.instance();
    info.PhysicalDevice = device.physical();
    info.Device = device.vk();
    info.QueueFamily = device.queueFamily();
    info.Queue = device.queue();
    info.DescriptorPool = dp;
    info.MinImageCount = minImages;
    info.ImageCount = static_cast<uint32_t>(images.size());
    info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    info.CheckVkResultFn = onImGuiVkResult;
    if (!ImGui_ImplVulkan_Init(&info, renderPass.get())) return Error{"The UI could not start its Vulkan renderer."};
    imguiReady = true;
    // The font atlas goes up once, on its own submission.
    VkCommandBufferBeginInfo begin = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    BRUME_VK(vkBeginCommandBuffer(cmd, &begin), "record the font upload");
    ImGui_ImplVulkan_CreateFontsTexture(cmd);
    BRUME_TRY(submitOnce("upload the UI font"));
    ImGui_ImplVulkan_DestroyFontUploadObjects();
    return {};
}

Result<void> Presenter::State::submitOnce(const std::string& what) {
    BRUME_VK(vkEndCommandBuffer(cmd), "record the commands to " + what);
    VkSubmitInfo submit = vkStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    BRUME_VK(vkQueueSubmit(device.queue(), 1, &submit, VK_NULL_HANDLE), what);
    BRUME_VK(vkQueueWaitIdle(device.queue()), what);
    return {};
}

Result<void> Presenter::State::ensureBuffer(gpu::Buffer& b, VkDeviceSize size, VkBufferUsageFlags usage,
                                            gpu::Memory memory, const char* name) {
    if (b.buffer && b.size >= size) return {};
    b = gpu::Buffer{};
    Result<gpu::Buffer> nb = gpu::createBuffer(device, size, usage, memory, name);
    if (!nb) return nb.error();
    b = std::move(nb.value());
    return {};
}

Result<void> Presenter::State::ensureSourceDisplay(glm::ivec2 size) {
    const VkExtent3D extent{static_cast<uint32_t>(size.x), static_cast<uint32_t>(size.y), 1};
    if (sourceDisplay.image && sourceDisplay.extent.width == extent.width && sourceDisplay.extent.height == extent.height)
        return {};
    sourceDisplay = gpu::GpuImage{};
    Result<gpu::GpuImage> img = gpu::createImage(device, extent, false, format.format,
                                                 // SAMPLED: createImage makes a view, which needs a view usage.
                                                 VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                                     VK_IMAGE_USAGE_SAMPLED_BIT,
                                                 "coarse display image");
    if (!img) return img.error();
    sourceDisplay = std::move(img.value());
    return ensureBuffer(sourcePixels, static_cast<VkDeviceSize>(size.x) * size.y * 4,
                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, gpu::Memory::DeviceLocal,
                        "coarse display pixels");
}

Presenter::State::~State() {
    vkDeviceWaitIdle(device.vk());
    if (imguiReady) ImGui_ImplVulkan_Shutdown();
}

Result<std::unique_ptr<Presenter>> Presenter::create(GLFWwindow* window, const gpu::Device& device) {
    if (!device.surface()) return Error{"The editor's Vulkan device was created without the window's surface."};
    auto s = std::make_unique<State>(device, window);
    BRUME_TRY(s->chooseFormat());
    BRUME_TRY(s->createRenderPass());
    BRUME_TRY(s->createSwapchain());
    BRUME_TRY(s->createCommands());
    BRUME_TRY(s->initImGui());
    BRUME_TRY(s->warmUpscale());
    return std::unique_ptr<Presenter>(new Presenter(std::move(s)));
}

Presenter::Presenter(std::unique_ptr<State> s) : s_(std::move(s)) {}
Presenter::~Presenter() = default;

GLFWwindow* Presenter::window() const { return s_->window; }

void Presenter::newFrame() { ImGui_ImplVulkan_NewFrame(); }

void Presenter::measureParts(bool on) { s_->measureParts = on; }

Result<std::vector<gpu::PassTiming>> Presenter::lastParts() {
    Result<std::vector<gpu::PassTiming>> gpuParts = s_->timer.read();
    if (!gpuParts) return gpuParts.error();
    std::vector<gpu::PassTiming> out;
    for (gpu::PassTiming& p : gpuParts.value()) out.push_back({"present: " + p.name + " (gpu)", p.gpuMs});
    for (const gpu::PassTiming& p : s_->hostParts) out.push_back({"present: " + p.name + " (cpu)", p.gpuMs});
    return out;
}

Result<void> Presenter::waitForFrame() {
    const VkFence fence = s_->fence.get();
    BRUME_VK(vkWaitForFences(s_->device.vk(), 1, &fence, VK_TRUE, UINT64_MAX), "wait for the previous window frame");
    return {};
}

namespace {

// The coarse frame's image (srcSize, TRANSFER_SRC) scaled over the top-left dstSize of a window
// image (TRANSFER_DST), linear: the Upscale path, and its warm-up at start (warmUpscale), which must
// run the same kind of blit for lavapipe to compile the shader the path uses.
void recordUpscale(VkCommandBuffer cmd, VkImage src, glm::ivec2 srcSize, VkImage dst, glm::ivec2 dstSize) {
    VkImageBlit blit{};
    blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.srcOffsets[1] = {srcSize.x, srcSize.y, 1};
    blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.dstOffsets[1] = {dstSize.x, dstSize.y, 1};
    vkCmdBlitImage(cmd, src, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit,
                   VK_FILTER_LINEAR);
}

VkImageMemoryBarrier imageBarrier(VkImage image, VkImageLayout from, VkImageLayout to, VkAccessFlags src, VkAccessFlags dst) {
    VkImageMemoryBarrier b = vkStruct<VkImageMemoryBarrier>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER);
    b.oldLayout = from;
    b.newLayout = to;
    b.srcAccessMask = src;
    b.dstAccessMask = dst;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    return b;
}

}  // namespace

// Lavapipe compiles the shader of a blit the first time it runs one with those formats, filter and
// kind of source (its sampler's variant knows whether the width and height are powers of two): 40-60
// ms on the first coarse frame of a session (its "present: upscale"), against ~4 after. One linear
// blit of a tiny 3x3 image (not a power of two, as a coarse image rarely is) of the coarse image's
// format over a window image, at start, pays it before anyone drags.
Result<void> Presenter::State::warmUpscale() {
    if (!canBlit) return {};  // the Upscale path is never taken (PresentPath)
    Result<gpu::GpuImage> small = gpu::createImage(device, VkExtent3D{3, 3, 1}, false, format.format,
                                                   VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                                       VK_IMAGE_USAGE_SAMPLED_BIT,
                                                   "upscale warm-up source");
    if (!small) return small.error();
    // Into a window image (it is written whole before it is first shown), at the window's size.
    const VkImage src = small.value().image.get(), dst = images.front();
    VkCommandBufferBeginInfo begin = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    BRUME_VK(vkBeginCommandBuffer(cmd, &begin), "record the upscale warm-up");
    const std::array<VkImageMemoryBarrier, 2> toWrite{
        imageBarrier(src, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0, VK_ACCESS_TRANSFER_WRITE_BIT),
        imageBarrier(dst, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0, VK_ACCESS_TRANSFER_WRITE_BIT)};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr,
                         static_cast<uint32_t>(toWrite.size()), toWrite.data());
    const VkClearColorValue black{{0.0f, 0.0f, 0.0f, 1.0f}};
    const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cmd, src, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &black, 1, &all);
    const VkImageMemoryBarrier toRead = imageBarrier(src, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                                     VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT,
                                                     VK_ACCESS_TRANSFER_READ_BIT);
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1,
                         &toRead);
    recordUpscale(cmd, src, glm::ivec2(3), dst, glm::ivec2(extent.width, extent.height));
    return submitOnce("run the upscale warm-up");
}

// Records: the renderer's output -> window pixels (display pass, or the background colour before
// any render) -> window image (transfer), or for a coarse frame (PresentPath::Upscale) the output ->
// display bytes at its own size -> small image -> linear blit into the window image; then ImGui
// over it (render pass), and for a capture, window image -> readback buffer.
void Presenter::State::record(uint32_t index, const gpu::OutputImage& source, PresentPath path, glm::ivec2 viewSize,
                              uint64_t generation, ImDrawData* ui, bool capture) {
    const VkImage image = images[index];
    VkCommandBufferBeginInfo begin = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkBeginCommandBuffer(cmd, &begin);
    // The parts' timestamps only while measuring (--bench reads them through lastParts): otherwise
    // they are queries and labels in every window frame that nothing reads.
    auto startPart = [&](const char* name) {
        if (measureParts) timer.begin(cmd, name);
    };
    auto endPart = [&] {
        if (measureParts) timer.end(cmd);
    };
    if (measureParts) timer.reset(cmd);
    startPart("display");
    const glm::ivec2 window(static_cast<int>(extent.width), static_cast<int>(extent.height));
    // The previous frame's copies read the pixel buffers; this frame rewrites them.
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0);
    shd::DisplayParams p{};
    p.toneMap = source.displayValues ? 0 : 1;
    p.bgra = bgra ? 1 : 0;
    const Shown now{source.view, source.size, viewSize, window, generation, path};
    const bool reuse = path != PresentPath::Background && shown == now;
    shown = now;
    if (reuse) {
        // The pixel buffer (Window) or the small image (Upscale) still holds this source's bytes.
    } else if (path == PresentPath::Window) {
        p.sourceSize = source.size;
        p.viewSize = viewSize;
        p.windowSize = window;
        display.record(device, cmd, source, windowPixels.buffer.get(), p);
    } else if (path == PresentPath::Upscale) {
        // Tone mapped at the source's size (exact texels), then its bytes into the small image.
        p.sourceSize = p.viewSize = p.windowSize = source.size;
        display.record(device, cmd, source, sourcePixels.buffer.get(), p);
        VkImageMemoryBarrier toFill = imageBarrier(sourceDisplay.image.get(), VK_IMAGE_LAYOUT_UNDEFINED,
                                                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0, VK_ACCESS_TRANSFER_WRITE_BIT);
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1, &toFill);
        VkBufferImageCopy small{};
        small.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        small.imageExtent = sourceDisplay.extent;
        vkCmdCopyBufferToImage(cmd, sourcePixels.buffer.get(), sourceDisplay.image.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               1, &small);
        VkImageMemoryBarrier toBlit = imageBarrier(sourceDisplay.image.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                                   VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT,
                                                   VK_ACCESS_TRANSFER_READ_BIT);
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1, &toBlit);
    } else {
        const uint32_t grey = shd::DISPLAY_BACKGROUND * 0x010101u | (255u << 24u);
        vkCmdFillBuffer(cmd, windowPixels.buffer.get(), 0, VK_WHOLE_SIZE, grey);
        gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                           VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    }
    endPart();
    startPart(path == PresentPath::Upscale ? "upscale" : "copy");
    VkImageMemoryBarrier toCopy = imageBarrier(image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                                               VK_ACCESS_TRANSFER_WRITE_BIT);
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1, &toCopy);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {extent.width, extent.height, 1};
    if (path == PresentPath::Upscale) {
        const glm::ivec2 view = glm::min(viewSize, window);
        if (view != window) {  // the window past the view (a frame after a resize) is the background
            const float grey = static_cast<float>(shd::DISPLAY_BACKGROUND) / 255.0f;
            const VkClearColorValue clear{{grey, grey, grey, 1.0f}};
            const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
            vkCmdClearColorImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &clear, 1, &all);
            gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                               VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
        }
        recordUpscale(cmd, sourceDisplay.image.get(), source.size, image, view);
    } else {
        vkCmdCopyBufferToImage(cmd, windowPixels.buffer.get(), image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    }

    endPart();
    startPart("ui");
    VkRenderPassBeginInfo rp = vkStruct<VkRenderPassBeginInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO);
    rp.renderPass = renderPass.get();
    rp.framebuffer = framebuffers[index].get();
    rp.renderArea.extent = extent;
    vkCmdBeginRenderPass(cmd, &rp, VK_SUBPASS_CONTENTS_INLINE);
    if (ui) ImGui_ImplVulkan_RenderDrawData(ui, cmd);
    vkCmdEndRenderPass(cmd);
    endPart();

    if (capture) {
        VkImageMemoryBarrier toRead = imageBarrier(image, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                                   0, VK_ACCESS_TRANSFER_READ_BIT);
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1, &toRead);
        vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.buffer.get(), 1, &region);
        VkImageMemoryBarrier back = imageBarrier(image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                                                 VK_ACCESS_TRANSFER_READ_BIT, 0);
        VkBufferMemoryBarrier host = vkStruct<VkBufferMemoryBarrier>(VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER);
        host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        host.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        host.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        host.buffer = readback.buffer.get();
        host.size = VK_WHOLE_SIZE;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT,
                             0, 0, nullptr, 1, &host, 1, &back);
    }
    vkEndCommandBuffer(cmd);
}

Result<void> Presenter::present(const gpu::OutputImage& source, glm::ivec2 viewSize, uint64_t generation, ImDrawData* ui,
                                Rgba8* capture) {
    State& s = *s_;
    const VkDevice device = s.device.vk();
    const VkFence fence = s.fence.get();
    BRUME_VK(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), "wait for the previous window frame");
    int w = 0, h = 0;
    glfwGetFramebufferSize(s.window, &w, &h);
    if (w == 0 || h == 0) return {};  // minimized
    if (static_cast<uint32_t>(w) != s.extent.width || static_cast<uint32_t>(h) != s.extent.height) {
        BRUME_VK(vkDeviceWaitIdle(device), "wait for the window before resizing");
        BRUME_TRY(s.createSwapchain());
    }
    s.hostParts.clear();
    double t0 = nowMs();
    auto part = [&s, &t0](const char* name) {
        const double t = nowMs();
        s.hostParts.push_back({name, t - t0});
        t0 = t;
    };
    uint32_t index = 0;
    const VkSemaphore acquired = s.acquired.get(), rendered = s.rendered.get();
    // A lost device here (or at the present below) is an Error that isDeviceLost: the editor's loop
    // recreates the device and this presenter (app/editor/main.cpp). Tests inject it (vk_check.h).
    VkResult r = gpu::injectedFault(gpu::FaultSite::Acquire);
    if (r == VK_SUCCESS) r = vkAcquireNextImageKHR(device, s.swapchain.get(), UINT64_MAX, acquired, VK_NULL_HANDLE, &index);
    if (r == VK_ERROR_OUT_OF_DATE_KHR) {
        BRUME_VK(vkDeviceWaitIdle(device), "wait for the window before resizing");
        return s.createSwapchain();  // the next frame draws
    }
    if (r != VK_SUBOPTIMAL_KHR) BRUME_VK(r, "get the next window image");
    part("acquire");
    BRUME_VK(vkResetFences(device, 1, &fence), "reset the window fence");
    const VkDeviceSize bytes = static_cast<VkDeviceSize>(s.extent.width) * s.extent.height * 4;
    BRUME_TRY(s.ensureBuffer(s.windowPixels, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                             VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::Memory::DeviceLocal, "window pixels"));
    const PresentPath path = choosePresentPath(source.view != VK_NULL_HANDLE, source.size, viewSize, s.canBlit);
    if (path == PresentPath::Upscale) BRUME_TRY(s.ensureSourceDisplay(source.size));
    if (capture)
        BRUME_TRY(s.ensureBuffer(s.readback, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::Memory::Readback, "screenshot"));
    s.record(index, source, path, viewSize, generation, ui, capture != nullptr);
    part("record");

    const VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_TRANSFER_BIT;
    VkSubmitInfo submit = vkStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.waitSemaphoreCount = 1;
    submit.pWaitSemaphores = &acquired;
    submit.pWaitDstStageMask = &waitStage;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &s.cmd;
    submit.signalSemaphoreCount = 1;
    submit.pSignalSemaphores = &rendered;
    BRUME_VK(vkQueueSubmit(s.device.queue(), 1, &submit, fence), "submit the window frame");
    part("submit");
    if (s.measureParts) {
        BRUME_VK(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), "wait for the window frame");
        part("device wait");
    }
    VkPresentInfoKHR present = vkStruct<VkPresentInfoKHR>(VK_STRUCTURE_TYPE_PRESENT_INFO_KHR);
    present.waitSemaphoreCount = 1;
    present.pWaitSemaphores = &rendered;
    present.swapchainCount = 1;
    const VkSwapchainKHR swapchain = s.swapchain.get();
    present.pSwapchains = &swapchain;
    present.pImageIndices = &index;
    r = gpu::injectedFault(gpu::FaultSite::Present);
    if (r == VK_SUCCESS) r = vkQueuePresentKHR(s.device.queue(), &present);
    if (r != VK_SUBOPTIMAL_KHR && r != VK_ERROR_OUT_OF_DATE_KHR) BRUME_VK(r, "show the window frame");
    part("queue present");
    if (gImGuiResult != VK_SUCCESS) return gpu::vkError("draw the UI", std::exchange(gImGuiResult, VK_SUCCESS));
    if (capture) {
        BRUME_VK(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), "wait for the screenshot");
        capture->width = static_cast<int>(s.extent.width);
        capture->height = static_cast<int>(s.extent.height);
        capture->pixels.resize(static_cast<size_t>(bytes));
        const auto* src = static_cast<const uint8_t*>(s.readback.mapped);
        for (size_t i = 0; i < capture->pixels.size(); i += 4) {
            capture->pixels[i + 0] = s.bgra ? src[i + 2] : src[i];
            capture->pixels[i + 1] = src[i + 1];
            capture->pixels[i + 2] = s.bgra ? src[i] : src[i + 2];
            capture->pixels[i + 3] = 255;
        }
    }
    return {};
}

}  // namespace brume::editor
