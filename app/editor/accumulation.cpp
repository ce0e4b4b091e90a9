#include "accumulation.h"

#include <algorithm>
#include <cmath>

#include "shaders/shared/brume.h"

namespace brume::editor {

int convergedFrames(const Scene& scene) {
    const float w = scene.temporal.enabled ? scene.temporal.history_weight : 0.0f;
    if (w <= 0.0f) return 1;
    // The first frame's share of what the view shows, under the renderer's own rule at rest
    // (shd::temporalRestWeight: a progressive mean of n frames, share 1/n, up to its cap, then the
    // exponential blend w). history_weight <= 0.99 (core/settings.h) needs 211 frames; 64 keeps a
    // weight-0.99 scene from churning for minutes on a CPU device.
    constexpr int kMaxFrames = 64;
    double share = 1.0;
    int n = 1;
    while (share >= 0.05 && n < kMaxFrames) {
        share *= shd::temporalRestWeight(n, w);  // frame n + 1 over a history of n rest frames
        ++n;
    }
    return n;
}

ViewPlan Interaction::plan(uint64_t revision, bool grouping, Quality preset, int width, int height) {
    const bool changed = seen_ && revision != revision_;
    seen_ = true;
    revision_ = revision;
    ViewPlan p;
    p.coarse = scale_ < 1.0 && (grouping || changed);
    p.quality = p.coarse ? Quality::Low : preset;
    const double s = p.coarse ? scale_ : 1.0;
    p.width = std::max(1, static_cast<int>(std::lround(width * s)));
    p.height = std::max(1, static_cast<int>(std::lround(height * s)));
    p.restartHistory = lastCoarse_ && !p.coarse;
    lastCoarse_ = p.coarse;
    return p;
}

bool Accumulation::wantsFrame(const ViewKey& key, const Scene& scene, bool force) const {
    if (force || !(key == key_)) return true;
    return frames_ < convergedFrames(scene);
}

void Accumulation::rendered(const ViewKey& key) {
    frames_ = key == key_ ? frames_ + 1 : 1;
    key_ = key;
}

}  // namespace brume::editor
