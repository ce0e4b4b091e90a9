#include "vk_check.h"

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <mutex>

namespace brume::gpu {

const char* describeVkResult(VkResult r) {
    switch (r) {
        case VK_SUCCESS: return "it succeeded";
        case VK_NOT_READY: return "the result is not ready yet";
        case VK_TIMEOUT: return "the operation timed out";
        case VK_INCOMPLETE: return "the returned list was incomplete";
        case VK_ERROR_OUT_OF_HOST_MEMORY: return "the computer ran out of memory";
        case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "the GPU ran out of memory (try a lower quality or a smaller image)";
        case VK_ERROR_INITIALIZATION_FAILED: return "the driver failed to initialize";
        case VK_ERROR_DEVICE_LOST: return "the GPU stopped responding (device lost; a driver crash or a timeout)";
        case VK_ERROR_MEMORY_MAP_FAILED: return "GPU memory could not be mapped for the CPU";
        case VK_ERROR_LAYER_NOT_PRESENT: return "a requested layer is not installed (the validation layer needs the Vulkan SDK or vulkan-validationlayers)";
        case VK_ERROR_EXTENSION_NOT_PRESENT: return "a required extension is not supported";
        case VK_ERROR_FEATURE_NOT_PRESENT: return "a required device feature is not supported";
        case VK_ERROR_INCOMPATIBLE_DRIVER: return "no compatible Vulkan driver is installed (check the driver or VK_ICD_FILENAMES)";
        case VK_ERROR_TOO_MANY_OBJECTS: return "too many objects of one kind were created";
        case VK_ERROR_FORMAT_NOT_SUPPORTED: return "an image format is not supported by this device";
        case VK_ERROR_FRAGMENTED_POOL: return "a descriptor pool is fragmented";
        case VK_ERROR_OUT_OF_POOL_MEMORY: return "a descriptor pool ran out of space";
        case VK_ERROR_INVALID_EXTERNAL_HANDLE: return "an external handle is invalid";
        case VK_ERROR_FRAGMENTATION: return "GPU memory is too fragmented";
        default: return "the driver reported an unknown error";
    }
}

Error vkError(const std::string& action, VkResult r) {
    return Error{"Vulkan could not " + action + ": " + describeVkResult(r) + "."};
}

bool isGpuFault(const Error& e) {
    if (e.message.rfind("Vulkan could not ", 0) != 0) return false;
    for (VkResult r : {VK_ERROR_OUT_OF_DEVICE_MEMORY, VK_ERROR_OUT_OF_HOST_MEMORY, VK_ERROR_DEVICE_LOST})
        if (e.message.find(describeVkResult(r)) != std::string::npos) return true;
    return false;
}

bool isDeviceLost(const Error& e) {
    return e.message.rfind("Vulkan could not ", 0) == 0 &&
           e.message.find(describeVkResult(VK_ERROR_DEVICE_LOST)) != std::string::npos;
}

namespace {

struct Injection {
    std::atomic<uint64_t> failAt{0};  // 0: never
    std::atomic<uint64_t> calls{0};
    std::atomic<bool> sticky{false};  // dead@N, acquire@N, present@N: the device stays lost
};
Injection g_injections[4];  // by FaultSite
// A lost device of a sticky fault: every submission, acquisition and presentation fails until a
// device is created (deviceCreated) ...
std::atomic<bool> g_dead{false};
// ... or, for gone@N, on every device from then on (the GPU is gone).
std::atomic<bool> g_gone{false};
std::once_flag g_fromEnvironment;

// BRUME_GPU_FAULT=oom@N | lost@N | dead@N | gone@N | acquire@N | present@N, read once.
void readEnvironment() {
    const char* v = std::getenv("BRUME_GPU_FAULT");
    if (!v) return;
    const char* at = std::strchr(v, '@');
    if (!at) return;
    char* end = nullptr;
    const unsigned long long n = std::strtoull(at + 1, &end, 10);
    if (end == at + 1 || *end != '\0') return;
    const std::string kind(v, at);
    FaultSite site = FaultSite::Submit;
    if (kind == "oom") site = FaultSite::Allocate;
    else if (kind == "acquire") site = FaultSite::Acquire;
    else if (kind == "present") site = FaultSite::Present;
    else if (kind != "lost" && kind != "dead" && kind != "gone") return;
    g_injections[int(site)].failAt = n;
    g_injections[int(site)].sticky = kind != "oom" && kind != "lost";
    if (kind == "gone") g_gone = true;  // armed: takes effect at the Nth submission
}

}  // namespace

void setFaultInjection(FaultSite site, uint64_t n) {
    std::call_once(g_fromEnvironment, readEnvironment);
    for (Injection& i : g_injections) i.calls = 0, i.sticky = false;
    g_dead = false;
    g_gone = false;
    g_injections[int(site)].failAt = n;
}

void deviceCreated() {
    std::call_once(g_fromEnvironment, readEnvironment);
    if (!g_gone) g_dead = false;
}

VkResult injectedFault(FaultSite site) {
    std::call_once(g_fromEnvironment, readEnvironment);
    Injection& i = g_injections[int(site)];
    const uint64_t call = ++i.calls;
    if (site != FaultSite::Allocate && g_dead) return VK_ERROR_DEVICE_LOST;
    if (i.failAt == 0 || call != i.failAt) return VK_SUCCESS;
    if (i.sticky) g_dead = true;
    return site == FaultSite::Allocate ? VK_ERROR_OUT_OF_DEVICE_MEMORY : VK_ERROR_DEVICE_LOST;
}

}  // namespace brume::gpu
