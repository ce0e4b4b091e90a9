// What every pass shares: the one descriptor set (its bindings: shaders/shared/frame_table.h), its
// pipeline layout, shader modules from the embedded SPIR-V, compute pipelines and barriers.
#pragma once

#include <map>
#include <span>
#include <string>

#include "resources.h"

namespace brume::gpu {

struct FrameResources;

struct DescriptorBindings {
    DescriptorSetLayoutOwner setLayout;
    PipelineLayoutOwner pipelineLayout;
    DescriptorPoolOwner pool;
    VkDescriptorSet set = VK_NULL_HANDLE;  // freed with the pool
};

Result<DescriptorBindings> createDescriptorBindings(const Device& device);

// One descriptor set of `bindings`: its layout, a pipeline layout with one compute push-constant
// range of `pushBytes` (0: none), a pool sized for exactly those descriptors, and the set; debug
// names start with `name`.
Result<DescriptorBindings> createDescriptorSet(const Device& device, std::span<const VkDescriptorSetLayoutBinding> bindings,
                                               uint32_t pushBytes, const std::string& name);

// Points every binding of the table at the current resources; call after any of them is recreated.
void writeDescriptorBindings(const Device& device, VkDescriptorSet set, const FrameResources& r);
// The temporal ping-pong pairs: *_IN = image 1 - writeIndex of each pair, *_OUT = image writeIndex.
// Called before recording each frame (the set is not in use then: the previous frame has finished).
void writeHistoryBindings(const Device& device, VkDescriptorSet set, const FrameResources& r, int writeIndex);

// name: a shader file name from shaders/, e.g. "voxelize.comp".
Result<ShaderModuleOwner> createShaderModule(const Device& device, const char* name);

// A compute pipeline of one shader variant.
struct ComputePass {
    PipelineOwner pipeline;
    std::string shader;  // the embedded SPIR-V's name, also the pipeline's debug name
};

Result<ComputePass> createComputePass(const Device& device, VkPipelineLayout layout, const std::string& shader);

// One pipeline per shader variant, created on first use (lavapipe compiles a pipeline in 10-100 ms,
// so a variant a scene never needs is never built).
class PipelineCache {
public:
    Result<const ComputePass*> get(const Device& device, VkPipelineLayout layout, const std::string& shader);
    size_t size() const { return passes_.size(); }

private:
    std::map<std::string, ComputePass> passes_;
};

void bindComputePass(VkCommandBuffer cmd, const ComputePass& pass, const DescriptorBindings& bindings);

// One barrier moving each image from one layout to another (whole image, colour aspect).
struct LayoutChange {
    VkImage image;
    VkImageLayout from, to;
};
void layoutBarrier(VkCommandBuffer cmd, std::span<const LayoutChange> images, VkPipelineStageFlags srcStage,
                   VkAccessFlags srcAccess, VkPipelineStageFlags dstStage, VkAccessFlags dstAccess);

// Global memory barrier: writes `srcAccess` by `src` stages before it become visible to `dstAccess`
// by `dst` stages after it.
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags src, VkAccessFlags srcAccess, VkPipelineStageFlags dst,
                   VkAccessFlags dstAccess);

}  // namespace brume::gpu
