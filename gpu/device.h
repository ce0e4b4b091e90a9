// The Vulkan instance, the chosen physical device, its logical device and queue, debug names and
// labels (VK_EXT_debug_utils when available) and the validation messenger.
//
// Device choice: the name given in GpuOptions::device, else the BRUME_DEVICE environment variable
// (case-insensitive substring of the device name), else the best kind present: discrete, then
// integrated, then virtual, then CPU (lavapipe). Validation: GpuOptions::validation or
// BRUME_VALIDATION=1; warnings and errors are collected so tests can assert there are none.
//
// Headless (the CLI, the tests) and windowed (the editor) use the same builder, as vk-bootstrap's
// set_headless: a PresentTarget adds the window system's instance extensions and a surface, and
// then only a device whose queue can also present to that surface is chosen (with
// VK_KHR_swapchain), so the renderer's images and the window share one device and one queue.
#pragma once

#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "core/result.h"
#include "vk_owner.h"

namespace brume::gpu {

// A window to present to (empty: headless). createSurface makes the surface on the new instance.
struct PresentTarget {
    std::vector<std::string> instanceExtensions;
    std::function<VkResult(VkInstance, VkSurfaceKHR*)> createSurface;
    bool enabled() const { return static_cast<bool>(createSurface); }
};

struct GpuOptions {
    std::string device;       // substring of the device name; empty = BRUME_DEVICE or automatic
    bool validation = false;  // also enabled by BRUME_VALIDATION=1
    PresentTarget present;    // headless unless set
    // false: the froxel passes run over the whole grid, not the regions that can hold media
    // (core/media_region.h); the images are the same, so this is for tests and measurements only.
    bool froxelRegions = true;
    // Tests only: each frame first fills the fog transmittance volume with NaN, so that a reader of a
    // cell the shadow volume pass did not write this frame shows in the image (tests/test_gpu_temporal.cpp).
    bool poisonShadowVolume = false;
    // Tests only: each frame first fills the integrated scattering with NaN, so that a lookup of an
    // entry the integrate pass did not store this frame (it stores only those some pixel or the glow
    // can read, in the columns they look up: shaders/integrate.comp) shows in the image.
    bool poisonIntegrated = false;
    // Tests only: each frame whose media region is not the whole grid first fills S and sigma_t (sourceImage,
    // sourceExtinction) with 1 (a finite value: the temporal resolve replaces a non-finite sample, so NaN
    // would hide), so that a temporal or integrate pass reading a froxel the light pass did not write
    // this frame shows in the image (it writes the temporal region: light_body.glsl).
    bool poisonSource = false;
    // false: every frame lights and resolves every froxel. true (the default): the froxels behind every
    // integrated entry a lookup reads are skipped (shaders/column_entries.glsl). The image at rest is
    // the same; in motion a froxel uncovered by the motion starts without history (docs/temporal.md,
    // "Hidden froxels"). false is for tests and measurements.
    bool skipHiddenFroxels = true;
};

class Device {
public:
    static Result<std::unique_ptr<Device>> create(const GpuOptions& options);
    ~Device();
    Device(const Device&) = delete;
    Device& operator=(const Device&) = delete;

    VkDevice vk() const { return device_; }
    VkInstance instance() const { return instance_; }
    VkPhysicalDevice physical() const { return physical_; }
    // VK_NULL_HANDLE when headless; else the queue presents to it.
    VkSurfaceKHR surface() const { return surface_.get(); }
    VkQueue queue() const { return queue_; }
    uint32_t queueFamily() const { return queueFamily_; }
    const std::string& name() const { return name_; }
    bool validationEnabled() const { return validation_; }
    // 0 when the queue cannot write timestamps.
    double timestampPeriodNs() const { return timestampPeriodNs_; }
    uint32_t timestampValidBits() const { return timestampValidBits_; }
    const VkPhysicalDeviceLimits& limits() const { return limits_; }
    // Whether storage images may use the extended formats (rgba16 for the integrated transmittance:
    // shared/frame_table.h); enabled on the logical device when the device has the feature.
    bool storageImageExtendedFormats() const { return storageImageExtendedFormats_; }

    // Debug names and labels are no-ops without VK_EXT_debug_utils.
    void setName(VkObjectType type, uint64_t handle, const std::string& name) const;
    template <class H>
    void name(H handle, VkObjectType type, const std::string& n) const {
        setName(type, reinterpret_cast<uint64_t>(handle), n);
    }
    void beginLabel(VkCommandBuffer cmd, const char* label) const;
    void endLabel(VkCommandBuffer cmd) const;

    Result<uint32_t> memoryType(uint32_t typeBits, VkMemoryPropertyFlags required) const;
    bool supportsFormat(VkFormat format, VkFormatFeatureFlags optimalFeatures) const;

    // Validation warnings and errors received so far (thread-safe).
    std::vector<std::string> validationMessages() const;
    void recordMessage(std::string message);

private:
    Device() = default;
    Result<void> createInstance(bool validation, const PresentTarget& present);
    Result<void> pickPhysicalDevice(const std::string& wanted);
    Result<void> createLogicalDevice();

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    SurfaceOwner surface_;  // destroyed by ~Device before the instance
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t queueFamily_ = 0;
    std::string name_;
    bool validation_ = false;
    bool debugUtils_ = false;
    double timestampPeriodNs_ = 0.0;
    uint32_t timestampValidBits_ = 0;
    VkPhysicalDeviceMemoryProperties memory_{};
    VkPhysicalDeviceLimits limits_{};
    bool storageImageExtendedFormats_ = false;

    PFN_vkSetDebugUtilsObjectNameEXT setObjectName_ = nullptr;
    PFN_vkCmdBeginDebugUtilsLabelEXT beginLabel_ = nullptr;
    PFN_vkCmdEndDebugUtilsLabelEXT endLabel_ = nullptr;

    mutable std::mutex messagesMutex_;
    std::vector<std::string> messages_;
};

}  // namespace brume::gpu
