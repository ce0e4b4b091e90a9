#include "timing.h"

#include "vk_check.h"

namespace brume::gpu {

Result<PassTimer> PassTimer::create(const Device& device, uint32_t maxPasses) {
    PassTimer t;
    t.device_ = &device;
    t.maxPasses_ = maxPasses;
    if (device.timestampPeriodNs() <= 0.0) return t;
    VkQueryPoolCreateInfo info = vkStruct<VkQueryPoolCreateInfo>(VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO);
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = 2 * maxPasses;
    VkQueryPool pool = VK_NULL_HANDLE;
    BRUME_VK(vkCreateQueryPool(device.vk(), &info, nullptr, &pool), "create the timestamp query pool");
    t.pool_ = QueryPoolOwner(device.vk(), pool);
    device.name(pool, VK_OBJECT_TYPE_QUERY_POOL, "pass timestamps");
    return t;
}

void PassTimer::reset(VkCommandBuffer cmd) {
    names_.clear();
    if (pool_) vkCmdResetQueryPool(cmd, pool_.get(), 0, 2 * maxPasses_);
}

void PassTimer::begin(VkCommandBuffer cmd, const char* name) {
    const auto i = static_cast<uint32_t>(names_.size());
    names_.emplace_back(name);
    device_->beginLabel(cmd, name);
    if (pool_ && i < maxPasses_) vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_.get(), 2 * i);
}

void PassTimer::end(VkCommandBuffer cmd) {
    const auto i = static_cast<uint32_t>(names_.size() - 1);
    if (pool_ && i < maxPasses_) vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_.get(), 2 * i + 1);
    device_->endLabel(cmd);
}

Result<std::vector<PassTiming>> PassTimer::read() const {
    std::vector<PassTiming> out;
    for (const std::string& n : names_) out.push_back({n, -1.0});
    if (!pool_ || names_.empty()) return out;
    const auto n = static_cast<uint32_t>(std::min<size_t>(names_.size(), maxPasses_));
    std::vector<uint64_t> ticks(2 * n);
    BRUME_VK(vkGetQueryPoolResults(device_->vk(), pool_.get(), 0, 2 * n, ticks.size() * sizeof(uint64_t),
                                   ticks.data(), sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
             "read the pass timestamps");
    const uint32_t bits = device_->timestampValidBits();
    const uint64_t mask = bits >= 64 ? ~0ull : (1ull << bits) - 1;
    for (uint32_t i = 0; i < n; ++i) {
        const uint64_t dt = (ticks[2 * i + 1] - ticks[2 * i]) & mask;  // wraps like the counter
        out[i].gpuMs = static_cast<double>(dt) * device_->timestampPeriodNs() * 1e-6;
    }
    return out;
}

}  // namespace brume::gpu
