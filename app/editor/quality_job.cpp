#include "quality_job.h"

#include <chrono>

namespace brume::editor {

const char* phaseName(JobPhase phase) {
    switch (phase) {
        case JobPhase::Idle: return "idle";
        case JobPhase::Reference: return "reference";
        case JobPhase::Candidates: return "candidates";
        case JobPhase::HeatMap: return "heat map";
        case JobPhase::Done: return "done";
        case JobPhase::Cancelled: return "cancelled";
        case JobPhase::Failed: return "failed";
    }
    return "?";
}

RendererFactory cpuRendererFactory(int threads) {
    return [threads]() -> Result<measure::CandidateRender> {
        auto cpu = std::make_shared<FroxelCpuRenderer>();
        return measure::CandidateRender([cpu, threads](const Scene& s, const RenderRequest& r) -> Result<Image> {
            RenderRequest req = r;
            req.threads = threads;
            return cpu->render(s, req).image;
        });
    };
}

QualityJob::~QualityJob() {
    cancel();
    wait();
}

void QualityJob::start(QualityJobSpec spec, RendererFactory factory) {
    cancel();
    wait();
    cancel_ = false;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        progress_ = JobProgress{};
        progress_.phase = JobPhase::Reference;
        progress_.candidates = measure::plannedCandidates(spec.plan, spec.heatQuality).size();
    }
    running_ = true;
    thread_ = std::thread([this, s = std::move(spec), f = std::move(factory)]() mutable { work(std::move(s), std::move(f)); });
}

void QualityJob::cancel() { cancel_ = true; }

void QualityJob::wait() {
    if (thread_.joinable()) thread_.join();
}

JobProgress QualityJob::progress() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return progress_;
}

JobResult QualityJob::result() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return result_;
}

// Cancelled and failed jobs keep the previous numbers (with the reason); a finished one replaces
// what it measured: the candidates, the heat map, or both.
void QualityJob::finish(JobPhase phase, JobResult* result, std::string message) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        progress_.phase = phase;
        if (result) {
            if (!result->candidates.empty() || !result->hasHeatMap) {
                result_.candidates = std::move(result->candidates);
                result_.width = result->width;
                result_.height = result->height;
            }
            if (result->hasHeatMap) {
                result_.hasHeatMap = true;
                result_.heatMap = std::move(result->heatMap);
                result_.heatQuality = result->heatQuality;
                result_.heatFrames = result->heatFrames;
            }
            result_.referencePath = result->referencePath;
        }
        result_.message = std::move(message);
    }
    ++generation_;
    running_ = false;
}

void QualityJob::work(QualityJobSpec spec, RendererFactory factory) {
    RenderRequest base;
    base.width = spec.width;
    base.height = spec.height;
    base.threads = spec.threads;
    base.history = HistoryMode::Restart;
    const auto start = std::chrono::steady_clock::now();
    auto progress = [this, start](float f) {
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::lock_guard<std::mutex> lock(mutex_);
        progress_.referenceFraction = f;
        // Extrapolated from the time so far, once there is a little to go on.
        progress_.referenceEtaSeconds = f >= 0.02f ? elapsed * (1.0 - f) / f : -1.0;
    };
    const std::string cacheDir = spec.cacheDir.empty() ? measure::defaultCacheDir() : spec.cacheDir;
    Result<measure::ReferenceResult> ref = measure::referenceImage(spec.scene, base, cacheDir, progress, &cancel_);
    if (!ref) {
        const bool cancelled = ref.error().message == measure::kCancelled;
        return finish(cancelled ? JobPhase::Cancelled : JobPhase::Failed, nullptr,
                      cancelled ? "The measurement was cancelled." : ref.error().message);
    }
    JobResult result;
    result.width = spec.width;
    result.height = spec.height;
    result.referencePath = ref.value().path;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        progress_.referenceFraction = 1.0f;
        progress_.referenceEtaSeconds = 0.0;
        progress_.referenceCached = ref.value().cached;
        progress_.phase = JobPhase::Candidates;
    }
    Result<measure::CandidateRender> render = factory();
    if (!render) return finish(JobPhase::Failed, nullptr, render.error().message);
    std::vector<TradeoffCandidate> cands = measure::plannedCandidates(spec.plan, spec.heatQuality);
    auto done = [this](size_t k) {
        std::lock_guard<std::mutex> lock(mutex_);
        progress_.candidatesDone = k;
    };
    Result<void> measured = measure::measureCandidates(spec.scene, base, ref.value().image, cands, spec.plan.warmup,
                                                       spec.plan.repeats, render.value(), done, &cancel_);
    if (!measured) {
        const bool cancelled = measured.error().message == measure::kCancelled;
        return finish(cancelled ? JobPhase::Cancelled : JobPhase::Failed, nullptr,
                      cancelled ? "The measurement was cancelled." : measured.error().message);
    }
    result.candidates = std::move(cands);
    if (spec.heatMap) {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            progress_.phase = JobPhase::HeatMap;
        }
        // The scene as the viewport renders it (its own temporal settings), not a candidate's.
        RenderRequest req = base;
        req.quality = spec.heatQuality;
        req.frames = spec.heatFrames;
        Result<Image> img = render.value()(spec.scene, req);
        if (!img) return finish(JobPhase::Failed, nullptr, img.error().message);
        if (cancel_) return finish(JobPhase::Cancelled, nullptr, "The measurement was cancelled.");
        result.hasHeatMap = true;
        result.heatMap = pixelErrorMap(img.value(), ref.value().image);
        result.heatQuality = spec.heatQuality;
        result.heatFrames = spec.heatFrames;
    }
    finish(JobPhase::Done, &result, ref.value().warning);
}

}  // namespace brume::editor
