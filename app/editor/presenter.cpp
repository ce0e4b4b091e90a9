#include "presenter.h"

#include <algorithm>
#include <cstring>
#include <mutex>
#include <utility>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

#include "gpu/vk_check.h"

namespace brume::editor {

using gpu::vkStruct;

namespace {

// ImGui's backend reports Vulkan failures through a C callback; the next present() turns the
// latest one into an Error.
VkResult gImGuiResult = VK_SUCCESS;
void onImGuiVkResult(VkResult r) {
    if (r != VK_SUCCESS) gImGuiResult = r;
}

struct HostBuffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    void* mapped = nullptr;
    VkDeviceSize size = 0;
};

}  // namespace

struct Presenter::State {
    GLFWwindow* window = nullptr;
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    uint32_t family = 0;
    VkQueue queue = VK_NULL_HANDLE;
    VkSurfaceFormatKHR format{};
    VkRenderPass renderPass = VK_NULL_HANDLE;
    VkSwapchainKHR swapchain = VK_NULL_HANDLE;
    VkExtent2D extent{};
    uint32_t minImages = 2;
    std::vector<VkImage> images;
    std::vector<VkImageView> views;
    std::vector<VkFramebuffer> framebuffers;
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    VkSemaphore acquired = VK_NULL_HANDLE;
    VkSemaphore rendered = VK_NULL_HANDLE;
    VkDescriptorPool descriptorPool = VK_NULL_HANDLE;
    HostBuffer upload;
    HostBuffer readback;
    bool imguiReady = false;
    bool swapBytes = false;  // B8G8R8A8 swapchain: swap R and B on the way in and out

    mutable std::mutex messagesMutex;
    std::vector<std::string> messages;

    ~State();
    Result<void> createInstance(bool validation);
    Result<void> createDevice();
    Result<void> createRenderPass();
    Result<void> createSwapchain();
    void destroySwapchainViews();
    Result<void> createCommands();
    Result<void> initImGui();
    Result<void> ensureBuffer(HostBuffer& b, VkDeviceSize size, VkBufferUsageFlags usage);
    void destroyBuffer(HostBuffer& b);
    void record(uint32_t image, ImDrawData* ui, bool capture);
};

namespace {

VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
                                         const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* s = static_cast<Presenter::State*>(user);
    const char* level = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning";
    std::lock_guard<std::mutex> lock(s->messagesMutex);
    s->messages.push_back(std::string("editor window: ") + level + ": " + (data->pMessage ? data->pMessage : ""));
    return VK_FALSE;
}

}  // namespace

Result<void> Presenter::State::createInstance(bool validation) {
    uint32_t n = 0;
    const char** required = glfwGetRequiredInstanceExtensions(&n);
    if (!required) return Error{"This display has no Vulkan presentation support (GLFW found no Vulkan surface extensions)."};
    std::vector<const char*> extensions(required, required + n);
    std::vector<const char*> layers;
    if (validation) {
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        layers.push_back("VK_LAYER_KHRONOS_validation");
    }
    VkApplicationInfo app = vkStruct<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
    app.pApplicationName = "brume-editor";
    app.apiVersion = VK_API_VERSION_1_1;
    VkInstanceCreateInfo info = vkStruct<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
    info.pApplicationInfo = &app;
    info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    info.enabledLayerCount = static_cast<uint32_t>(layers.size());
    info.ppEnabledLayerNames = layers.data();
    BRUME_VK(vkCreateInstance(&info, nullptr, &instance), "create the editor window's instance");
    if (validation) {
        VkDebugUtilsMessengerCreateInfoEXT m = vkStruct<VkDebugUtilsMessengerCreateInfoEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT);
        m.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
        m.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
        m.pfnUserCallback = onMessage;
        m.pUserData = this;
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
        if (create) BRUME_VK(create(instance, &m, nullptr, &messenger), "create the validation callback");
    }
    BRUME_VK(glfwCreateWindowSurface(instance, window, nullptr, &surface), "create the window surface");
    return {};
}

Result<void> Presenter::State::createDevice() {
    uint32_t n = 0;
    BRUME_VK(vkEnumeratePhysicalDevices(instance, &n, nullptr), "list the devices");
    std::vector<VkPhysicalDevice> devices(n);
    BRUME_VK(vkEnumeratePhysicalDevices(instance, &n, devices.data()), "list the devices");
    for (VkPhysicalDevice pd : devices) {
        uint32_t qn = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(pd, &qn, nullptr);
        std::vector<VkQueueFamilyProperties> families(qn);
        vkGetPhysicalDeviceQueueFamilyProperties(pd, &qn, families.data());
        for (uint32_t f = 0; f < qn && !physical; ++f) {
            VkBool32 present = VK_FALSE;
            vkGetPhysicalDeviceSurfaceSupportKHR(pd, f, surface, &present);
            if (present && (families[f].queueFlags & VK_QUEUE_GRAPHICS_BIT)) physical = pd, family = f;
        }
        if (physical) break;
    }
    if (!physical) return Error{"No Vulkan device can draw to this window (none supports presentation to it)."};
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo q = vkStruct<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
    q.queueFamilyIndex = family;
    q.queueCount = 1;
    q.pQueuePriorities = &priority;
    const char* swapchainExt = VK_KHR_SWAPCHAIN_EXTENSION_NAME;
    VkDeviceCreateInfo info = vkStruct<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &q;
    info.enabledExtensionCount = 1;
    info.ppEnabledExtensionNames = &swapchainExt;
    BRUME_VK(vkCreateDevice(physical, &info, nullptr, &device), "create the editor window's device");
    vkGetDeviceQueue(device, family, 0, &queue);

    uint32_t fn = 0;
    vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &fn, nullptr);
    std::vector<VkSurfaceFormatKHR> formats(fn);
    vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &fn, formats.data());
    if (formats.empty()) return Error{"The window surface offers no pixel formats."};
    // UNORM, not SRGB: the viewport bytes are already display-encoded (the PNG's bytes).
    format = formats[0];
    for (const VkSurfaceFormatKHR& f : formats)
        if (f.format == VK_FORMAT_B8G8R8A8_UNORM || f.format == VK_FORMAT_R8G8B8A8_UNORM) format = f;
    if (format.format != VK_FORMAT_B8G8R8A8_UNORM && format.format != VK_FORMAT_R8G8B8A8_UNORM)
        return Error{"The window surface offers no 8-bit UNORM RGBA format, which the editor needs."};
    swapBytes = format.format == VK_FORMAT_B8G8R8A8_UNORM;
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
    BRUME_VK(vkCreateRenderPass(device, &info, nullptr, &renderPass), "create the window's render pass");
    return {};
}

void Presenter::State::destroySwapchainViews() {
    for (VkFramebuffer f : framebuffers) vkDestroyFramebuffer(device, f, nullptr);
    for (VkImageView v : views) vkDestroyImageView(device, v, nullptr);
    framebuffers.clear();
    views.clear();
}

Result<void> Presenter::State::createSwapchain() {
    VkSurfaceCapabilitiesKHR caps;
    BRUME_VK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(physical, surface, &caps), "query the window surface");
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
    info.surface = surface;
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
    info.oldSwapchain = swapchain;
    VkSwapchainKHR next = VK_NULL_HANDLE;
    BRUME_VK(vkCreateSwapchainKHR(device, &info, nullptr, &next), "create the window's swapchain");
    destroySwapchainViews();
    if (swapchain) vkDestroySwapchainKHR(device, swapchain, nullptr);
    swapchain = next;
    uint32_t n = 0;
    BRUME_VK(vkGetSwapchainImagesKHR(device, swapchain, &n, nullptr), "list the swapchain images");
    images.resize(n);
    BRUME_VK(vkGetSwapchainImagesKHR(device, swapchain, &n, images.data()), "list the swapchain images");
    for (VkImage image : images) {
        VkImageViewCreateInfo v = vkStruct<VkImageViewCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO);
        v.image = image;
        v.viewType = VK_IMAGE_VIEW_TYPE_2D;
        v.format = format.format;
        v.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkImageView view = VK_NULL_HANDLE;
        BRUME_VK(vkCreateImageView(device, &v, nullptr, &view), "create a swapchain image view");
        views.push_back(view);
        VkFramebufferCreateInfo f = vkStruct<VkFramebufferCreateInfo>(VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO);
        f.renderPass = renderPass;
        f.attachmentCount = 1;
        f.pAttachments = &view;
        f.width = extent.width;
        f.height = extent.height;
        f.layers = 1;
        VkFramebuffer fb = VK_NULL_HANDLE;
        BRUME_VK(vkCreateFramebuffer(device, &f, nullptr, &fb), "create a framebuffer");
        framebuffers.push_back(fb);
    }
    return {};
}

Result<void> Presenter::State::createCommands() {
    VkCommandPoolCreateInfo p = vkStruct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    p.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    p.queueFamilyIndex = family;
    BRUME_VK(vkCreateCommandPool(device, &p, nullptr, &pool), "create the window's command pool");
    VkCommandBufferAllocateInfo a = vkStruct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
    a.commandPool = pool;
    a.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    a.commandBufferCount = 1;
    BRUME_VK(vkAllocateCommandBuffers(device, &a, &cmd), "allocate the window's command buffer");
    VkFenceCreateInfo f = vkStruct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
    f.flags = VK_FENCE_CREATE_SIGNALED_BIT;
    BRUME_VK(vkCreateFence(device, &f, nullptr, &fence), "create a fence");
    VkSemaphoreCreateInfo s = vkStruct<VkSemaphoreCreateInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO);
    BRUME_VK(vkCreateSemaphore(device, &s, nullptr, &acquired), "create a semaphore");
    BRUME_VK(vkCreateSemaphore(device, &s, nullptr, &rendered), "create a semaphore");
    return {};
}

Result<void> Presenter::State::initImGui() {
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16};
    VkDescriptorPoolCreateInfo d = vkStruct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
    d.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    d.maxSets = 16;
    d.poolSizeCount = 1;
    d.pPoolSizes = &size;
    BRUME_VK(vkCreateDescriptorPool(device, &d, nullptr, &descriptorPool), "create the UI's descriptor pool");
    ImGui_ImplVulkan_InitInfo info{};
    info.Instance = instance;
    info.PhysicalDevice = physical;
    info.Device = device;
    info.QueueFamily = family;
    info.Queue = queue;
    info.DescriptorPool = descriptorPool;
    info.MinImageCount = minImages;
    info.ImageCount = static_cast<uint32_t>(images.size());
    info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    info.CheckVkResultFn = onImGuiVkResult;
    if (!ImGui_ImplVulkan_Init(&info, renderPass)) return Error{"The UI could not start its Vulkan renderer."};
    imguiReady = true;
    // The font atlas goes up once, on its own submission.
    VkCommandBufferBeginInfo begin = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    BRUME_VK(vkBeginCommandBuffer(cmd, &begin), "record the font upload");
    ImGui_ImplVulkan_CreateFontsTexture(cmd);
    BRUME_VK(vkEndCommandBuffer(cmd), "record the font upload");
    VkSubmitInfo submit = vkStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    BRUME_VK(vkQueueSubmit(queue, 1, &submit, VK_NULL_HANDLE), "upload the UI font");
    BRUME_VK(vkQueueWaitIdle(queue), "upload the UI font");
    ImGui_ImplVulkan_DestroyFontUploadObjects();
    return {};
}

Result<void> Presenter::State::ensureBuffer(HostBuffer& b, VkDeviceSize size, VkBufferUsageFlags usage) {
    if (b.size >= size) return {};
    destroyBuffer(b);
    VkBufferCreateInfo info = vkStruct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    info.size = size;
    info.usage = usage;
    BRUME_VK(vkCreateBuffer(device, &info, nullptr, &b.buffer), "create a staging buffer");
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device, b.buffer, &req);
    VkPhysicalDeviceMemoryProperties mem;
    vkGetPhysicalDeviceMemoryProperties(physical, &mem);
    const VkMemoryPropertyFlags want = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    uint32_t type = UINT32_MAX;
    for (uint32_t i = 0; i < mem.memoryTypeCount && type == UINT32_MAX; ++i)
        if ((req.memoryTypeBits & (1u << i)) && (mem.memoryTypes[i].propertyFlags & want) == want) type = i;
    if (type == UINT32_MAX) return Error{"The window's device has no host-visible memory for the viewport."};
    VkMemoryAllocateInfo a = vkStruct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
    a.allocationSize = req.size;
    a.memoryTypeIndex = type;
    BRUME_VK(vkAllocateMemory(device, &a, nullptr, &b.memory), "allocate the viewport's staging memory");
    BRUME_VK(vkBindBufferMemory(device, b.buffer, b.memory, 0), "bind the viewport's staging memory");
    BRUME_VK(vkMapMemory(device, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped), "map the viewport's staging memory");
    b.size = size;
    return {};
}

void Presenter::State::destroyBuffer(HostBuffer& b) {
    if (b.buffer) vkDestroyBuffer(device, b.buffer, nullptr);
    if (b.memory) vkFreeMemory(device, b.memory, nullptr);
    b = HostBuffer{};
}

Presenter::State::~State() {
    if (device) vkDeviceWaitIdle(device);
    if (imguiReady) ImGui_ImplVulkan_Shutdown();
    if (device) {
        destroyBuffer(upload);
        destroyBuffer(readback);
        destroySwapchainViews();
        if (swapchain) vkDestroySwapchainKHR(device, swapchain, nullptr);
        if (descriptorPool) vkDestroyDescriptorPool(device, descriptorPool, nullptr);
        if (acquired) vkDestroySemaphore(device, acquired, nullptr);
        if (rendered) vkDestroySemaphore(device, rendered, nullptr);
        if (fence) vkDestroyFence(device, fence, nullptr);
        if (pool) vkDestroyCommandPool(device, pool, nullptr);
        if (renderPass) vkDestroyRenderPass(device, renderPass, nullptr);
        vkDestroyDevice(device, nullptr);
    }
    if (surface) vkDestroySurfaceKHR(instance, surface, nullptr);
    if (messenger) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(instance, messenger, nullptr);
    }
    if (instance) vkDestroyInstance(instance, nullptr);
}

Result<std::unique_ptr<Presenter>> Presenter::create(GLFWwindow* window, bool validation) {
    auto s = std::make_unique<State>();
    s->window = window;
    BRUME_TRY(s->createInstance(validation));
    BRUME_TRY(s->createDevice());
    BRUME_TRY(s->createRenderPass());
    BRUME_TRY(s->createSwapchain());
    BRUME_TRY(s->createCommands());
    BRUME_TRY(s->initImGui());
    return std::unique_ptr<Presenter>(new Presenter(std::move(s)));
}

Presenter::Presenter(std::unique_ptr<State> s) : s_(std::move(s)) {}
Presenter::~Presenter() = default;

GLFWwindow* Presenter::window() const { return s_->window; }

void Presenter::newFrame() { ImGui_ImplVulkan_NewFrame(); }

std::vector<std::string> Presenter::validationMessages() const {
    std::lock_guard<std::mutex> lock(s_->messagesMutex);
    return s_->messages;
}

namespace {

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

// Records: viewport bytes -> window image (transfer), ImGui over it (render pass), and for a
// capture, window image -> readback buffer.
void Presenter::State::record(uint32_t index, ImDrawData* ui, bool capture) {
    const VkImage image = images[index];
    VkCommandBufferBeginInfo begin = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkBeginCommandBuffer(cmd, &begin);
    VkImageMemoryBarrier toCopy = imageBarrier(image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                                               VK_ACCESS_TRANSFER_WRITE_BIT);
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1, &toCopy);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {extent.width, extent.height, 1};
    vkCmdCopyBufferToImage(cmd, upload.buffer, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);

    VkRenderPassBeginInfo rp = vkStruct<VkRenderPassBeginInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO);
    rp.renderPass = renderPass;
    rp.framebuffer = framebuffers[index];
    rp.renderArea.extent = extent;
    vkCmdBeginRenderPass(cmd, &rp, VK_SUBPASS_CONTENTS_INLINE);
    if (ui) ImGui_ImplVulkan_RenderDrawData(ui, cmd);
    vkCmdEndRenderPass(cmd);

    if (capture) {
        VkImageMemoryBarrier toRead = imageBarrier(image, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                                   0, VK_ACCESS_TRANSFER_READ_BIT);
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1, &toRead);
        vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.buffer, 1, &region);
        VkImageMemoryBarrier back = imageBarrier(image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                                                 VK_ACCESS_TRANSFER_READ_BIT, 0);
        VkBufferMemoryBarrier host = vkStruct<VkBufferMemoryBarrier>(VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER);
        host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        host.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        host.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        host.buffer = readback.buffer;
        host.size = VK_WHOLE_SIZE;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT,
                             0, 0, nullptr, 1, &host, 1, &back);
    }
    vkEndCommandBuffer(cmd);
}

// Fills the staging buffer with the window-sized image: the viewport at the top-left, dark grey
// where the viewport does not reach (e.g. the frame after a resize, before the next render).
static void fillUpload(void* dst, VkExtent2D extent, const Rgba8& viewport, bool swapBytes) {
    auto* out = static_cast<uint8_t*>(dst);
    for (uint32_t y = 0; y < extent.height; ++y) {
        for (uint32_t x = 0; x < extent.width; ++x) {
            uint8_t* d = out + (static_cast<size_t>(y) * extent.width + x) * 4;
            if (static_cast<int>(x) < viewport.width && static_cast<int>(y) < viewport.height) {
                const uint8_t* s = viewport.pixels.data() + (static_cast<size_t>(y) * static_cast<size_t>(viewport.width) + x) * 4;
                d[0] = swapBytes ? s[2] : s[0];
                d[1] = s[1];
                d[2] = swapBytes ? s[0] : s[2];
                d[3] = 255;
            } else {
                d[0] = d[1] = d[2] = 24;
                d[3] = 255;
            }
        }
    }
}

Result<void> Presenter::present(const Rgba8& viewport, ImDrawData* ui, Rgba8* capture) {
    State& s = *s_;
    BRUME_VK(vkWaitForFences(s.device, 1, &s.fence, VK_TRUE, UINT64_MAX), "wait for the previous window frame");
    int w = 0, h = 0;
    glfwGetFramebufferSize(s.window, &w, &h);
    if (w == 0 || h == 0) return {};  // minimized
    if (static_cast<uint32_t>(w) != s.extent.width || static_cast<uint32_t>(h) != s.extent.height) {
        BRUME_VK(vkDeviceWaitIdle(s.device), "wait for the window before resizing");
        BRUME_TRY(s.createSwapchain());
    }
    uint32_t index = 0;
    VkResult r = vkAcquireNextImageKHR(s.device, s.swapchain, UINT64_MAX, s.acquired, VK_NULL_HANDLE, &index);
    if (r == VK_ERROR_OUT_OF_DATE_KHR) {
        BRUME_VK(vkDeviceWaitIdle(s.device), "wait for the window before resizing");
        return s.createSwapchain();  // the next frame draws
    }
    if (r != VK_SUBOPTIMAL_KHR) BRUME_VK(r, "get the next window image");
    BRUME_VK(vkResetFences(s.device, 1, &s.fence), "reset the window fence");
    const VkDeviceSize bytes = static_cast<VkDeviceSize>(s.extent.width) * s.extent.height * 4;
    BRUME_TRY(s.ensureBuffer(s.upload, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT));
    if (capture) BRUME_TRY(s.ensureBuffer(s.readback, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT));
    fillUpload(s.upload.mapped, s.extent, viewport, s.swapBytes);
    s.record(index, ui, capture != nullptr);

    const VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_TRANSFER_BIT;
    VkSubmitInfo submit = vkStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.waitSemaphoreCount = 1;
    submit.pWaitSemaphores = &s.acquired;
    submit.pWaitDstStageMask = &waitStage;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &s.cmd;
    submit.signalSemaphoreCount = 1;
    submit.pSignalSemaphores = &s.rendered;
    BRUME_VK(vkQueueSubmit(s.queue, 1, &submit, s.fence), "submit the window frame");
    VkPresentInfoKHR present = vkStruct<VkPresentInfoKHR>(VK_STRUCTURE_TYPE_PRESENT_INFO_KHR);
    present.waitSemaphoreCount = 1;
    present.pWaitSemaphores = &s.rendered;
    present.swapchainCount = 1;
    present.pSwapchains = &s.swapchain;
    present.pImageIndices = &index;
    r = vkQueuePresentKHR(s.queue, &present);
    if (r != VK_SUBOPTIMAL_KHR && r != VK_ERROR_OUT_OF_DATE_KHR) BRUME_VK(r, "show the window frame");
    if (gImGuiResult != VK_SUCCESS) return gpu::vkError("draw the UI", std::exchange(gImGuiResult, VK_SUCCESS));
    if (capture) {
        BRUME_VK(vkWaitForFences(s.device, 1, &s.fence, VK_TRUE, UINT64_MAX), "wait for the screenshot");
        capture->width = static_cast<int>(s.extent.width);
        capture->height = static_cast<int>(s.extent.height);
        capture->pixels.resize(static_cast<size_t>(bytes));
        const auto* src = static_cast<const uint8_t*>(s.readback.mapped);
        for (size_t i = 0; i < capture->pixels.size(); i += 4) {
            capture->pixels[i + 0] = s.swapBytes ? src[i + 2] : src[i];
            capture->pixels[i + 1] = src[i + 1];
            capture->pixels[i + 2] = s.swapBytes ? src[i] : src[i + 2];
            capture->pixels[i + 3] = 255;
        }
    }
    return {};
}

}  // namespace brume::editor
