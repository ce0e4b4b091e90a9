// RAII owners for Vulkan objects: one move-only owner per handle, destroyed with its device.
// Objects owned by a device are declared after the Device in every class, so they die first.
#pragma once

#include <utility>

#include <vulkan/vulkan.h>

namespace brume::gpu {

template <class Handle, void (*Destroy)(VkDevice, Handle, const VkAllocationCallbacks*)>
class Owner {
public:
    Owner() = default;
    Owner(VkDevice device, Handle handle) : device_(device), handle_(handle) {}
    Owner(const Owner&) = delete;
    Owner& operator=(const Owner&) = delete;
    Owner(Owner&& o) noexcept : device_(o.device_), handle_(std::exchange(o.handle_, VK_NULL_HANDLE)) {}
    Owner& operator=(Owner&& o) noexcept {
        if (this != &o) {
            reset();
            device_ = o.device_;
            handle_ = std::exchange(o.handle_, VK_NULL_HANDLE);
        }
        return *this;
    }
    ~Owner() { reset(); }

    void reset() {
        if (handle_ != VK_NULL_HANDLE) Destroy(device_, handle_, nullptr);
        handle_ = VK_NULL_HANDLE;
    }
    Handle get() const { return handle_; }
    explicit operator bool() const { return handle_ != VK_NULL_HANDLE; }

private:
    VkDevice device_ = VK_NULL_HANDLE;
    Handle handle_ = VK_NULL_HANDLE;
};

using BufferOwner = Owner<VkBuffer, vkDestroyBuffer>;
using MemoryOwner = Owner<VkDeviceMemory, vkFreeMemory>;
using ImageOwner = Owner<VkImage, vkDestroyImage>;
using ImageViewOwner = Owner<VkImageView, vkDestroyImageView>;
using ShaderModuleOwner = Owner<VkShaderModule, vkDestroyShaderModule>;
using PipelineOwner = Owner<VkPipeline, vkDestroyPipeline>;
using PipelineLayoutOwner = Owner<VkPipelineLayout, vkDestroyPipelineLayout>;
using DescriptorSetLayoutOwner = Owner<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout>;
using DescriptorPoolOwner = Owner<VkDescriptorPool, vkDestroyDescriptorPool>;
using CommandPoolOwner = Owner<VkCommandPool, vkDestroyCommandPool>;
using FenceOwner = Owner<VkFence, vkDestroyFence>;
using QueryPoolOwner = Owner<VkQueryPool, vkDestroyQueryPool>;
using RenderPassOwner = Owner<VkRenderPass, vkDestroyRenderPass>;
using FramebufferOwner = Owner<VkFramebuffer, vkDestroyFramebuffer>;

}  // namespace brume::gpu
