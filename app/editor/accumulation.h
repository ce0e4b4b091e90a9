// When the viewport re-renders. While the view rests (same document revision, preset and size) the
// editor keeps rendering with the GPU history carried on (HistoryMode::Continue), so temporal
// accumulation converges on screen, and stops once it has: after convergedFrames() frames the
// first frame's share of the view is below 5%, and more frames only trade flicker for flicker.
// Any change starts the count again; the renderer itself decides whether its history survives it
// (temporalSceneKey drops it on media, light, grid or temporal edits; camera moves reproject it).
#pragma once

#include <cstdint>

#include "core/quality.h"
#include "core/scene.h"

namespace brume::editor {

// What the viewport shows; a different key is a change.
struct ViewKey {
    uint64_t revision = ~uint64_t(0);
    Quality quality = Quality::Low;
    int width = 0;
    int height = 0;
    int debugView = 0;  // DebugViewState (debug_view.h): another slice is another image
    int debugSlice = 0;
    // Scene time (scene_time.h): a moving time restarts the count, so the view keeps rendering while
    // a texture scrolls; the GPU history is kept and its neighbourhood clamp follows the drift.
    double time = 0.0;
    bool operator==(const ViewKey&) const = default;
};

// Frames after which the view keeps less than 5% of its first frame, under the renderer's blend at
// rest (a progressive mean, then the exponential blend with weight `temporal.history_weight`:
// shd::temporalRestWeight); 1 when temporal is off: every frame would be the same.
int convergedFrames(const Scene& scene);

// Scale while interacting, as DCC viewports do. While the user interacts (a begin ... end group is
// open: a gizmo or camera drag, a fly, an inspector slider; or the document changed since the
// previous frame: a wheel zoom, a script's action) the viewport renders a coarse frame: the `low`
// preset at `scale` of the window's size, which the display pass upscales. At rest it renders the
// chosen preset at the window's size with the history restarted, so that it converges to
// `brume render --frames N` of the same scene, preset and size. scale 1 turns this off.
struct ViewPlan {
    bool coarse = false;
    Quality quality = Quality::Low;
    int width = 0;
    int height = 0;
    bool restartHistory = false;  // the first full frame after coarse ones
};

class Interaction {
public:
    explicit Interaction(double scale) : scale_(scale) {}
    // Called once per frame, before rendering, with the document's state.
    ViewPlan plan(uint64_t revision, bool grouping, Quality preset, int width, int height);
    double scale() const { return scale_; }

private:
    double scale_;
    bool seen_ = false;
    uint64_t revision_ = 0;
    bool lastCoarse_ = false;
};

class Accumulation {
public:
    // Whether the next frame should be rendered (`force`: always, as --frames does to time frames).
    bool wantsFrame(const ViewKey& key, const Scene& scene, bool force) const;
    // Records a rendered frame of `key`.
    void rendered(const ViewKey& key);
    // Frames rendered since the last change (the one the viewport shows counts).
    int frames() const { return frames_; }

private:
    ViewKey key_;
    int frames_ = 0;
};

}  // namespace brume::editor
