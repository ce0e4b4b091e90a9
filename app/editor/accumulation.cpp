#include "accumulation.h"

#include <algorithm>
#include <cmath>

#include "core/settings.h"
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

Interaction::Interaction(double maxScale, double budgetMs)
    : maxScale_(std::clamp(maxScale, minScale(), 1.0)), budgetMs_(std::max(budgetMs, 0.0)), scale_(maxScale_) {}

double Interaction::minScale() { return settings::editor_interactive_scale.min; }

ViewPlan Interaction::plan(uint64_t revision, bool grouping, Quality preset, int width, int height) {
    const bool changed = seen_ && revision != revision_;
    seen_ = true;
    revision_ = revision;
    ViewPlan p;
    p.coarse = maxScale_ < 1.0 && (grouping || changed);
    if (p.coarse) {
        p = coarsePlan(width, height);
    } else {
        p.quality = preset;
        p.width = std::max(1, width);
        p.height = std::max(1, height);
    }
    p.moving = grouping || changed;
    p.restartHistory = lastCoarse_ && !p.coarse;
    p.steady = p.coarse && lastCoarse_ && p.scale == lastScale_;
    lastCoarse_ = p.coarse;
    lastScale_ = p.scale;
    return p;
}

ViewPlan Interaction::coarsePlan(int width, int height) const {
    ViewPlan p;
    p.coarse = true;
    p.quality = Quality::Low;
    p.scale = scale_;
    p.width = std::max(1, static_cast<int>(std::lround(width * p.scale)));
    p.height = std::max(1, static_cast<int>(std::lround(height * p.scale)));
    return p;
}

void Interaction::measured(double frameMs) {
    if (budgetMs_ <= 0.0 || !(frameMs > 0.0) || !std::isfinite(frameMs)) return;
    // Dead band: a frame between 60% and 100% of the budget keeps its size.
    if (frameMs <= budgetMs_ && frameMs >= 0.6 * budgetMs_) return;
    // Pixels follow budget / time (aiming at 80% of the budget), at most halved or doubled a frame.
    const double pixels = std::clamp(0.8 * budgetMs_ / frameMs, 0.5, 2.0);
    double s = scale_ * std::sqrt(pixels);
    s = std::round(s / kScaleStep) * kScaleStep;
    scale_ = std::clamp(s, minScale(), maxScale_);
}

int coarseTilePx(int lowTilePx, double scale) {
    return std::max(1, static_cast<int>(std::lround(lowTilePx * std::sqrt(scale / 0.5))));
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
