// The Quality panel's measurement (docs/quality.md, "The editor's Quality panel"): `brume tradeoff`
// on the current view, run on a worker thread so the editor stays responsive. The numbers come from
// the same code as the command line (app/tradeoff_measure.h); this adds the thread, the progress the
// panel shows (the reference's fraction and ETA, candidate k of n) and cancel, and the error heat
// map: the image the viewport converges to against the same cached reference.
//
// Threads: start() launches one worker; progress() and result() copy under a lock, from any thread.
// The worker makes its renderer itself (a GPU renderer is created, used and destroyed there).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "app/tradeoff_measure.h"
#include "core/scene.h"
#include "core/tradeoff.h"

namespace brume::editor {

struct QualityJobSpec {
    Scene scene;  // the view's scene: the editor's camera, hidden volumes left out, at the view's time
    int width = 0;
    int height = 0;
    measure::TradeoffPlan plan;  // no qualities and no grids: the heat map only
    std::string cacheDir;        // empty: measure::defaultCacheDir()
    int threads = 0;             // the reference's threads (0 = every core)
    bool heatMap = true;         // also the heat map of heatQuality after heatFrames frames
    Quality heatQuality = Quality::Medium;
    int heatFrames = 1;
};

enum class JobPhase { Idle, Reference, Candidates, HeatMap, Done, Cancelled, Failed };

struct JobProgress {
    JobPhase phase = JobPhase::Idle;
    float referenceFraction = 0.0f;
    double referenceEtaSeconds = -1.0;  // < 0: not known yet
    bool referenceCached = false;
    size_t candidatesDone = 0;
    size_t candidates = 0;
};

struct JobResult {
    int width = 0;
    int height = 0;
    std::vector<TradeoffCandidate> candidates;  // measured, Pareto front marked (empty for a heat map only)
    bool hasHeatMap = false;
    ErrorMap heatMap;
    Quality heatQuality = Quality::Medium;
    int heatFrames = 1;
    std::string referencePath;
    std::string message;  // why it failed, or a warning (the reference could not be cached)
};

// Makes the candidates' renderer, on the worker thread.
using RendererFactory = std::function<Result<measure::CandidateRender>()>;
// The CPU froxel renderer on `threads` threads (0 = every core).
RendererFactory cpuRendererFactory(int threads);

class QualityJob {
public:
    QualityJob() = default;
    ~QualityJob();  // cancels and joins
    QualityJob(const QualityJob&) = delete;
    QualityJob& operator=(const QualityJob&) = delete;

    // Starts measuring `spec` (a running job is cancelled and joined first).
    void start(QualityJobSpec spec, RendererFactory factory);
    // Asks the worker to stop at its next check (a reference row, a render); returns at once.
    void cancel();
    // Blocks until the worker has finished (tests).
    void wait();
    bool running() const { return running_.load(); }
    JobProgress progress() const;
    // The last finished job's result (Done, Cancelled or Failed keep the previous numbers, with
    // message set); `generation` grows with every finished job, so a panel sees new results.
    JobResult result() const;
    uint64_t generation() const { return generation_.load(); }

private:
    void work(QualityJobSpec spec, RendererFactory factory);
    void finish(JobPhase phase, JobResult* result, std::string message);

    std::thread thread_;
    std::atomic<bool> cancel_{false};
    std::atomic<bool> running_{false};
    std::atomic<uint64_t> generation_{0};
    mutable std::mutex mutex_;
    JobProgress progress_;
    JobResult result_;
};

const char* phaseName(JobPhase phase);

// What a measurement was taken of: the view's scene (its render block aside: applying a candidate
// does not make the numbers stale) and the viewport's preset (the heat map's image). Another view
// (an edit, a camera move, another scene time or preset) makes its numbers stale.
struct MeasuredView {
    bool valid = false;
    Scene scene;
    Quality quality = Quality::Low;
    bool operator==(const MeasuredView&) const = default;
};

// The Quality panel's state, held by the Editor so that actions (`tradeoff ...`) reach it.
struct QualityTool {
    QualityJob job;
    bool show = false;
    int divisor = 4;  // the measured size: the view's size divided by this (1, 2 or 4)
    bool cpu = false;  // time the CPU froxel renderer instead of the GPU
    std::string qualities = "low,medium,high,ultra";  // the plan, as `brume tradeoff --quality/--frames`
    std::string frames = "1,4,16";
    std::string cacheDir;      // empty: measure::defaultCacheDir()
    RendererFactory gpu;       // set by the window (a GPU renderer of its own on the worker thread)
    MeasuredView running;      // what the running (or last started) job measures
    bool runningCandidates = false;  // ... and whether it measures candidates, a heat map or both
    bool runningHeatMap = false;
    MeasuredView measured;     // what the candidates were measured on
    MeasuredView heatMapView;  // what the heat map was computed for
    uint64_t seenGeneration = 0;
    int selected = -1;         // the table's chosen row
};

}  // namespace brume::editor
