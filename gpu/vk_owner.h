// RAII owners for Vulkan objects: one move-only owner per handle, destroyed with its parent (the
// device, or the instance for a surface). Objects owned by a device are declared after the Device
// in every class, so they die first.
#pragma once

#include <utility>

#include <vulkan/vulkan.h>

namespace brume::gpu {

template <class Parent, class Handle, void (*Destroy)(Parent, Handle, const VkAllocationCallbacks*)>
class ParentOwner {
public:
    ParentOwner() = default;
    ParentOwner(Parent device, Handle handle) : device_(device), handle_(handle) {}
    ParentOwner(const ParentOwner&) = delete;
    ParentOwner& operator=(const ParentOwner&) = delete;
    ParentOwner(ParentOwner&& o) noexcept : device_(o.device_), handle_(std::exchange(o.handle_, VK_NULL_HANDLE)) {}
    ParentOwner& operator=(ParentOwner&& o) noexcept {
        if (this != &o) {
            reset();
            device_ = o.device_;
            handle_ = std::exchange(o.handle_, VK_NULL_HANDLE);
        }
        return *this;
    }
    ~ParentOwner() { reset(); }

    void reset() {
        if (handle_ != VK_NULL_HANDLE) Destroy(device_, handle_, nullptr);
        handle_ = VK_NULL_HANDLE;
    }
    Handle get() const { return handle_; }
    explicit operator bool() const { return handle_ != VK_NULL_HANDLE; }

private:
    Parent device_ = VK_NULL_HANDLE;
    Handle handle_ = VK_NULL_HANDLE;
};

template <class Handle, void (*Destroy)(VkDevice, Handle, const VkAllocationCallbacks*)>
using Owner = ParentOwner<VkDevice, Handle, Destroy>;

using BufferOwner = Owner<VkBuffer, vkDestroyBuffer>;
using BufferViewOwner = Owner<VkBufferView, vkDestroyBufferView>;
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
using SemaphoreOwner = Owner<VkSemaphore, vkDestroySemaphore>;
using SwapchainOwner = Owner<VkSwapchainKHR, vkDestroySwapchainKHR>;
using SurfaceOwner = ParentOwner<VkInstance, VkSurfaceKHR, vkDestroySurfaceKHR>;

}  // namespace brume::gpu
