// Progress of long work on stderr: one line rewritten in place ("rendering (reference) 42%") when
// stderr is a terminal, a few plain lines (every 25%) when it is a file or a pipe, so that logs stay
// short. update() is called from renderer worker threads.
#pragma once

#include <chrono>
#include <mutex>
#include <string>

namespace brume::app {

class ProgressLine {
public:
    // eta: also show the time left, extrapolated from the time so far (for work of a minute or more).
    explicit ProgressLine(std::string label, bool eta = false);
    ProgressLine(const ProgressLine&) = delete;
    ProgressLine& operator=(const ProgressLine&) = delete;
    ~ProgressLine();

    void update(float fraction);
    // Shows 100% and ends the line (success).
    void complete();
    // Ends a terminal line without claiming completion (failure); idempotent.
    void end();

private:
    void show(int percent);
    std::string etaText(int percent) const;

    std::mutex mutex_;
    std::string label_;
    bool terminal_;
    bool eta_;
    std::chrono::steady_clock::time_point start_;
    int shown_ = -1;  // last percent printed
    bool ended_ = false;
};

}  // namespace brume::app
