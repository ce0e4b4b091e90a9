#include "pipeline.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <new>
#include <mutex>
#include <optional>
#include <set>
#include <span>
#include <system_error>
#include <thread>
#include <vector>

#include "frame_resources.h"
#include "shaders/shared/bindings.h"
#include "shaders/shared/brume.h"
#include "spirv.h"
#include "vk_check.h"

namespace brume::gpu {

Result<DescriptorBindings> createDescriptorBindings(const Device& device) {
    std::array<VkDescriptorSetLayoutBinding, kBindingCount> bindings{};
    for (const BindingDecl& d : bindingTable()) {
        if (d.binding < 0) return Error{"Brume's GPU binding table has a gap; this build of brume is broken."};
        // Only the buffers and texel views reach the geometry pass: devices may allow as few as 4
        // storage images per graphics stage.
        const VkShaderStageFlags stages = d.computeOnly ? VK_SHADER_STAGE_COMPUTE_BIT
                                                  : VK_SHADER_STAGE_COMPUTE_BIT | VK_SHADER_STAGE_VERTEX_BIT |
                                                        VK_SHADER_STAGE_FRAGMENT_BIT;
        bindings[static_cast<size_t>(d.binding)] = {static_cast<uint32_t>(d.binding), d.type, 1, stages, nullptr};
    }
    // The push constants are the debug view's, the glow pass's or the temporal and integrate passes'
    // parameters; the other passes ignore them.
    return createDescriptorSet(device, bindings,
                               static_cast<uint32_t>(std::max({sizeof(shd::DebugViewParams), sizeof(shd::GlowParams),
                                                               sizeof(shd::FroxelRegionParams),
                                                               sizeof(shd::IntegrateParams)})),
                               "froxel");
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

    // The pool holds exactly the set's descriptors.
    std::map<VkDescriptorType, uint32_t> counts;
    for (const VkDescriptorSetLayoutBinding& binding : bindings) counts[binding.descriptorType] += binding.descriptorCount;
    std::vector<VkDescriptorPoolSize> sizes;
    for (const auto& [type, n] : counts) sizes.push_back({type, n});
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

// Points binding `binding` at a buffer, an image view or a texel buffer view.
VkWriteDescriptorSet descriptorWrite(VkDescriptorSet set, int binding, VkDescriptorType type,
                                     const VkDescriptorBufferInfo* buffer, const VkDescriptorImageInfo* image,
                                     const VkBufferView* texels = nullptr) {
    VkWriteDescriptorSet w = vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    w.dstSet = set;
    w.dstBinding = static_cast<uint32_t>(binding);
    w.descriptorCount = 1;
    w.descriptorType = type;
    w.pBufferInfo = buffer;
    w.pImageInfo = image;
    w.pTexelBufferView = texels;
    return w;
}

}  // namespace

void writeDescriptorBindings(const Device& device, VkDescriptorSet set, const FrameResources& r) {
    std::array<VkDescriptorBufferInfo, kBuffers.size()> bufferInfos{};
    std::array<VkDescriptorImageInfo, kImages.size()> imageInfos{};
    std::array<VkBufferView, kTexelViews.size()> texelViews{};
    std::vector<VkWriteDescriptorSet> writes;
    for (size_t i = 0; i < kBuffers.size(); ++i) {
        bufferInfos[i] = {r.buffers[i].buffer.get(), 0, VK_WHOLE_SIZE};
        writes.push_back(descriptorWrite(set, kBuffers[i].binding, descriptorType(kBuffers[i].kind), &bufferInfos[i], nullptr));
    }
    for (size_t i = 0; i < kImages.size(); ++i) {
        imageInfos[i] = {VK_NULL_HANDLE, r.images[i].view.get(), VK_IMAGE_LAYOUT_GENERAL};
        writes.push_back(descriptorWrite(set, kImages[i].binding, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, nullptr, &imageInfos[i]));
    }
    for (size_t i = 0; i < kTexelViews.size(); ++i) {
        texelViews[i] = r.texelViews[i].get();
        writes.push_back(descriptorWrite(set, kTexelViews[i].binding, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, nullptr,
                                         nullptr, &texelViews[i]));
    }
    vkUpdateDescriptorSets(device.vk(), static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);
}

void writeHistoryBindings(const Device& device, VkDescriptorSet set, const FrameResources& r, int writeIndex) {
    std::array<VkDescriptorImageInfo, 2 * kHistory.size()> infos{};
    std::array<VkWriteDescriptorSet, 2 * kHistory.size()> writes{};
    for (size_t i = 0; i < kHistory.size(); ++i) {
        const auto& pair = r.history[i];
        infos[2 * i] = {VK_NULL_HANDLE, pair[static_cast<size_t>(1 - writeIndex)].view.get(), VK_IMAGE_LAYOUT_GENERAL};
        infos[2 * i + 1] = {VK_NULL_HANDLE, pair[static_cast<size_t>(writeIndex)].view.get(), VK_IMAGE_LAYOUT_GENERAL};
        writes[2 * i] = descriptorWrite(set, kHistory[i].inBinding, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, nullptr, &infos[2 * i]);
        writes[2 * i + 1] =
            descriptorWrite(set, kHistory[i].outBinding, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, nullptr, &infos[2 * i + 1]);
    }
    vkUpdateDescriptorSets(device.vk(), static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);
}

namespace {

// Profiling aid (docs/performance.md "How to measure"): with BRUME_SPV_DIR set, a file DIR/NAME.spv
// replaces the embedded SPIR-V of shader NAME, so a pass can be timed with parts of its shader switched
// off without rebuilding brume. Said on stderr for every shader it replaces, so that no image is taken
// from a replaced shader unnoticed. Returns false where no replacement applies.
bool replacementSpirv(const char* name, std::vector<uint32_t>& words, std::string& problem) {
    const char* dir = std::getenv("BRUME_SPV_DIR");
    if (!dir || !*dir) return false;
    const std::filesystem::path path = std::filesystem::path(dir) / (std::string(name) + ".spv");
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return false;
    std::ifstream in(path, std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.good() && !in.eof()) {
        problem = path.string() + ": cannot read the replacement shader (BRUME_SPV_DIR).";
        return true;
    }
    if (bytes.empty() || bytes.size() % sizeof(uint32_t) != 0) {
        problem = path.string() + ": not SPIR-V (its size is not a whole number of 32-bit words).";
        return true;
    }
    words.resize(bytes.size() / sizeof(uint32_t));
    std::copy(bytes.begin(), bytes.end(), reinterpret_cast<char*>(words.data()));
    constexpr uint32_t kSpirvMagic = 0x07230203u;
    if (words[0] != kSpirvMagic) {
        problem = path.string() + ": not SPIR-V (it does not begin with SPIR-V's magic number).";
        return true;
    }
    std::fprintf(stderr, "brume: shader %s replaced by %s (BRUME_SPV_DIR)\n", name, path.string().c_str());
    return true;
}

}  // namespace

Result<ShaderModuleOwner> createShaderModule(const Device& device, const char* name) {
    std::span<const uint32_t> words = embeddedSpirv(name);
    std::vector<uint32_t> replaced;
    std::string problem;
    if (replacementSpirv(name, replaced, problem)) {
        if (!problem.empty()) return Error{problem};
        words = replaced;
    }
    if (words.empty()) return Error{std::string("The shader ") + name + " is missing from this build of brume."};
    VkShaderModuleCreateInfo info = vkStruct<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
    info.codeSize = words.size_bytes();
    info.pCode = words.data();
    VkShaderModule module = VK_NULL_HANDLE;
    BRUME_VK(vkCreateShaderModule(device.vk(), &info, nullptr, &module), std::string("load the shader ") + name);
    device.name(module, VK_OBJECT_TYPE_SHADER_MODULE, name);
    return ShaderModuleOwner(device.vk(), module);
}

namespace {

// Adds the SpecIds that a SPIR-V module decorates (OpDecorate <id> SpecId <n>) to ids.
void addSpecIds(std::span<const uint32_t> words, std::set<uint32_t>& ids) {
    constexpr uint32_t kOpDecorate = 71;
    constexpr uint32_t kDecorationSpecId = 1;
    constexpr size_t kHeaderWords = 5;
    for (size_t i = kHeaderWords; i < words.size();) {
        const uint32_t count = words[i] >> 16;
        const uint32_t op = words[i] & 0xFFFFu;
        if (count == 0 || i + count > words.size()) break;
        if (op == kOpDecorate && count >= 4 && words[i + 2] == kDecorationSpecId) ids.insert(words[i + 3]);
        i += count;
    }
}

// The SpecIds shader `name` declares, scanned once per shader (every frame asks for its passes' keys).
const std::set<uint32_t>& specIdsOf(const char* name) {
    static std::mutex mutex;
    static std::map<std::string, std::set<uint32_t>, std::less<>> scanned;
    std::lock_guard<std::mutex> lock(mutex);
    auto it = scanned.find(std::string_view(name));
    if (it == scanned.end()) {
        std::set<uint32_t> ids;
        addSpecIds(embeddedSpirv(name), ids);
        it = scanned.emplace(name, std::move(ids)).first;
    }
    return it->second;
}

}  // namespace

SpecKey constantsReadBy(const SpecKey& key, std::initializer_list<const char*> shaders) {
    std::set<uint32_t> ids;
    for (const char* s : shaders) {
        const std::set<uint32_t>& read = specIdsOf(s);
        ids.insert(read.begin(), read.end());
    }
    SpecKey out;
#define BRUME_CPP_SPEC_KEEP(name, id, value) \
    if (ids.count(id) != 0) out[SpecId::name] = key[SpecId::name];
    BRUME_SPEC_CONSTANTS(BRUME_CPP_SPEC_KEEP)
#undef BRUME_CPP_SPEC_KEEP
    return out;
}

std::string SpecKey::text() const {
    std::string t;
    for (size_t i = 0; i < values.size(); ++i) t += (i ? "," : "") + std::to_string(values[i]);
    return t;
}

Specialization::Specialization(const SpecKey& key) {
#define BRUME_CPP_SPEC_ENTRY(name, id, value)                                                                  \
    entries.push_back({static_cast<uint32_t>(id), static_cast<uint32_t>(sizeof(int32_t) * static_cast<size_t>(SpecId::name)), \
                       sizeof(int32_t)});
    BRUME_SPEC_CONSTANTS(BRUME_CPP_SPEC_ENTRY)
#undef BRUME_CPP_SPEC_ENTRY
    info.mapEntryCount = static_cast<uint32_t>(entries.size());
    info.pMapEntries = entries.data();
    info.dataSize = sizeof(key.values);
    info.pData = key.values.data();
}

Result<ComputePass> createComputePass(const Device& device, VkPipelineLayout layout, const std::string& shader,
                                      const SpecKey* spec) {
    Result<ShaderModuleOwner> module = createShaderModule(device, shader.c_str());
    if (!module) return module.error();
    VkComputePipelineCreateInfo info = vkStruct<VkComputePipelineCreateInfo>(VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO);
    info.stage = vkStruct<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO);
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module.value().get();
    info.stage.pName = "main";
    std::optional<Specialization> specialization;
    if (spec) info.stage.pSpecializationInfo = &specialization.emplace(*spec).info;
    info.layout = layout;
    VkPipeline pipeline = VK_NULL_HANDLE;
    BRUME_VK(vkCreateComputePipelines(device.vk(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline),
             "create the " + shader + " pipeline");
    device.name(pipeline, VK_OBJECT_TYPE_PIPELINE, spec ? shader + " [" + spec->text() + "]" : shader);
    ComputePass pass;
    pass.pipeline = PipelineOwner(device.vk(), pipeline);
    pass.shader = shader;
    return pass;
}

namespace {

// The cache's name for the pipeline of `shader` specialized by the constants of `spec` it reads.
std::pair<std::string, std::optional<SpecKey>> cacheKey(const std::string& shader, const SpecKey* spec) {
    // Keyed by the constants the shader reads: keys that differ only in others (the editor's coarse and
    // full frames) share a pipeline.
    std::optional<SpecKey> read;
    if (spec) read = constantsReadBy(*spec, {shader.c_str()});
    return {read ? shader + "#" + read->text() : shader, read};
}

}  // namespace

Result<void> PipelineBatch::run() {
    std::vector<Job> jobs = std::move(jobs_);
    jobs_.clear();
    if (jobs.empty()) return {};
    std::vector<size_t> order(jobs.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return jobs[a].cost > jobs[b].cost; });
    std::vector<std::optional<Error>> failed(jobs.size());
    std::atomic<size_t> next{0};
    auto work = [&] {
        for (size_t k = next++; k < order.size(); k = next++) {
            const size_t i = order[k];
            // An exception must not leave a helper thread (std::terminate): it becomes the job's error.
            try {
                if (Result<void> r = jobs[i].create(); !r) failed[i] = r.error();
            } catch (const std::bad_alloc&) {
                failed[i] = Error{"A shader pipeline could not be created: the host is out of memory."};
            } catch (const std::exception& e) {
                failed[i] = Error{std::string("A shader pipeline could not be created: ") + e.what() + "."};
            }
        }
    };
    const size_t threads = std::min<size_t>(jobs.size(), std::max(1u, std::thread::hardware_concurrency()));
    std::vector<std::thread> helpers;
    for (size_t t = 1; t < threads; ++t) {
        try {
            helpers.emplace_back(work);
        } catch (const std::system_error&) {
            break;  // no thread to spare: this one takes the jobs the helper would have
        }
    }
    work();
    for (std::thread& h : helpers) h.join();
    for (std::optional<Error>& e : failed)
        if (e) return std::move(*e);
    return {};
}

Result<const ComputePass*> PipelineCache::get(const Device& device, VkPipelineLayout layout, const std::string& shader,
                                              const SpecKey* spec) {
    auto [key, read] = cacheKey(shader, spec);
    auto it = passes_.find(key);
    if (it != passes_.end() && it->second.pipeline) return &it->second;
    Result<ComputePass> p = createComputePass(device, layout, shader, read ? &*read : nullptr);
    if (!p) return p.error();
    if (it == passes_.end()) it = passes_.emplace(key, ComputePass{}).first;
    it->second = std::move(p.value());
    return &it->second;
}

bool PipelineCache::has(const std::string& shader, const SpecKey* spec) const {
    const auto it = passes_.find(cacheKey(shader, spec).first);
    return it != passes_.end() && it->second.pipeline;
}

void PipelineCache::request(const Device& device, VkPipelineLayout layout, const std::string& shader,
                            const SpecKey* spec, PipelineBatch& batch) {
    auto [key, read] = cacheKey(shader, spec);
    auto [it, added] = passes_.emplace(key, ComputePass{});
    if (!added) return;  // made, or requested by an earlier batch that failed: get() reports why
    // The entry's address stays put while the batch runs (std::map), and only this job writes it.
    ComputePass* out = &it->second;
    batch.add(
        [&device, layout, shader, read = std::move(read), out]() -> Result<void> {
            Result<ComputePass> p = createComputePass(device, layout, shader, read ? &*read : nullptr);
            if (!p) return p.error();
            *out = std::move(p.value());
            return {};
        },
        embeddedSpirv(shader).size());
}

void bindComputePass(VkCommandBuffer cmd, const ComputePass& pass, const DescriptorBindings& bindings) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pass.pipeline.get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, bindings.pipelineLayout.get(), 0, 1, &bindings.set,
                            0, nullptr);
}

void layoutBarrier(VkCommandBuffer cmd, std::span<const LayoutChange> images, VkPipelineStageFlags srcStage,
                   VkAccessFlags srcAccess, VkPipelineStageFlags dstStage, VkAccessFlags dstAccess) {
    if (images.empty()) return;
    std::vector<VkImageMemoryBarrier> barriers;
    for (const LayoutChange& c : images) {
        VkImageMemoryBarrier b = vkStruct<VkImageMemoryBarrier>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER);
        b.srcAccessMask = srcAccess;
        b.dstAccessMask = dstAccess;
        b.oldLayout = c.from;
        b.newLayout = c.to;
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = c.image;
        b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        barriers.push_back(b);
    }
    vkCmdPipelineBarrier(cmd, srcStage, dstStage, 0, 0, nullptr, 0, nullptr, static_cast<uint32_t>(barriers.size()),
                         barriers.data());
}

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags src, VkAccessFlags srcAccess, VkPipelineStageFlags dst,
                   VkAccessFlags dstAccess) {
    VkMemoryBarrier b = vkStruct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
    b.srcAccessMask = srcAccess;
    b.dstAccessMask = dstAccess;
    vkCmdPipelineBarrier(cmd, src, dst, 0, 1, &b, 0, nullptr, 0, nullptr);
}

}  // namespace brume::gpu
