#include "resources.h"

#include "vk_check.h"

namespace brume::gpu {
namespace {

Result<MemoryOwner> allocate(const Device& device, VkMemoryRequirements req, Memory kind, const std::string& name) {
    VkMemoryPropertyFlags flags = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    if (kind != Memory::DeviceLocal) flags = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    // Reading uncached memory from the CPU is ~10x slower: prefer cached for read-back.
    Result<uint32_t> type = device.memoryType(req.memoryTypeBits,
                                              kind == Memory::Readback ? flags | VK_MEMORY_PROPERTY_HOST_CACHED_BIT : flags);
    if (!type) type = device.memoryType(req.memoryTypeBits, flags);
    if (!type) return type.error();
    VkMemoryAllocateInfo info = vkStruct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
    info.allocationSize = req.size;
    info.memoryTypeIndex = type.value();
    VkDeviceMemory memory = VK_NULL_HANDLE;
    const VkResult injected = injectedFault(FaultSite::Allocate);  // tests only (vk_check.h)
    BRUME_VK(injected != VK_SUCCESS ? injected : vkAllocateMemory(device.vk(), &info, nullptr, &memory),
             "allocate " + std::to_string(req.size >> 20) + " MiB for " + name);
    device.name(memory, VK_OBJECT_TYPE_DEVICE_MEMORY, name + " memory");
    return MemoryOwner(device.vk(), memory);
}

}  // namespace

Result<Buffer> createBuffer(const Device& device, VkDeviceSize size, VkBufferUsageFlags usage, Memory memory,
                            const std::string& name) {
    Buffer b;
    b.size = size;
    VkBufferCreateInfo info = vkStruct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    info.size = size;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VkBuffer buffer = VK_NULL_HANDLE;
    BRUME_VK(vkCreateBuffer(device.vk(), &info, nullptr, &buffer), "create the buffer " + name);
    b.buffer = BufferOwner(device.vk(), buffer);
    device.name(buffer, VK_OBJECT_TYPE_BUFFER, name);
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device.vk(), buffer, &req);
    Result<MemoryOwner> mem = allocate(device, req, memory, name);
    if (!mem) return mem.error();
    b.memory = std::move(mem.value());
    BRUME_VK(vkBindBufferMemory(device.vk(), buffer, b.memory.get(), 0), "bind memory to " + name);
    if (memory != Memory::DeviceLocal)
        BRUME_VK(vkMapMemory(device.vk(), b.memory.get(), 0, VK_WHOLE_SIZE, 0, &b.mapped), "map " + name);
    return b;
}

Result<GpuImage> createImage(const Device& device, VkExtent3D extent, bool volume, VkFormat format,
                          VkImageUsageFlags usage, const std::string& name) {
    GpuImage img;
    img.format = format;
    img.extent = extent;
    VkImageCreateInfo info = vkStruct<VkImageCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO);
    info.imageType = volume ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = extent;
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImage image = VK_NULL_HANDLE;
    BRUME_VK(vkCreateImage(device.vk(), &info, nullptr, &image), "create the image " + name);
    img.image = ImageOwner(device.vk(), image);
    device.name(image, VK_OBJECT_TYPE_IMAGE, name);
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device.vk(), image, &req);
    Result<MemoryOwner> mem = allocate(device, req, Memory::DeviceLocal, name);
    if (!mem) return mem.error();
    img.memory = std::move(mem.value());
    BRUME_VK(vkBindImageMemory(device.vk(), image, img.memory.get(), 0), "bind memory to " + name);

    VkImageViewCreateInfo view = vkStruct<VkImageViewCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO);
    view.image = image;
    view.viewType = volume ? VK_IMAGE_VIEW_TYPE_3D : VK_IMAGE_VIEW_TYPE_2D;
    view.format = format;
    const bool depth = format == VK_FORMAT_D32_SFLOAT;
    view.subresourceRange = {depth ? VkImageAspectFlags(VK_IMAGE_ASPECT_DEPTH_BIT) : VkImageAspectFlags(VK_IMAGE_ASPECT_COLOR_BIT),
                             0, 1, 0, 1};
    VkImageView v = VK_NULL_HANDLE;
    BRUME_VK(vkCreateImageView(device.vk(), &view, nullptr, &v), "create a view of " + name);
    img.view = ImageViewOwner(device.vk(), v);
    device.name(v, VK_OBJECT_TYPE_IMAGE_VIEW, name + " view");
    return img;
}

}  // namespace brume::gpu
