#include "progress.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <unistd.h>

namespace brume::app {

// Plain (non-terminal) output prints only at these steps: 4 lines per render at most.
static constexpr int kPlainStep = 25;

ProgressLine::ProgressLine(std::string label, bool eta)
    : label_(std::move(label)), terminal_(isatty(STDERR_FILENO) == 1), eta_(eta), start_(std::chrono::steady_clock::now()) {}

std::string ProgressLine::etaText(int percent) const {
    if (!eta_ || percent <= 0 || percent >= 100) return "";
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double left = elapsed * (100.0 - percent) / percent;
    char buf[64];
    if (left < 90.0)
        std::snprintf(buf, sizeof(buf), ", about %.0f s left", left);
    else
        std::snprintf(buf, sizeof(buf), ", about %.0f min left", left / 60.0);
    return buf;
}

ProgressLine::~ProgressLine() { end(); }

void ProgressLine::show(int percent) {
    if (terminal_) {
        // Padded: a shorter ETA must not leave the end of a longer one on screen.
        std::fprintf(stderr, "\r%s %3d%%%-24s", label_.c_str(), percent, etaText(percent).c_str());
    } else {
        std::fprintf(stderr, "%s %d%%%s\n", label_.c_str(), percent, etaText(percent).c_str());
    }
    std::fflush(stderr);
    shown_ = percent;
}

void ProgressLine::update(float fraction) {
    if (!std::isfinite(fraction)) return;
    const int percent = std::clamp(static_cast<int>(fraction * 100.0f), 0, 100);
    std::lock_guard lock(mutex_);
    if (ended_ || percent <= shown_) return;
    if (terminal_ || percent / kPlainStep > std::max(shown_, 0) / kPlainStep) {
        show(terminal_ ? percent : percent / kPlainStep * kPlainStep);
    }
}

void ProgressLine::complete() {
    std::lock_guard lock(mutex_);
    if (ended_) return;
    if (shown_ < 100) show(100);
    if (terminal_) std::fputc('\n', stderr);
    ended_ = true;
}

void ProgressLine::end() {
    std::lock_guard lock(mutex_);
    if (ended_) return;
    if (terminal_ && shown_ >= 0) std::fputc('\n', stderr);
    ended_ = true;
}

}  // namespace brume::app
