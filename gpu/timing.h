// Per-pass GPU time from timestamp queries, with a debug label around each pass.
//
// Each pass writes its start timestamp BEFORE the barrier that waits for the previous pass: on
// lavapipe a timestamp written after a barrier can read earlier than the barrier's wait. With
// bottom-of-pipe timestamps the start of pass i is then the end of pass i-1, so the passes' times
// add up to the whole command buffer, which tests cross-check with the wall clock.
#pragma once

#include <string>
#include <vector>

#include "device.h"
#include "vk_owner.h"

namespace brume::gpu {

struct PassTiming {
    std::string name;
    double gpuMs = -1.0;  // -1 when the device cannot write timestamps
};

class PassTimer {
public:
    static Result<PassTimer> create(const Device& device, uint32_t maxPasses);

    void reset(VkCommandBuffer cmd);  // once per command buffer, before the first begin()
    void begin(VkCommandBuffer cmd, const char* name);
    void end(VkCommandBuffer cmd);
    // After the command buffer has completed.
    Result<std::vector<PassTiming>> read() const;

private:
    const Device* device_ = nullptr;
    QueryPoolOwner pool_;
    uint32_t maxPasses_ = 0;
    std::vector<std::string> names_;
};

}  // namespace brume::gpu
