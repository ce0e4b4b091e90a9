// brume-editor --bench: every frame's wall time and, for frames that rendered, the renderer's
// per-pass GPU times and the window's present time; printed at exit as median and p95 per kind of
// frame (coarse while interacting, full at rest, UI only), skipping the first (it compiles shaders).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "gpu/timing.h"

namespace brume::editor {

class FrameStats {
public:
    // kind: "coarse", "rest" or "ui" (nothing rendered).
    void add(const std::string& kind, double frameMs, const std::vector<gpu::PassTiming>& passes, double presentMs);
    std::string report() const;

private:
    struct Samples {
        std::vector<double> frameMs;
        std::map<std::string, std::vector<double>> passMs;
        std::vector<std::string> passOrder;
    };
    int frames_ = 0;
    Samples all_;
    std::map<std::string, Samples> byKind_;
};

}  // namespace brume::editor
