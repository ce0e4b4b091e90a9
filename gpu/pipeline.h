// What every pass shares: the one descriptor set (bindings: shaders/shared/bindings.h), its
// pipeline layout, shader modules from the embedded SPIR-V, compute pipelines and barriers.
#pragma once

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

// Points every binding at the current resources; call after any of them is recreated.
void writeDescriptorBindings(const Device& device, VkDescriptorSet set, const FrameResources& r);
// The temporal ping-pong pair: *_IN = r.history[1 - writeIndex], *_OUT = r.history[writeIndex].
// Called before recording each frame (the set is not in use then: the previous frame has finished).
void writeHistoryBindings(const Device& device, VkDescriptorSet set, const FrameResources& r, int writeIndex);

// name: a shader file name from shaders/, e.g. "voxelize.comp".
Result<ShaderModuleOwner> createShaderModule(const Device& device, const char* name);

// A compute pass: one pipeline and its label for debuggers and timings.
struct ComputePass {
    PipelineOwner pipeline;
    const char* label = "";
};

Result<ComputePass> createComputePass(const Device& device, VkPipelineLayout layout, const char* shader,
                                      const char* label);

void bindComputePass(VkCommandBuffer cmd, const ComputePass& pass, const DescriptorBindings& bindings);

// Global memory barrier: writes `srcAccess` by `src` stages before it become visible to `dstAccess`
// by `dst` stages after it.
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags src, VkAccessFlags srcAccess, VkPipelineStageFlags dst,
                   VkAccessFlags dstAccess);

// The barrier between two compute passes: the earlier one's storage writes feed the later one.
void computeToComputeBarrier(VkCommandBuffer cmd);

}  // namespace brume::gpu
