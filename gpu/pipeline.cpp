#include "pipeline.h"

#include <algorithm>
#include <array>
#include <vector>

#include "frame_resources.h"
#include "shaders/shared/bindings.h"
#include "shaders/shared/brume.h"
#include "spirv.h"
#include "vk_check.h"

namespace brume::gpu {
namespace {

VkDescriptorType bindingType(int binding) {
    if (binding == shd::BINDING_FRAME || binding == shd::BINDING_PREVIOUS_FRAME) return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    if (binding <= shd::BINDING_COUNTERS || binding == shd::BINDING_SHADOW_TRANSMITTANCE ||
        binding == shd::BINDING_VDB_GRIDS || binding == shd::BINDING_LIGHT_CLUSTERS ||
        binding == shd::BINDING_SUN_SHADOW_MAP || binding == shd::BINDING_LOCAL_SHADOW_MAPS)
        return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    return VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
}

}  // namespace

Result<DescriptorBindings> createDescriptorBindings(const Device& device) {
    std::array<VkDescriptorSetLayoutBinding, shd::BINDING_COUNT> bindings{};
    for (int i = 0; i < shd::BINDING_COUNT; ++i) {
        // Only the buffers reach the geometry pass: devices may allow as few as 4 storage images
        // per graphics stage.
        const VkShaderStageFlags stages = bindingType(i) == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE
                                              ? VK_SHADER_STAGE_COMPUTE_BIT
                                              : VK_SHADER_STAGE_COMPUTE_BIT | VK_SHADER_STAGE_VERTEX_BIT |
                                                    VK_SHADER_STAGE_FRAGMENT_BIT;
        bindings[static_cast<size_t>(i)] = {static_cast<uint32_t>(i), bindingType(i), 1, stages, nullptr};
    }
    // The push constants are the debug view pass's parameters; the other passes ignore them.
    return createDescriptorSet(device, bindings, sizeof(shd::DebugViewParams), "froxel");
}

Result<DescriptorBindings> createDescriptorSet(const Device& device, std::span<const VkDescriptorSetLayoutBinding> bindings,
                                               uint32_t pushBytes, const std::string& name) {
    DescriptorBindings b;
    VkDescriptorSetLayoutCreateInfo layoutInfo = vkStruct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
    layoutInfo.bindingCount = static_cast<uint32_t>(bindings.size());
    layoutInfo.pBindings = bindings.data();
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    BRUME_VK(vkCreateDescriptorSetLayout(device.vk(), &layoutInfo, nullptr, &setLayout), "create the " + name + " descriptor set layout");
    b.setLayout = DescriptorSetLayoutOwner(device.vk(), setLayout);
    device.name(setLayout, VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, name + " bindings layout");

    VkPipelineLayoutCreateInfo plInfo = vkStruct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
    plInfo.setLayoutCount = 1;
    plInfo.pSetLayouts = &setLayout;
    const VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, pushBytes};
    plInfo.pushConstantRangeCount = pushBytes > 0 ? 1 : 0;
    plInfo.pPushConstantRanges = &push;
    VkPipelineLayout pl = VK_NULL_HANDLE;
    BRUME_VK(vkCreatePipelineLayout(device.vk(), &plInfo, nullptr, &pl), "create the " + name + " pipeline layout");
    b.pipelineLayout = PipelineLayoutOwner(device.vk(), pl);
    device.name(pl, VK_OBJECT_TYPE_PIPELINE_LAYOUT, name + " pipeline layout");

    std::vector<VkDescriptorPoolSize> sizes;
    for (const VkDescriptorSetLayoutBinding& binding : bindings) {
        auto same = [&](const VkDescriptorPoolSize& s) { return s.type == binding.descriptorType; };
        auto it = std::find_if(sizes.begin(), sizes.end(), same);
        if (it == sizes.end()) sizes.push_back({binding.descriptorType, binding.descriptorCount});
        else it->descriptorCount += binding.descriptorCount;
    }
    VkDescriptorPoolCreateInfo poolInfo = vkStruct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
    poolInfo.maxSets = 1;
    poolInfo.poolSizeCount = static_cast<uint32_t>(sizes.size());
    poolInfo.pPoolSizes = sizes.data();
    VkDescriptorPool pool = VK_NULL_HANDLE;
    BRUME_VK(vkCreateDescriptorPool(device.vk(), &poolInfo, nullptr, &pool), "create the " + name + " descriptor pool");
    b.pool = DescriptorPoolOwner(device.vk(), pool);
    device.name(pool, VK_OBJECT_TYPE_DESCRIPTOR_POOL, name + " descriptor pool");

    VkDescriptorSetAllocateInfo alloc = vkStruct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
    alloc.descriptorPool = pool;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &setLayout;
    BRUME_VK(vkAllocateDescriptorSets(device.vk(), &alloc, &b.set), "allocate the " + name + " descriptor set");
    device.name(b.set, VK_OBJECT_TYPE_DESCRIPTOR_SET, name + " bindings");
    return b;
}

namespace {

// Points binding i at a buffer or an image view.
VkWriteDescriptorSet descriptorWrite(VkDescriptorSet set, int binding, const VkDescriptorBufferInfo* buffer,
                                     const VkDescriptorImageInfo* image) {
    VkWriteDescriptorSet w = vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    w.dstSet = set;
    w.dstBinding = static_cast<uint32_t>(binding);
    w.descriptorCount = 1;
    w.descriptorType = bindingType(binding);
    w.pBufferInfo = buffer;
    w.pImageInfo = image;
    return w;
}

}  // namespace

void writeDescriptorBindings(const Device& device, VkDescriptorSet set, const FrameResources& r) {
    // Bindings 0..3, BINDING_PREVIOUS_FRAME, BINDING_SHADOW_TRANSMITTANCE, BINDING_VDB_GRIDS,
    // BINDING_LIGHT_CLUSTERS, BINDING_SUN_SHADOW_MAP and BINDING_LOCAL_SHADOW_MAPS are buffers, 4..BINDING_OUTPUT images; the
    // history pair is bound per frame by writeHistoryBindings.
    const std::array<const Buffer*, 10> buffers{&r.frame,         &r.volumes,
                                                &r.lights,        &r.counters,
                                                &r.previousFrame, &r.shadowTransmittance,
                                                &r.vdbGrids,      &r.lightClusters,
                                                &r.sunShadowMap,  &r.localShadowMaps};
    const std::array<int, 10> bufferBindings{shd::BINDING_FRAME,          shd::BINDING_VOLUMES,
                                             shd::BINDING_LIGHTS,         shd::BINDING_COUNTERS,
                                             shd::BINDING_PREVIOUS_FRAME, shd::BINDING_SHADOW_TRANSMITTANCE,
                                             shd::BINDING_VDB_GRIDS,      shd::BINDING_LIGHT_CLUSTERS,
                                             shd::BINDING_SUN_SHADOW_MAP, shd::BINDING_LOCAL_SHADOW_MAPS};
    const std::array<const GpuImage*, shd::BINDING_OUTPUT - 3> images{
        &r.mediaScatteringG, &r.mediaExtinction, &r.mediaEmission, &r.source, &r.integratedScattering,
        &r.integratedTransmittance, &r.sceneColor, &r.sceneDepth, &r.output};
    std::array<VkDescriptorBufferInfo, buffers.size()> bufferInfos{};
    std::array<VkDescriptorImageInfo, images.size()> imageInfos{};
    std::array<VkWriteDescriptorSet, buffers.size() + images.size()> writes{};
    for (size_t i = 0; i < buffers.size(); ++i) {
        bufferInfos[i] = {buffers[i]->buffer.get(), 0, VK_WHOLE_SIZE};
        writes[i] = descriptorWrite(set, bufferBindings[i], &bufferInfos[i], nullptr);
    }
    for (size_t k = 0; k < images.size(); ++k) {
        imageInfos[k] = {VK_NULL_HANDLE, images[k]->view.get(), VK_IMAGE_LAYOUT_GENERAL};
        writes[buffers.size() + k] = descriptorWrite(set, static_cast<int>(k) + 4, nullptr, &imageInfos[k]);
    }
    vkUpdateDescriptorSets(device.vk(), static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);
}

void writeHistoryBindings(const Device& device, VkDescriptorSet set, const FrameResources& r, int writeIndex) {
    const HistoryImages& in = r.history[static_cast<size_t>(1 - writeIndex)];
    const HistoryImages& out = r.history[static_cast<size_t>(writeIndex)];
    const std::array<std::pair<int, const GpuImage*>, 4> images{{{shd::BINDING_HISTORY_SOURCE_IN, &in.source},
                                                                 {shd::BINDING_HISTORY_EXTINCTION_IN, &in.extinction},
                                                                 {shd::BINDING_HISTORY_SOURCE_OUT, &out.source},
                                                                 {shd::BINDING_HISTORY_EXTINCTION_OUT, &out.extinction}}};
    std::array<VkDescriptorImageInfo, 4> infos{};
    std::array<VkWriteDescriptorSet, 4> writes{};
    for (size_t i = 0; i < images.size(); ++i) {
        infos[i] = {VK_NULL_HANDLE, images[i].second->view.get(), VK_IMAGE_LAYOUT_GENERAL};
        writes[i] = descriptorWrite(set, images[i].first, nullptr, &infos[i]);
    }
    vkUpdateDescriptorSets(device.vk(), static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);
}

Result<ShaderModuleOwner> createShaderModule(const Device& device, const char* name) {
    const std::span<const uint32_t> words = embeddedSpirv(name);
    if (words.empty()) return Error{std::string("The shader ") + name + " is missing from this build of brume."};
    VkShaderModuleCreateInfo info = vkStruct<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
    info.codeSize = words.size_bytes();
    info.pCode = words.data();
    VkShaderModule module = VK_NULL_HANDLE;
    BRUME_VK(vkCreateShaderModule(device.vk(), &info, nullptr, &module), std::string("load the shader ") + name);
    device.name(module, VK_OBJECT_TYPE_SHADER_MODULE, name);
    return ShaderModuleOwner(device.vk(), module);
}

Result<ComputePass> createComputePass(const Device& device, VkPipelineLayout layout, const char* shader,
                                      const char* label) {
    Result<ShaderModuleOwner> module = createShaderModule(device, shader);
    if (!module) return module.error();
    VkComputePipelineCreateInfo info = vkStruct<VkComputePipelineCreateInfo>(VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO);
    info.stage = vkStruct<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO);
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module.value().get();
    info.stage.pName = "main";
    info.layout = layout;
    VkPipeline pipeline = VK_NULL_HANDLE;
    BRUME_VK(vkCreateComputePipelines(device.vk(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline),
             std::string("create the ") + label + " pipeline");
    device.name(pipeline, VK_OBJECT_TYPE_PIPELINE, std::string(label) + " pipeline");
    ComputePass pass;
    pass.pipeline = PipelineOwner(device.vk(), pipeline);
    pass.label = label;
    return pass;
}

void bindComputePass(VkCommandBuffer cmd, const ComputePass& pass, const DescriptorBindings& bindings) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pass.pipeline.get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, bindings.pipelineLayout.get(), 0, 1, &bindings.set,
                            0, nullptr);
}

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags src, VkAccessFlags srcAccess, VkPipelineStageFlags dst,
                   VkAccessFlags dstAccess) {
    VkMemoryBarrier b = vkStruct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
    b.srcAccessMask = srcAccess;
    b.dstAccessMask = dstAccess;
    vkCmdPipelineBarrier(cmd, src, dst, 0, 1, &b, 0, nullptr, 0, nullptr);
}

void computeToComputeBarrier(VkCommandBuffer cmd) {
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
}

}  // namespace brume::gpu
