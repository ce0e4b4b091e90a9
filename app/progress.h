// Progress of long work on stderr: one line rewritten in place ("rendering (reference) 42%") when
// stderr is a terminal, a few plain lines (every 25%) when it is a file or a pipe, so that logs stay
// short. update() is called from renderer worker threads.
#pragma once

#include <mutex>
#include <string>

namespace brume::app {

class ProgressLine {
public:
    explicit ProgressLine(std::string label);
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

    std::mutex mutex_;
    std::string label_;
    bool terminal_;
    int shown_ = -1;  // last percent printed
    bool ended_ = false;
};

}  // namespace brume::app
