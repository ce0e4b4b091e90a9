// The measurement of `brume tradeoff` (docs/quality.md), shared by the command line and the
// editor's Quality panel (app/editor/quality_job.h) so both give the same numbers: the reference
// rendered once and cached by the scene's content, every candidate timed (median after warm-up) and
// compared with it. The renderer is a callback: the command line passes its RenderSession, the
// editor a renderer it creates on its worker thread. Progress and cancel are for either caller.
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/render.h"
#include "core/result.h"
#include "core/tradeoff.h"

namespace brume::measure {

// $XDG_CACHE_HOME/brume/references, else ~/.cache/brume/references, else .brume-cache/references.
std::string defaultCacheDir();

// The cache file of the reference of `scene` at width x height: named by a hash of the scene's
// content (its canonical JSON without the froxel settings, the image size, the reference's version
// and the bytes of every file it reads).
std::string referenceCachePath(const Scene& scene, int width, int height, const std::string& cacheDir);

struct ReferenceResult {
    Image image;
    bool cached = false;  // read from the cache, not rendered
    std::string path;     // its cache file
    std::string warning;  // set when a rendered reference could not be cached (the next run renders it again)
};

// The reference of `scene` at base's size: from the cache, else rendered with base's threads (with
// `progress`) and cached whole (temporary file, then rename). Once `cancel` is set, the render stops
// early and this returns an Error "cancelled" with nothing written to the cache.
Result<ReferenceResult> referenceImage(const Scene& scene, const RenderRequest& base, const std::string& cacheDir,
                                       const ProgressFn& progress = nullptr,
                                       const std::atomic<bool>* cancel = nullptr);

// One render of a candidate: the image after request.frames frames from a fresh history.
using CandidateRender = std::function<Result<Image>(const Scene& scene, const RenderRequest& request)>;

// What to measure: the presets x frames, then each grid (with base.quality's other settings) x frames.
struct TradeoffPlan {
    std::vector<Quality> qualities;
    std::vector<int> frames;
    std::vector<std::pair<int, int>> grids;  // (tile_px, slices)
    int repeats = 3;  // timed renders per candidate (the median is reported)
    int warmup = 1;   // untimed renders before them
};

// The plan of comma-separated presets ("low,medium") and frames ("1,4,16") and TILExSLICES grids,
// checked as `brume tradeoff` checks --quality, --frames and --grid: an Error (badInput) naming the
// option and the word. repeats and warmup are left at their defaults.
Result<TradeoffPlan> parsePlan(const std::string& qualities, const std::string& frames,
                               const std::vector<std::string>& grids = {});

// The candidates of `plan`, not yet measured; grids take `gridQuality` for the rest of the preset.
std::vector<TradeoffCandidate> plannedCandidates(const TradeoffPlan& plan, Quality gridQuality);

// The scene and request one candidate renders: temporal on, the grid override, its preset and frames.
std::pair<Scene, RenderRequest> candidateRender(const Scene& scene, const RenderRequest& base,
                                                const TradeoffCandidate& c);

// Times every candidate (the median wall time of `repeats` renders after `warmup`) and measures its
// last image against `reference`, then marks the Pareto front. `done(k)` after the k-th candidate.
// A render's error is returned as it is; a set `cancel` returns an Error "cancelled" between renders.
Result<void> measureCandidates(const Scene& scene, const RenderRequest& base, const Image& reference,
                               std::vector<TradeoffCandidate>& candidates, int warmup, int repeats,
                               const CandidateRender& render, const std::function<void(size_t done)>& done = nullptr,
                               const std::atomic<bool>* cancel = nullptr);

// The message of the Error a cancel returns.
inline constexpr const char* kCancelled = "cancelled";

}  // namespace brume::measure
