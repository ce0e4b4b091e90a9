// The live view's scene time: density textures scroll by scroll_mps x time (docs/vdb.md) and
// keyframed settings follow their keys (core/animate.h; the Timeline panel plays and scrubs it). View
// state, like the camera preset: not saved in the scene, not an undo step. Interactively it follows
// the wall clock while playing; under --script / --screenshot the clock is the frame count
// (1/24 s per frame) and play starts off, so screenshots stay reproducible.
#pragma once

#include "core/scene.h"

namespace brume::editor {

// The fixed step of the deterministic (scripted, screenshot) clock.
inline constexpr double kScriptedFrameSeconds = 1.0 / 24.0;

// Whether anything changes with time: a volume's density texture scrolls, or a setting carries
// keyframes (otherwise advancing time changes nothing and the view may rest and converge).
bool sceneScrolls(const Scene& scene);

class SceneTime {
public:
    explicit SceneTime(bool playing) : playing_(playing) {}
    double seconds() const { return seconds_; }
    bool playing() const { return playing_; }
    void set(double seconds) { seconds_ = seconds; }
    void play(bool on) { playing_ = on; }
    // Moves time on by dt [s] while playing and the scene scrolls.
    void advance(const Scene& scene, double dt) {
        if (playing_ && dt > 0.0 && sceneScrolls(scene)) seconds_ += dt;
    }

private:
    double seconds_ = 0.0;
    bool playing_;
};

}  // namespace brume::editor
