#include "device.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>

#include "vk_check.h"

namespace brume::gpu {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

const char* kNoDevice =
    "No Vulkan device was found: install a Vulkan driver (for example Mesa's lavapipe, package "
    "mesa-vulkan-drivers) or check that VK_ICD_FILENAMES names an existing driver manifest.";

bool envFlag(const char* name) {
    const char* v = std::getenv(name);
    return v && std::strcmp(v, "1") == 0;
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

bool hasLayer(const char* name) {
    uint32_t n = 0;
    if (vkEnumerateInstanceLayerProperties(&n, nullptr) != VK_SUCCESS) return false;
    std::vector<VkLayerProperties> layers(n);
    if (vkEnumerateInstanceLayerProperties(&n, layers.data()) != VK_SUCCESS) return false;
    for (const VkLayerProperties& l : layers)
        if (std::strcmp(l.layerName, name) == 0) return true;
    return false;
}

bool hasInstanceExtension(const char* name, const char* layer) {
    uint32_t n = 0;
    if (vkEnumerateInstanceExtensionProperties(layer, &n, nullptr) != VK_SUCCESS) return false;
    std::vector<VkExtensionProperties> exts(n);
    if (vkEnumerateInstanceExtensionProperties(layer, &n, exts.data()) != VK_SUCCESS) return false;
    for (const VkExtensionProperties& e : exts)
        if (std::strcmp(e.extensionName, name) == 0) return true;
    return false;
}

VKAPI_ATTR VkBool32 VKAPI_CALL onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                               VkDebugUtilsMessageTypeFlagsEXT,
                                               const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    // Mesa 22.3's SPIR-V parser (lavapipe) warns that it drops `invariant gl_Position` (glslang puts
    // the decoration on the gl_PerVertex member, which SPIR-V allows); later Mesa drops it silently.
    // The geometry pass's depth pre-pass asks for invariance for the drivers that honour it.
    if (data->pMessage && std::strstr(data->pMessage, "Decoration not allowed on struct members: SpvDecorationInvariant"))
        return VK_FALSE;
    const char* level = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning";
    static_cast<Device*>(user)->recordMessage(std::string(level) + ": " + (data->pMessage ? data->pMessage : ""));
    return VK_FALSE;
}

VkDebugUtilsMessengerCreateInfoEXT messengerInfo(Device* owner) {
    VkDebugUtilsMessengerCreateInfoEXT info = vkStruct<VkDebugUtilsMessengerCreateInfoEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT);
    info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    info.pfnUserCallback = onDebugMessage;
    info.pUserData = owner;
    return info;
}

// Higher is preferred: real GPUs before software rasterizers.
int kindRank(VkPhysicalDeviceType t) {
    switch (t) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
        default: return 0;
    }
}

bool hasDeviceExtension(VkPhysicalDevice pd, const char* name) {
    uint32_t n = 0;
    if (vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr) != VK_SUCCESS) return false;
    std::vector<VkExtensionProperties> exts(n);
    if (vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, exts.data()) != VK_SUCCESS) return false;
    for (const VkExtensionProperties& e : exts)
        if (std::strcmp(e.extensionName, name) == 0) return true;
    return false;
}

// A queue family that does graphics and compute (every Vulkan GPU has one) and, given a surface,
// presents to it; -1 if none.
int universalQueueFamily(VkPhysicalDevice pd, VkSurfaceKHR surface) {
    if (surface && !hasDeviceExtension(pd, VK_KHR_SWAPCHAIN_EXTENSION_NAME)) return -1;
    uint32_t n = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, nullptr);
    std::vector<VkQueueFamilyProperties> families(n);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, families.data());
    const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    for (uint32_t i = 0; i < n; ++i) {
        if ((families[i].queueFlags & need) != need) continue;
        VkBool32 present = VK_TRUE;
        if (surface && vkGetPhysicalDeviceSurfaceSupportKHR(pd, i, surface, &present) != VK_SUCCESS) present = VK_FALSE;
        if (present) return static_cast<int>(i);
    }
    return -1;
}

}  // namespace

Result<std::unique_ptr<Device>> Device::create(const GpuOptions& options) {
    std::unique_ptr<Device> d(new Device());
    BRUME_TRY(d->createInstance(options.validation || envFlag("BRUME_VALIDATION"), options.present));
    std::string wanted = options.device;
    if (wanted.empty() && std::getenv("BRUME_DEVICE")) wanted = std::getenv("BRUME_DEVICE");
    BRUME_TRY(d->pickPhysicalDevice(wanted));
    BRUME_TRY(d->createLogicalDevice());
    deviceCreated();  // fault injection (vk_check.h): a new device is not a lost one
    return d;
}

Device::~Device() {
    if (device_) vkDestroyDevice(device_, nullptr);
    surface_.reset();
    if (messenger_) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(instance_, messenger_, nullptr);
    }
    if (instance_) vkDestroyInstance(instance_, nullptr);
}

Result<void> Device::createInstance(bool validation, const PresentTarget& present) {
    if (validation && !hasLayer(kValidationLayer))
        return Error{"The Vulkan validation layer (VK_LAYER_KHRONOS_validation) was requested but is not installed; "
                     "install vulkan-validationlayers or unset BRUME_VALIDATION."};
    validation_ = validation;
    debugUtils_ = hasInstanceExtension(VK_EXT_DEBUG_UTILS_EXTENSION_NAME, nullptr) ||
                  (validation && hasInstanceExtension(VK_EXT_DEBUG_UTILS_EXTENSION_NAME, kValidationLayer));
    std::vector<const char*> extensions, layers;
    if (debugUtils_) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (validation) layers.push_back(kValidationLayer);
    for (const std::string& e : present.instanceExtensions) extensions.push_back(e.c_str());

    VkApplicationInfo app = vkStruct<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
    app.pApplicationName = "brume";
    app.pEngineName = "brume";
    app.apiVersion = VK_API_VERSION_1_1;
    VkInstanceCreateInfo info = vkStruct<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
    info.pApplicationInfo = &app;
    info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    info.enabledLayerCount = static_cast<uint32_t>(layers.size());
    info.ppEnabledLayerNames = layers.data();
    // Chained so that messages about instance creation itself are collected too.
    VkDebugUtilsMessengerCreateInfoEXT messenger = messengerInfo(this);
    if (debugUtils_ && validation) info.pNext = &messenger;
    // Synchronization validation catches missing barriers between passes, which plain validation
    // does not (and which lavapipe's in-order execution would hide).
    const VkValidationFeatureEnableEXT syncValidation = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    VkValidationFeaturesEXT features = vkStruct<VkValidationFeaturesEXT>(VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT);
    if (validation && hasInstanceExtension(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME, kValidationLayer)) {
        extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
        info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
        info.ppEnabledExtensionNames = extensions.data();
        features.enabledValidationFeatureCount = 1;
        features.pEnabledValidationFeatures = &syncValidation;
        features.pNext = info.pNext;
        info.pNext = &features;
    }

    const VkResult r = vkCreateInstance(&info, nullptr, &instance_);
    if (r == VK_ERROR_INCOMPATIBLE_DRIVER) return Error{kNoDevice};
    BRUME_VK(r, "create an instance");
    if (debugUtils_) {
        setObjectName_ = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
            vkGetInstanceProcAddr(instance_, "vkSetDebugUtilsObjectNameEXT"));
        beginLabel_ = reinterpret_cast<PFN_vkCmdBeginDebugUtilsLabelEXT>(
            vkGetInstanceProcAddr(instance_, "vkCmdBeginDebugUtilsLabelEXT"));
        endLabel_ = reinterpret_cast<PFN_vkCmdEndDebugUtilsLabelEXT>(
            vkGetInstanceProcAddr(instance_, "vkCmdEndDebugUtilsLabelEXT"));
    }
    if (debugUtils_ && validation) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
        if (!create) return Error{"Vulkan could not create the validation message callback: the function is missing."};
        BRUME_VK(create(instance_, &messenger, nullptr, &messenger_), "create the validation message callback");
    }
    if (present.enabled()) {
        VkSurfaceKHR surface = VK_NULL_HANDLE;
        BRUME_VK(present.createSurface(instance_, &surface), "create the window surface");
        surface_ = SurfaceOwner(instance_, surface);
    }
    return {};
}

Result<void> Device::pickPhysicalDevice(const std::string& wanted) {
    uint32_t n = 0;
    const VkResult r = vkEnumeratePhysicalDevices(instance_, &n, nullptr);
    if (r == VK_ERROR_INITIALIZATION_FAILED || (r == VK_SUCCESS && n == 0)) return Error{kNoDevice};
    BRUME_VK(r, "list the devices");
    std::vector<VkPhysicalDevice> devices(n);
    BRUME_VK(vkEnumeratePhysicalDevices(instance_, &n, devices.data()), "list the devices");

    int bestRank = -1;
    std::string names;
    for (VkPhysicalDevice pd : devices) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(pd, &p);
        names += (names.empty() ? "" : ", ") + std::string(p.deviceName);
        if (p.apiVersion < VK_API_VERSION_1_1 || universalQueueFamily(pd, surface_.get()) < 0) continue;
        if (!wanted.empty() && lower(p.deviceName).find(lower(wanted)) == std::string::npos) continue;
        if (kindRank(p.deviceType) <= bestRank) continue;
        bestRank = kindRank(p.deviceType);
        physical_ = pd;
        name_ = p.deviceName;
        timestampPeriodNs_ = p.limits.timestampComputeAndGraphics ? p.limits.timestampPeriod : 0.0;
        limits_ = p.limits;
    }
    if (!physical_ && !wanted.empty())
        return Error{"No Vulkan device matches \"" + wanted + "\" (from the device option or BRUME_DEVICE); available: " +
                     names + "."};
    if (!physical_ && surface_)
        return Error{"No Vulkan device supports Vulkan 1.1 with a graphics and compute queue that can also draw to this "
                     "window; available: " + names + "."};
    if (!physical_)
        return Error{"No Vulkan device supports Vulkan 1.1 with a graphics and compute queue; available: " + names + "."};
    queueFamily_ = static_cast<uint32_t>(universalQueueFamily(physical_, surface_.get()));
    uint32_t qn = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &qn, nullptr);
    std::vector<VkQueueFamilyProperties> families(qn);
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &qn, families.data());
    timestampValidBits_ = families[queueFamily_].timestampValidBits;
    if (timestampValidBits_ == 0) timestampPeriodNs_ = 0.0;
    vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);
    return {};
}

Result<void> Device::createLogicalDevice() {
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue = vkStruct<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
    queue.queueFamilyIndex = queueFamily_;
    queue.queueCount = 1;
    queue.pQueuePriorities = &priority;
    VkPhysicalDeviceFeatures supported{};
    vkGetPhysicalDeviceFeatures(physical_, &supported);
    VkPhysicalDeviceFeatures features{};
    features.shaderStorageImageExtendedFormats = supported.shaderStorageImageExtendedFormats;
    storageImageExtendedFormats_ = supported.shaderStorageImageExtendedFormats == VK_TRUE;
    VkDeviceCreateInfo info = vkStruct<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queue;
    info.pEnabledFeatures = &features;
    const char* swapchain = VK_KHR_SWAPCHAIN_EXTENSION_NAME;
    if (surface_) {
        info.enabledExtensionCount = 1;
        info.ppEnabledExtensionNames = &swapchain;
    }
    BRUME_VK(vkCreateDevice(physical_, &info, nullptr, &device_), "create a logical device on " + name_);
    vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);
    name(queue_, VK_OBJECT_TYPE_QUEUE, "brume queue");
    return {};
}

void Device::setName(VkObjectType type, uint64_t handle, const std::string& n) const {
    if (!setObjectName_ || !device_) return;
    VkDebugUtilsObjectNameInfoEXT info = vkStruct<VkDebugUtilsObjectNameInfoEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT);
    info.objectType = type;
    info.objectHandle = handle;
    info.pObjectName = n.c_str();
    setObjectName_(device_, &info);
}

void Device::beginLabel(VkCommandBuffer cmd, const char* label) const {
    if (!beginLabel_) return;
    VkDebugUtilsLabelEXT l = vkStruct<VkDebugUtilsLabelEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT);
    l.pLabelName = label;
    beginLabel_(cmd, &l);
}

void Device::endLabel(VkCommandBuffer cmd) const {
    if (endLabel_) endLabel_(cmd);
}

Result<uint32_t> Device::memoryType(uint32_t typeBits, VkMemoryPropertyFlags required) const {
    for (uint32_t i = 0; i < memory_.memoryTypeCount; ++i) {
        if ((typeBits & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & required) == required) return i;
    }
    return Error{"The device " + name_ + " has no memory of the kind a GPU resource needs."};
}

bool Device::supportsFormat(VkFormat format, VkFormatFeatureFlags optimalFeatures) const {
    VkFormatProperties p;
    vkGetPhysicalDeviceFormatProperties(physical_, format, &p);
    return (p.optimalTilingFeatures & optimalFeatures) == optimalFeatures;
}

std::vector<std::string> Device::validationMessages() const {
    std::lock_guard<std::mutex> lock(messagesMutex_);
    return messages_;
}

void Device::recordMessage(std::string message) {
    std::lock_guard<std::mutex> lock(messagesMutex_);
    messages_.push_back(std::move(message));
}

}  // namespace brume::gpu
