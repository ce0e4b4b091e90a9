// When the editor's loop may sleep until the next event instead of drawing another frame.
//
// The loop draws a frame (input, UI, render when the view changed, present) and then polls again.
// With nothing to do (the view converged, no script step due, time paused, no background job) that
// loop redrew the same UI without end: ~1.2 of this machine's 2 cores while the editor sat idle,
// taken from every other program and from the Quality panel's own renderer. FramePacer says after
// each frame how long glfwWaitEventsTimeout may sleep before the next: 0 while something moves, then,
// after a few quiet frames (ImGui needs a frame or two to settle hover and focus after an input), up
// to kIdleWaitSeconds, so that clocks (autosave, notifications, a text cursor) still advance.
#pragma once

namespace brume::editor {

// What the loop knows at the end of a frame.
struct FrameActivity {
    bool rendered = false;       // the renderer drew this frame (an edit, a camera move, accumulation)
    bool scriptStepDue = false;  // a script has lines left and no `wait` pending
    double scriptWaitLeft = -1.0;  // seconds until a pending script `wait` ends; < 0: none
    bool playing = false;        // scene time runs and something follows it (sceneScrolls)
    bool jobRunning = false;     // a background job (the Quality panel's) runs: its progress is redrawn
    bool fixedFrames = false;    // --frames N: every frame counts, none is skipped
    bool woken = false;          // the previous sleep ended early: an event (input, resize) arrived
};

class FramePacer {
public:
    // Frames drawn after the last activity before the loop sleeps.
    static constexpr int kSettleFrames = 3;
    // The longest sleep [s]: the idle editor draws ~2 frames a second.
    static constexpr double kIdleWaitSeconds = 0.5;
    // The sleep while a background job runs [s]: its progress shows 10 times a second, and the job
    // keeps the cores the loop would have spent redrawing the same panel.
    static constexpr double kProgressWaitSeconds = 0.1;

    // Seconds the loop may sleep before the next frame (0: poll and draw at once).
    double next(const FrameActivity& a) {
        if (a.rendered || a.scriptStepDue || a.playing || a.fixedFrames || a.woken) {
            quietFrames_ = 0;
            return 0.0;
        }
        if (++quietFrames_ < kSettleFrames) return 0.0;
        const double wait = a.jobRunning ? kProgressWaitSeconds : kIdleWaitSeconds;
        return a.scriptWaitLeft >= 0.0 && a.scriptWaitLeft < wait ? a.scriptWaitLeft : wait;
    }

private:
    int quietFrames_ = 0;
};

}  // namespace brume::editor
