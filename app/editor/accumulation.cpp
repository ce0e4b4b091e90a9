#include "accumulation.h"

#include <algorithm>
#include <cmath>

namespace brume::editor {

int convergedFrames(const Scene& scene) {
    const double w = scene.temporal.enabled ? static_cast<double>(scene.temporal.history_weight) : 0.0;
    if (w <= 0.0) return 1;
    // w^n < 0.05; history_weight <= 0.99 (core/settings.h) caps this at 299 frames, 64 keeps a
    // weight-0.99 scene from churning for minutes on a CPU device.
    const double n = std::ceil(std::log(0.05) / std::log(w));
    return std::clamp(static_cast<int>(n), 1, 64);
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
