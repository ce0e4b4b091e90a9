#include "sequence.h"

#include <charconv>
#include <cmath>

namespace brume {

namespace {

std::optional<int> parseFrame(std::string_view s) {
    if (s.empty() || s.size() > 7) return std::nullopt;
    int v = 0;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    if (r.ec != std::errc() || r.ptr != s.data() + s.size() || v < 0) return std::nullopt;
    return v;
}

}  // namespace

std::optional<FrameRange> parseFrameRange(std::string_view text) {
    const size_t dash = text.find('-');
    if (dash == std::string_view::npos) return std::nullopt;
    const std::optional<int> a = parseFrame(text.substr(0, dash));
    const std::optional<int> b = parseFrame(text.substr(dash + 1));
    if (!a || !b || *a > *b || *b > kMaxSequenceFrame) return std::nullopt;
    return FrameRange{*a, *b};
}

int temporalWarmupFrames(const Temporal& t) {
    const double w = t.history_weight;
    if (!t.enabled || !(w > 0.0)) return 0;
    constexpr double kResidual = 0.01;
    return static_cast<int>(std::ceil(std::log(kResidual) / std::log(w)));
}

int temporalBlockFrames(const Temporal& t) {
    const int w = temporalWarmupFrames(t);
    return w == 0 ? 1 : 4 * w;
}

int historyChainStart(int frame, const Temporal& t) {
    const int k = temporalBlockFrames(t);
    return (frame / k) * k - temporalWarmupFrames(t);
}

}  // namespace brume
