// Buffers and images with their own memory (the renderer owns ~15 resources, so one allocation
// each is simpler than a sub-allocator and well below maxMemoryAllocationCount = 4096).
#pragma once

#include <string>

#include "device.h"
#include "vk_owner.h"

namespace brume::gpu {

enum class Memory { DeviceLocal, Upload, Readback };

struct Buffer {
    BufferOwner buffer;
    MemoryOwner memory;
    void* mapped = nullptr;  // persistently mapped for Upload and Readback
    VkDeviceSize size = 0;
};

struct GpuImage {
    ImageOwner image;
    MemoryOwner memory;
    ImageViewOwner view;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkExtent3D extent{0, 0, 0};
};

Result<Buffer> createBuffer(const Device& device, VkDeviceSize size, VkBufferUsageFlags usage, Memory memory,
                            const std::string& name);

// 2D when extent.depth == 1 and !volume, else 3D. Optimal tiling, device-local, one mip, one layer.
Result<GpuImage> createImage(const Device& device, VkExtent3D extent, bool volume, VkFormat format,
                          VkImageUsageFlags usage, const std::string& name);

}  // namespace brume::gpu
