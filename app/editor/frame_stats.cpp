#include "frame_stats.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace brume::editor {
namespace {

// Nearest-rank percentile (p in [0, 1]) of a copy of `v`; 0 when empty.
double percentile(std::vector<double> v, double p) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const size_t rank = static_cast<size_t>(std::ceil(p * static_cast<double>(v.size())));
    return v[std::clamp<size_t>(rank, 1, v.size()) - 1];
}

// The median and p95, and the slowest frame with its number (counted from 1, the first included):
// a hitch, such as a pipeline compiled mid-drag, shows there rather than in the median.
std::string line(const char* label, const std::vector<double>& ms, const std::vector<int>& frame) {
    char buf[200];
    const size_t slowest = static_cast<size_t>(std::max_element(ms.begin(), ms.end()) - ms.begin());
    std::snprintf(buf, sizeof buf, "%-7s %4zu frames: median %8.1f ms, p95 %8.1f ms, max %8.1f ms (frame %d)", label,
                  ms.size(), percentile(ms, 0.5), percentile(ms, 0.95), ms.empty() ? 0.0 : ms[slowest],
                  ms.empty() ? 0 : frame[slowest]);
    return buf;
}

}  // namespace

void FrameStats::add(const std::string& kind, double frameMs, const std::vector<gpu::PassTiming>& passes,
                     double presentMs) {
    if (++frames_ == 1) return;  // the first frame also compiles the shaders
    for (Samples* s : {&all_, &byKind_[kind]}) {
        s->frameMs.push_back(frameMs);
        s->frame.push_back(frames_);
        auto put = [s](const std::string& name, double ms) {
            if (ms < 0.0) return;
            if (!s->passMs.count(name)) s->passOrder.push_back(name);
            s->passMs[name].push_back(ms);
        };
        for (const gpu::PassTiming& p : passes) put(p.name, p.gpuMs);
        put("present", presentMs);
    }
}

void FrameStats::addCoarseScale(double scale) { scales_.push_back(scale); }
void FrameStats::addSettle(double ms) { settleMs_.push_back(ms); }
void FrameStats::addCompiled() {
    if (frames_ > 1) compiled_.push_back(frames_);
}

std::string FrameStats::report() const {
    std::string out = "bench: frame wall time (frames after the first)\n  " + line("all", all_.frameMs, all_.frame) + "\n";
    for (const auto& [kind, s] : byKind_) {
        out += "  " + line(kind.c_str(), s.frameMs, s.frame) + "\n";
        if (s.passOrder.empty()) continue;
        out += "    median ms:";
        for (const std::string& name : s.passOrder) {
            char buf[96];
            std::snprintf(buf, sizeof buf, " %s %.1f,", name.c_str(), percentile(s.passMs.at(name), 0.5));
            out += buf;
        }
        out.back() = '\n';
    }
    if (!scales_.empty()) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "  coarse scale: first %.3f, last %.3f, median %.3f of the window\n", scales_.front(),
                      scales_.back(), percentile(scales_, 0.5));
        out += buf;
    }
    if (!settleMs_.empty()) {
        char buf[200];
        std::snprintf(buf, sizeof buf, "  settle  %4zu times: median %8.1f ms, max %8.1f ms (last edit to the first full-preset frame)\n",
                      settleMs_.size(), percentile(settleMs_, 0.5), percentile(settleMs_, 1.0));
        out += buf;
    }
    out += "  compiled " + std::to_string(compiled_.size()) + " frames (pipelines made in the frame's render)";
    for (size_t i = 0; i < compiled_.size(); ++i) out += (i == 0 ? ": " : ", ") + std::to_string(compiled_[i]);
    out += "\n";
    return out;
}

}  // namespace brume::editor
