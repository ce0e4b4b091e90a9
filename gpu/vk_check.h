// VkResult -> Error with a sentence a user can act on; raw VkResult codes never reach users.
#pragma once

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
