// What every pass shares: the one descriptor set (its bindings: shaders/shared/frame_table.h), its
// pipeline layout, shader modules from the embedded SPIR-V, compute pipelines and barriers.
#pragma once

#include <array>
#include <compare>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "resources.h"
#include "shaders/shared/specialization.h"

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

// The values of shaders/shared/specialization.h's constants, in constant_id order. A default key is
// the shaders' own defaults (nothing left out).
enum class SpecId : uint8_t {
#define BRUME_CPP_SPEC_ID(name, id, value) name,
    BRUME_SPEC_CONSTANTS(BRUME_CPP_SPEC_ID)
#undef BRUME_CPP_SPEC_ID
};
struct SpecKey {
    std::array<int32_t, 0
#define BRUME_CPP_SPEC_COUNT(name, id, value) +1
                        BRUME_SPEC_CONSTANTS(BRUME_CPP_SPEC_COUNT)
#undef BRUME_CPP_SPEC_COUNT
               >
        values{
#define BRUME_CPP_SPEC_DEFAULT(name, id, value) value,
            BRUME_SPEC_CONSTANTS(BRUME_CPP_SPEC_DEFAULT)
#undef BRUME_CPP_SPEC_DEFAULT
        };
    int32_t& operator[](SpecId id) { return values[static_cast<size_t>(id)]; }
    int32_t operator[](SpecId id) const { return values[static_cast<size_t>(id)]; }
    auto operator<=>(const SpecKey&) const = default;
    std::string text() const;  // "k0,k1,...": part of a pipeline's debug name
};

// key with every constant that none of `shaders` (embedded SPIR-V names, e.g. "geometry.frag")
// declares reset to its default: spirv-opt leaves in each module only the constants it reads, so keys
// that differ only in the others build one pipeline, not two (the editor's coarse and full frames differ
// in the froxel passes' shadow reduction, which the geometry pass does not read). The embedded SPIR-V's
// constants, also where BRUME_SPV_DIR replaces a shader.
SpecKey constantsReadBy(const SpecKey& key, std::initializer_list<const char*> shaders);

// A VkSpecializationInfo pointing into its own entries and the key's values (keep both alive).
struct Specialization {
    std::vector<VkSpecializationMapEntry> entries;
    VkSpecializationInfo info{};
    explicit Specialization(const SpecKey& key);
    Specialization(const Specialization&) = delete;
    Specialization& operator=(const Specialization&) = delete;
};

// name: a shader file name from shaders/, e.g. "voxelize.comp".
Result<ShaderModuleOwner> createShaderModule(const Device& device, const char* name);

// A compute pipeline of one shader variant.
struct ComputePass {
    PipelineOwner pipeline;
    std::string shader;  // the embedded SPIR-V's name, also the pipeline's debug name
};

// spec: the specialization constants' values; null = none given (the shader's defaults).
Result<ComputePass> createComputePass(const Device& device, VkPipelineLayout layout, const std::string& shader,
                                      const SpecKey* spec = nullptr);

// Pipelines to create at once before a frame records. Lavapipe compiles a pipeline on the thread that
// creates it (10-250 ms each), so a frame that needs several new ones (a scene's first frame, an edit
// that changes a key) waits for about their sum over the cores instead of their sum. Each job writes
// only its own result; the caches hand out a result only once it is made (PipelineCache::get).
class PipelineBatch {
public:
    // cost: any measure that grows with the job's compile time (the SPIR-V's size of its shaders): the
    // longest start first, so that no core is left with a long one at the end.
    void add(std::function<Result<void>()> job, size_t cost) { jobs_.push_back({std::move(job), cost}); }
    size_t size() const { return jobs_.size(); }
    // Runs every job, on up to one thread per core, and waits for them all; the first failed job's
    // error (in the order added), after every job has finished.
    Result<void> run();

private:
    struct Job {
        std::function<Result<void>()> create;
        size_t cost;
    };
    std::vector<Job> jobs_;
};

// One pipeline per shader variant and specialization key (the constants the shader reads:
// constantsReadBy), created on first use (lavapipe compiles a pipeline in 10-250 ms, so a variant a
// scene never needs is never built), or ahead of it in a batch with others (request).
class PipelineCache {
public:
    Result<const ComputePass*> get(const Device& device, VkPipelineLayout layout, const std::string& shader,
                                   const SpecKey* spec = nullptr);
    // Adds to `batch` the creation of the pipeline that get() with these arguments returns, unless it
    // exists or is already in a batch. Run the batch before the next get() or request().
    void request(const Device& device, VkPipelineLayout layout, const std::string& shader, const SpecKey* spec,
                 PipelineBatch& batch);
    // Whether get() with these arguments would return a pipeline made earlier, without compiling.
    bool has(const std::string& shader, const SpecKey* spec) const;
    size_t size() const { return passes_.size(); }

private:
    // By shader name, plus "#" and the key when specialized. An entry whose pipeline is null was
    // requested and not (yet, or successfully) made: get() makes it then.
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
