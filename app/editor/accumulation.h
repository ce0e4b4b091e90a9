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
// preset at a fraction of the window's size, which the display pass upscales. At rest it renders the
// chosen preset at the window's size with the history restarted, so that it converges to
// `brume render --frames N` of the same scene, preset and size. maxScale 1 turns this off.
//
// The fraction adapts to the machine (settings::editor_frame_budget_ms): after each coarse frame the
// editor reports its wall time (measured()), and the next coarse frame's pixel count is scaled by
// budget / time (the per-pixel passes dominate a coarse frame), within [minScale(), maxScale], in
// steps of kScaleStep, with a dead band so that a steady drag keeps one size (each size change
// reallocates the renderer's images). The scale learnt is kept for the next drag. The froxel grid
// follows the image more slowly (coarseTilePx): its columns go with the square root of the scale,
// so the froxel passes (a fixed cost once the image is small) shrink too while the fog keeps more
// of its resolution than the image.
struct ViewPlan {
    bool coarse = false;
    Quality quality = Quality::Low;
    int width = 0;
    int height = 0;
    double scale = 1.0;           // of the window's size
    bool restartHistory = false;  // the first full frame after coarse ones
    bool moving = false;          // the document changed since the last frame, or a drag is under way
                                  // (coarse when maxScale < 1; full size otherwise)
    // A coarse frame of the same size as the previous frame: its time measures the scale (the first
    // frame of another size also reallocates the renderer's images).
    bool steady = false;
};

class Interaction {
public:
    static constexpr double kScaleStep = 1.0 / 40.0;  // 32 px of a 1280 px window
    // maxScale: settings::editor_interactive_scale; budgetMs: settings::editor_frame_budget_ms (0:
    // the scale stays at maxScale).
    explicit Interaction(double maxScale, double budgetMs = 0.0);
    // Called once per frame, before rendering, with the document's state.
    ViewPlan plan(uint64_t revision, bool grouping, Quality preset, int width, int height);
    // The plan of the next coarse frame, if an interaction began now (plan() is left as it is).
    ViewPlan coarsePlan(int width, int height) const;
    // The wall time of a frame that rendered a steady coarse plan (the whole frame: UI, render,
    // present): sets the scale of the next coarse frames.
    void measured(double frameMs);
    double scale() const { return scale_; }  // of the next coarse frame
    double maxScale() const { return maxScale_; }
    static double minScale();

private:
    double maxScale_;
    double budgetMs_;
    double scale_;
    bool seen_ = false;
    uint64_t revision_ = 0;
    bool lastCoarse_ = false;
    double lastScale_ = 0.0;
};

// The froxel tile [px] of a coarse frame rendered at `scale` of the window: the `low` preset's tile
// (lowTilePx, after the scene's overrides) times sqrt(scale / 0.5), so at scale 0.5 the grid is a
// half-size `low` frame's and its columns go with sqrt(scale) below that (at 0.1: 19 x 11 columns
// of a 1280x720 window instead of 8 x 5); at least 1 px.
int coarseTilePx(int lowTilePx, double scale);

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
