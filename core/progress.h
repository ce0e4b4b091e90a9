// Thread-safe progress reporting for the CPU renderers (RenderRequest::progress).
#pragma once

#include <algorithm>
#include <atomic>
#include <mutex>

#include "render.h"

namespace brume {

// Reports progress over passes of work items, weighted by their item counts; calls the user's
// callback at most once per percent (the contract allows ~100 calls), from any worker thread, with
// values that never decrease.
class ProgressReporter {
public:
    ProgressReporter(const ProgressFn& fn, double totalItems) : fn_(fn), total_(std::max(totalItems, 1.0)) {}
    // Between passes only, when no worker is reporting.
    void finishedPass(double items) { base_ += items; }
    // `done` items of the current pass have finished.
    void report(int done) {
        if (!fn_) return;
        const int percent = std::min(static_cast<int>(100.0 * (base_ + done) / total_), 100);
        // Cheap early out; the decision and the call happen under the lock, so calls arrive in order.
        if (percent <= last_.load(std::memory_order_relaxed)) return;
        std::lock_guard<std::mutex> lock(mutex_);
        if (percent <= last_.load(std::memory_order_relaxed)) return;
        last_.store(percent, std::memory_order_relaxed);
        fn_(static_cast<float>(percent) * 0.01f);
    }

private:
    const ProgressFn& fn_;
    double total_;
    double base_ = 0.0;
    std::atomic<int> last_{-1};
    std::mutex mutex_;
};

}  // namespace brume
