// VkResult -> Error with a sentence a user can act on; raw VkResult codes never reach users.
#pragma once

#include <cstdint>
#include <string>

#include <vulkan/vulkan.h>

#include "core/result.h"

namespace brume::gpu {

// What a failed call's result means, in words ("the device ran out of memory").
const char* describeVkResult(VkResult r);

// A zeroed Vulkan struct with its sType set (brace-initializing only sType trips
// -Wmissing-field-initializers).
template <class T>
T vkStruct(VkStructureType type) {
    T s{};
    s.sType = type;
    return s;
}

// "Vulkan could not <action>: <description>."
Error vkError(const std::string& action, VkResult r);
// Whether `e` came from vkError for out-of-memory or device loss: a lower quality may still render.
bool isGpuFault(const Error& e);
// Whether `e` came from vkError for a lost device: the device is unusable and must be recreated.
bool isDeviceLost(const Error& e);

// Fault injection for tests (docs/reliability.md, "GPU faults"). The environment variable
// BRUME_GPU_FAULT=oom@N makes the Nth GPU memory allocation of the process fail with
// VK_ERROR_OUT_OF_DEVICE_MEMORY, and lost@N the Nth frame submission fail with VK_ERROR_DEVICE_LOST
// (the frame is not submitted); N counts from 1, and a bad value is ignored. dead@N stands for a
// real device loss: the Nth submission and every submission, window image acquisition and
// presentation after it fail, until a device is created again (deviceCreated). acquire@N and
// present@N do the same from the editor window's Nth image acquisition or presentation (the image
// is not acquired or presented). gone@N is dead@N on every device created after it too (a GPU that
// fell off the bus). setFaultInjection does the same in-process (n = 0: none, never sticky) and
// restarts the counts.
enum class FaultSite { Allocate, Submit, Acquire, Present };
void setFaultInjection(FaultSite site, uint64_t n);
// Called by Device::create: a lost device of dead@N (acquire@N, present@N) is replaced, and calls
// succeed again.
void deviceCreated();
// VK_SUCCESS, or the injected failure when this call is the chosen one (counts every call).
VkResult injectedFault(FaultSite site);

}  // namespace brume::gpu

// Evaluates a Vulkan call; on failure returns vkError(action, result) from the enclosing function
// (whose return type is any Result<T>).
#define BRUME_VK(call, action)                                        \
    do {                                                               \
        const VkResult brumeVkResult_ = (call);                        \
        if (brumeVkResult_ != VK_SUCCESS)                              \
            return ::brume::gpu::vkError((action), brumeVkResult_);    \
    } while (0)

// Propagates the error of a Result<void> expression.
#define BRUME_TRY(expr)                                 \
    do {                                                \
        auto brumeTry_ = (expr);                        \
        if (!brumeTry_.ok()) return brumeTry_.error();  \
    } while (0)
