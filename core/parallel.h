// Minimal parallel loop over rows or tiles: the renderers split work into independent items.
#pragma once

#include <algorithm>
#include <atomic>
#include <functional>
#include <thread>
#include <vector>

namespace brume {

inline int defaultThreadCount() { return std::max(1u, std::thread::hardware_concurrency()); }

// Calls fn(i) for every i in [0, count) on `threads` threads (0 = all cores), handing out items
// dynamically. `done` (optional) is called from the worker that finished an item, with the number
// of items finished so far; it must be thread-safe.
inline void parallelFor(int count, int threads, const std::function<void(int)>& fn,
                        const std::function<void(int)>& done = nullptr) {
    const int n = std::max(1, std::min(threads > 0 ? threads : defaultThreadCount(), count));
    std::atomic<int> next{0}, finished{0};
    auto worker = [&] {
        for (int i = next++; i < count; i = next++) {
            fn(i);
            const int f = ++finished;
            if (done) done(f);
        }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < n; ++t) pool.emplace_back(worker);
    worker();
    for (std::thread& t : pool) t.join();
}

}  // namespace brume
