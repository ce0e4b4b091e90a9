// brume-editor --bench: every frame's wall time and, for frames that rendered, the renderer's
// per-pass GPU times and the window's present time; printed at exit as median, p95 and the slowest
// frame per kind of frame (coarse while interacting, full at rest, UI only), skipping the first (it
// compiles shaders); also the coarse frames' scale and how long the view took to settle after an interaction.
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
    // The scale of the window a coarse frame rendered at (Interaction, accumulation.h).
    void addCoarseScale(double scale);
    // From the start of the last coarse frame of an interaction (the frame of its last edit) to the
    // end of the first full-preset frame after it: when the view shows the preset again.
    void addSettle(double ms);
    // The frame last added made pipelines in its render (gpu::GpuRender::compiled): a hitch that a
    // fallback or a stand-in should have avoided. Not counted for the first frame.
    void addCompiled();
    std::string report() const;

private:
    struct Samples {
        std::vector<double> frameMs;
        std::vector<int> frame;  // each sample's frame number, counted from 1
        std::map<std::string, std::vector<double>> passMs;
        std::vector<std::string> passOrder;
    };
    int frames_ = 0;
    std::vector<double> scales_;
    std::vector<double> settleMs_;
    std::vector<int> compiled_;  // frame numbers
    Samples all_;
    std::map<std::string, Samples> byKind_;
};

}  // namespace brume::editor
