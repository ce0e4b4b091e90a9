#include "render_command.h"
#include "vdb_command.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cctype>
#include <filesystem>
#include <limits>
#include <optional>

#include <csignal>

#include <unistd.h>

#include <nlohmann/json.hpp>

#if BRUME_HAS_GPU
#include "gpu/gpu_renderer.h"
#endif

#include "cli_text.h"
#include "core/animate.h"
#include "core/debug_view.h"
#include "core/sequence.h"
#include "io/atomic_file.h"
#include "io/image_io.h"
#include "io/scene_json.h"
#include "progress.h"

namespace brume::app {

namespace fs = std::filesystem;

const char* rendererName(RendererKind kind) {
    switch (kind) {
        case RendererKind::Gpu: return "gpu";
        case RendererKind::FroxelCpu: return "cpu";
        case RendererKind::Reference: return "reference";
    }
    return "?";
}

#if BRUME_HAS_GPU
struct RenderSession::Gpu {
    std::unique_ptr<gpu::GpuRenderer> renderer;
};
#else
struct RenderSession::Gpu {};
#endif

RenderSession::RenderSession(RendererKind kind, const std::string& device) : kind_(kind) {
    if (kind != RendererKind::Gpu) return;
#if BRUME_HAS_GPU
    Result<std::unique_ptr<gpu::GpuRenderer>> r = gpu::GpuRenderer::create({device, false, {}});
    if (!r) {
        startFailure_ = RenderFailure{true, r.error().message};
        return;
    }
    gpu_ = std::make_unique<Gpu>();
    gpu_->renderer = std::move(r.value());
#else
    (void)device;
    startFailure_ = RenderFailure{true, "this build of brume has no GPU renderer (BRUME_BUILD_GPU=OFF); use --cpu."};
#endif
}

// With BRUME_VALIDATION=1 the layer's messages would otherwise go unseen: one line names their count.
RenderSession::~RenderSession() {
#if BRUME_HAS_GPU
    if (!gpu_ || !gpu_->renderer->validationEnabled()) return;
    const std::vector<std::string> messages = gpu_->renderer->validationMessages();
    if (!messages.empty())
        std::fprintf(stderr, "warning: the Vulkan validation layer reported %zu messages; the first: %s\n", messages.size(),
                     messages.front().c_str());
#endif
}

std::variant<RenderOutput, RenderFailure> RenderSession::render(const Scene& scene, const RenderRequest& request) {
    if (startFailure_) return *startFailure_;
    const auto start = std::chrono::steady_clock::now();
    RenderOutput out;
    switch (kind_) {
        case RendererKind::Gpu: {
#if BRUME_HAS_GPU
            Result<gpu::GpuRender> r = gpu_->renderer->render(scene, request);
            if (!r) return RenderFailure{r.error().badInput, r.error().message};
            out.image = std::move(r.value().image);
            out.stats.device = gpu_->renderer->deviceName();
            for (const gpu::PassTiming& p : r.value().passes) out.stats.passes.push_back({p.name, p.gpuMs});
            out.stats.froxelDims = r.value().dims;
            out.stats.litFroxels = r.value().litFroxels;
            out.stats.skippedFroxels = r.value().skippedFroxels;
            out.stats.overfullClusters = r.value().overfullClusters;
#endif
            break;
        }
        case RendererKind::FroxelCpu: {
            FroxelResult r = cpu_.render(scene, request);
            out.image = std::move(r.image);
            out.stats.froxelDims = r.volumes.dims;
            out.stats.litFroxels = r.volumes.litFroxels;
            out.stats.skippedFroxels = r.volumes.skippedFroxels;
            out.stats.overfullClusters = r.volumes.overfullClusters;
            break;
        }
        case RendererKind::Reference: out.image = renderReference(scene, request); break;
    }
    out.stats.wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return out;
}

Result<void> writeStatsJson(const std::string& path, RendererKind kind, const RenderRequest& request,
                            const RenderStats& stats) {
    nlohmann::ordered_json j;
    j["renderer"] = rendererName(kind);
    if (!stats.device.empty()) j["device"] = stats.device;
    j["width"] = request.width;
    j["height"] = request.height;
    j["quality"] = toString(request.quality);
    j["wall_ms"] = stats.wallMs;
    nlohmann::ordered_json passes = nlohmann::ordered_json::object();
    for (const PassTime& p : stats.passes) passes[p.name] = p.gpuMs;
    j["gpu_pass_ms"] = passes;
    if (kind != RendererKind::Reference) {
        j["froxels"] = {stats.froxelDims.x, stats.froxelDims.y, stats.froxelDims.z};
        j["lit_froxels"] = stats.litFroxels;
        j["skipped_froxels"] = stats.skippedFroxels;
        j["overfull_light_clusters"] = stats.overfullClusters;
    }
    return writeTextFileAtomic(path, j.dump(2) + "\n");
}

CLI::App* addRenderCommand(CLI::App& app, RenderOptions& o) {
    CLI::App* cmd = app.add_subcommand("render", "Render a scene to a PNG (tone mapped) or EXR (linear radiance).");
    cmd->add_option("SCENE", o.scenePath, "Scene file (JSON; see docs/scene-format.md).")->required();
    cmd->add_option("-o,--output", o.outputPath,
                    "Output image: .png (exposure, ACES filmic, sRGB) or .exr (linear, 32-bit float). "
                    "Written atomically; its folder must exist. With --sequence, a run of # in the file name "
                    "is replaced by the frame number, zero-padded to its length (out_####.png).")
        ->required();
    const std::string w = std::to_string(settings::render_width.i());
    const std::string h = std::to_string(settings::render_height.i());
    o.widthOption = cmd->add_option("--width", o.width,
                                    optionHelp(settings::render_width, "the scene's render.width (" + w + " px if absent)"));
    o.heightOption = cmd->add_option(
        "--height", o.height, optionHelp(settings::render_height, "the scene's render.height (" + h + " px if absent)"));
    o.qualityOption = cmd->add_option(
        "--quality", o.quality,
        optionHelp(settings::render_quality, "the scene's render.quality (" + formatDefault(settings::render_quality) +
                                                 " if absent); the reference renderer ignores it"));
    o.frames = settings::cli_frames.i();
    o.framesOption = cmd->add_option("--frames", o.frames, optionHelp(settings::cli_frames, "the scene's render.frames"));
    o.orbit = settings::cli_orbit.f();
    o.orbitOption = cmd->add_option("--orbit", o.orbit, optionHelp(settings::cli_orbit));
    o.time = settings::cli_time.f();
    o.timeOption = cmd->add_option("--time", o.time, optionHelp(settings::cli_time));
    o.fps = settings::cli_fps.f();
    cmd->add_option("--fps", o.fps, optionHelp(settings::cli_fps, "24 1/s (with --sequence, frame f is at time f / fps)"));
    cmd->add_option("--sequence", o.sequence,
                    "Render frames A to B (A-B, integers, 0 <= A <= B) of the scene time, frame f at f / --fps, "
                    "each to -o with its #### replaced by f. Frames already on disk are skipped (resume) unless "
                    "--overwrite; Ctrl-C stops after the frame being written. The temporal history is carried from "
                    "frame to frame and warmed up the same way whatever the range, so a range rendered in parts "
                    "equals the whole (docs/cli.md). Default: none (one image).");
    cmd->add_flag("--overwrite", o.overwrite, "With --sequence: render frames already on disk again. Default: off.");
    auto* ref = cmd->add_flag("--reference", o.reference,
                              "Use the per-pixel reference ray marcher (ground truth; slow). Default: off.");
    auto* cpu = cmd->add_flag("--cpu", o.cpu,
                              "Use the CPU froxel renderer (the GPU renderer's oracle). Default: off (the GPU renders).");
    ref->excludes(cpu);
    cmd->add_option("--device", o.device,
                    "GPU renderer: Vulkan device whose name contains this text (case-insensitive). "
                    "Default: the BRUME_DEVICE environment variable, else a discrete GPU, an integrated GPU, "
                    "then a CPU implementation (lavapipe).");
    o.statsOption = cmd->add_option("--stats", o.statsPath,
                    "Write render statistics as JSON: per-pass GPU milliseconds (GPU renderer), wall "
                    "milliseconds, froxel grid size, lit and skipped froxels. Written atomically. Default: none.");
    o.exposure = settings::cli_exposure.f();
    cmd->add_option("--exposure", o.exposure, optionHelp(settings::cli_exposure));
    o.debugView = settings::cli_debug_view.choices.substr(0, settings::cli_debug_view.choices.find('|'));
    cmd->add_option("--debug-view", o.debugView, optionHelp(settings::cli_debug_view));
    o.debugSlice = settings::cli_debug_slice.i();
    cmd->add_option("--debug-slice", o.debugSlice, optionHelp(settings::cli_debug_slice));
    o.threads = settings::cli_threads.i();
    cmd->add_option("--threads", o.threads, optionHelp(settings::cli_threads));
    o.vdbMemoryMb = settings::cli_vdb_memory.i();
    cmd->add_option("--vdb-memory-mb", o.vdbMemoryMb, optionHelp(settings::cli_vdb_memory));
    return cmd;
}

static std::optional<CommandResult> checkRange(const char* name, double v, const Setting& s) {
    if (std::isfinite(v) && v >= s.min && v <= s.max) return std::nullopt;
    return badInput(std::string(name) + " " + formatNumber(v) + " is out of range: expected " + formatRange(s) + ".");
}

static std::optional<CommandResult> checkOutputPath(const std::string& out) {
    const fs::path path(out);
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext != ".png" && ext != ".exr") {
        return badInput(out + ": unsupported output extension '" + ext + "'; use .png or .exr.");
    }
    const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return badInput(out + ": output folder '" + dir.string() + "' does not exist.");
    if (access(dir.c_str(), W_OK) != 0) return badInput(out + ": output folder '" + dir.string() + "' is not writable.");
    if (fs::is_directory(path, ec)) return badInput(out + ": output path is a folder.");
    return std::nullopt;
}

static std::optional<CommandResult> checkDebugView(const RenderOptions& o) {
    int view = 0;
    if (!parseDebugView(o.debugView, view))
        return badInput("--debug-view '" + o.debugView + "' is not one of " + std::string(settings::cli_debug_view.choices) + ".");
    if (view != shd::DEBUG_VIEW_FINAL && o.reference)
        return badInput("--debug-view shows froxel volumes; the reference renderer (--reference) has none.");
    return checkRange("--debug-slice", o.debugSlice, settings::cli_debug_slice);
}

// The run of '#' in the output's file name (not its folder): [position, length); length 0 if none.
static std::pair<size_t, size_t> framePattern(const std::string& out) {
    const size_t nameStart = out.find_last_of('/') == std::string::npos ? 0 : out.find_last_of('/') + 1;
    const size_t at = out.find('#', nameStart);
    if (at == std::string::npos) return {0, 0};
    return {at, out.find_first_not_of('#', at) == std::string::npos ? out.size() - at : out.find_first_not_of('#', at) - at};
}

static std::string framePath(const std::string& out, int frame) {
    const auto [at, length] = framePattern(out);
    std::string number = std::to_string(frame);
    if (number.size() < length) number.insert(0, length - number.size(), '0');
    return out.substr(0, at) + number + out.substr(at + length);
}

static std::optional<CommandResult> checkSequence(const RenderOptions& o) {
    if (o.sequence.empty()) {
        if (o.overwrite) return badInput("--overwrite only applies to --sequence.");
        return std::nullopt;
    }
    if (!parseFrameRange(o.sequence))
        return badInput("--sequence '" + o.sequence + "' is not a frame range A-B of integers with 0 <= A <= B <= " +
                        std::to_string(kMaxSequenceFrame) + " (example: --sequence 0-47).");
    const std::pair<CLI::Option*, const char*> exclusive[] = {
        {o.framesOption, "--frames"}, {o.timeOption, "--time"}, {o.orbitOption, "--orbit"}, {o.statsOption, "--stats"}};
    for (const auto& [option, name] : exclusive)
        if (option && option->count() > 0)
            return badInput(std::string(name) + " cannot be combined with --sequence (frame f is rendered at time f / --fps, "
                            "its history warmed up by the sequence itself).");
    if (o.debugView != settings::cli_debug_view.choices.substr(0, settings::cli_debug_view.choices.find('|')))
        return badInput("--debug-view cannot be combined with --sequence.");
    if (framePattern(o.outputPath).second == 0)
        return badInput(o.outputPath + ": --sequence needs a run of # in the output's file name for the frame number "
                        "(example: -o out_####.png).");
    return std::nullopt;
}

static std::optional<CommandResult> checkOptions(const RenderOptions& o) {
    if (o.widthOption->count() > 0)
        if (auto e = checkRange("--width", o.width, settings::render_width)) return e;
    if (o.heightOption->count() > 0)
        if (auto e = checkRange("--height", o.height, settings::render_height)) return e;
    Quality q;
    if (o.qualityOption->count() > 0 && !parseQuality(o.quality, q)) {
        return badInput("--quality '" + o.quality + "' is not one of " + std::string(settings::render_quality.choices) + ".");
    }
    if (auto e = checkRange("--frames", o.frames, settings::cli_frames)) return e;
    if (auto e = checkRange("--orbit", o.orbit, settings::cli_orbit)) return e;
    if (auto e = checkRange("--time", o.time, settings::cli_time)) return e;
    if (auto e = checkRange("--fps", o.fps, settings::cli_fps)) return e;
    if (auto e = checkRange("--exposure", o.exposure, settings::cli_exposure)) return e;
    if (auto e = checkRange("--vdb-memory-mb", o.vdbMemoryMb, settings::cli_vdb_memory)) return e;
    if (auto e = checkRange("--threads", o.threads, settings::cli_threads)) return e;
    if (auto e = checkDebugView(o)) return e;
    if (auto e = checkSequence(o)) return e;
    if (!o.statsPath.empty()) {
        const fs::path dir = fs::path(o.statsPath).parent_path().empty() ? fs::path(".") : fs::path(o.statsPath).parent_path();
        std::error_code ec;
        if (!fs::is_directory(dir, ec)) return badInput(o.statsPath + ": stats folder '" + dir.string() + "' does not exist.");
    }
    return checkOutputPath(o.outputPath);
}

static RenderRequest requestFromOptions(const Scene& scene, const RenderOptions& o) {
    RenderRequest r = requestFromScene(scene);
    if (o.widthOption->count() > 0) r.width = o.width;
    if (o.heightOption->count() > 0) r.height = o.height;
    if (o.qualityOption->count() > 0) parseQuality(o.quality, r.quality);
    r.frames = o.framesOption->count() > 0 ? o.frames : scene.render.frames;
    r.threads = o.threads;
    parseDebugView(o.debugView, r.debugView);
    r.debugSlice = o.debugSlice;
    return r;
}

static bool scrollsTextures(const Scene& scene) {
    for (const Volume& v : scene.volumes)
        if (v.density_texture && (v.density_texture->scroll_mps != glm::vec3(0.0f) ||
                                  (v.density_texture->detail && v.density_texture->detail->scroll_mps != glm::vec3(0.0f))))
            return true;
    return false;
}

// request.frames frames; with an orbit, a scrolling density texture, keyframes or influencers, one render call per frame
// (each with its camera and scene time, the history carried over by the session's renderer), progress
// shown for the last only so it never goes back. Frame n of N is at time - (N - 1 - n) / fps: the
// written frame is at --time whatever --frames is.
static std::variant<RenderOutput, RenderFailure> renderFrames(RenderSession& session, const Scene& scene,
                                                              const RenderRequest& request, float orbitDegPerFrame,
                                                              float fps) {
    // Influencers move and their wakes decay with the time too (docs/scene-format.md, Influencers).
    if (orbitDegPerFrame == 0.0f &&
        (request.frames <= 1 || (!scrollsTextures(scene) && !hasKeys(scene) && scene.influencers.empty())))
        return session.render(bakeKeys(scene, scene.time_s), request);
    Scene s = scene;
    RenderRequest frame = request;
    frame.frames = 1;
    frame.progress = nullptr;
    for (int n = 0;; ++n) {
        s = bakeKeys(scene, scene.time_s - static_cast<float>(request.frames - 1 - n) / fps);
        if (orbitDegPerFrame != 0.0f) s.camera = orbitCamera(scene.camera, orbitDegPerFrame * static_cast<float>(n));
        frame.history = n == 0 ? HistoryMode::Restart : HistoryMode::Continue;
        if (n == request.frames - 1) {
            frame.progress = request.progress;
            return session.render(s, frame);
        }
        std::variant<RenderOutput, RenderFailure> r = session.render(s, frame);
        if (std::holds_alternative<RenderFailure>(r)) return r;
    }
}

// Over-full clusters cost time, not correctness: say which limit and what it costs.
void printClusterWarning(const std::string& scenePath, const RenderStats& stats) {
    if (stats.overfullClusters == 0) return;
    std::fprintf(stderr,
                 "warning: %s: %zu light clusters are reached by more than %d lights; their froxels loop over every "
                 "light (the image is unchanged, the light pass is slower); shorten the lights' ranges or narrow "
                 "their cones (docs/gpu.md, Light clusters)\n",
                 scenePath.c_str(), stats.overfullClusters, shd::CLUSTER_MAX_LIGHTS);
}

// Debug views are display values already: PNG as they are, EXR as for any image.
static Result<void> writeOutput(const Image& image, const RenderOptions& o, bool debugView) {
    if (debugView && fs::path(o.outputPath).extension() != ".exr") return writeDisplayPng(image, o.outputPath);
    return writeImage(image, o.outputPath, o.exposure);
}

// Ctrl-C during a sequence: the frame being rendered is finished and written (atomically), then the
// command stops; a second Ctrl-C kills at once (the default action), which leaves at most a hidden
// temporary file, never a partial frame under its name.
namespace {
volatile std::sig_atomic_t gInterrupted = 0;
extern "C" void onInterrupt(int) {
    gInterrupted = 1;
    std::signal(SIGINT, SIG_DFL);
}
struct InterruptGuard {
    InterruptGuard() { std::signal(SIGINT, onInterrupt); }
    ~InterruptGuard() { std::signal(SIGINT, SIG_DFL); }
};
}  // namespace

static bool frameOnDisk(const std::string& path) {
    std::error_code ec;
    return fs::is_regular_file(path, ec) && fs::file_size(path, ec) > 0 && !ec;
}

// Frames A..B (core/sequence.h): each frame's history chain starts at historyChainStart(f); when the
// session's history is not the one frame f needs (first frame, a skipped one, a block boundary), the
// chain is rendered again from its start without writing.
static CommandResult renderSequence(RenderSession& session, const Scene& scene, RenderRequest request,
                                    const RenderOptions& o, RendererKind kind) {
    const FrameRange range = *parseFrameRange(o.sequence);
    const int total = range.last - range.first + 1;
    InterruptGuard guard;
    gInterrupted = 0;
    int next = std::numeric_limits<int>::min();  // the frame the session's history is ready for
    int written = 0;
    int skipped = 0;
    int warmup = 0;
    request.frames = 1;
    const auto start = std::chrono::steady_clock::now();
    auto renderAt = [&](int frame, HistoryMode mode) {
        RenderRequest r = request;
        r.history = mode;
        r.progress = nullptr;
        return session.render(bakeKeys(scene, static_cast<float>(frame) / o.fps), r);
    };
    for (int f = range.first; f <= range.last; ++f) {
        const std::string path = framePath(o.outputPath, f);
        if (!o.overwrite && frameOnDisk(path)) {
            ++skipped;
            continue;
        }
        const int chain = historyChainStart(f, scene.temporal);
        if (next != f || chain == f - temporalWarmupFrames(scene.temporal)) {
            for (int g = chain; g < f; ++g, ++warmup) {
                std::variant<RenderOutput, RenderFailure> r = renderAt(g, g == chain ? HistoryMode::Restart : HistoryMode::Continue);
                if (const RenderFailure* e = std::get_if<RenderFailure>(&r))
                    return e->userCanFix ? badInput(e->message) : internalFailure(e->message);
            }
        }
        std::variant<RenderOutput, RenderFailure> r = renderAt(f, chain == f ? HistoryMode::Restart : HistoryMode::Continue);
        if (const RenderFailure* e = std::get_if<RenderFailure>(&r))
            return e->userCanFix ? badInput(e->message) : internalFailure(e->message);
        next = f + 1;
        const RenderOutput& out = std::get<RenderOutput>(r);
        if (!allFinite(out.image))
            return internalFailure(std::string("the ") + rendererName(kind) + " renderer produced non-finite pixels in frame " +
                                   std::to_string(f) + "; " + path + " was not written.");
        if (Result<void> w = writeImage(out.image, path, o.exposure); !w) return badInput(w.error().message);
        ++written;
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const int done = f - range.first + 1;
        std::printf("frame %d/%d: wrote %s (t = %g s, %.2f s elapsed)\n", done, total, path.c_str(),
                    static_cast<double>(f) / o.fps, elapsed);
        std::fflush(stdout);
        if (gInterrupted && f < range.last)
            return {130, "interrupted after frame " + std::to_string(f) + "; every frame written is complete; run the "
                         "same command again to render the rest"};
    }
    std::printf("sequence %d-%d: %d written, %d already on disk (skipped; --overwrite renders them again), %d warm-up "
                "frames (%s renderer, %dx%d, quality %s)\n",
                range.first, range.last, written, skipped, warmup, rendererName(kind), request.width, request.height,
                toString(request.quality));
    return success();
}

CommandResult runRender(const RenderOptions& o) {
    if (auto e = checkOptions(o)) return *e;
    Result<Scene> scene = loadSceneFile(o.scenePath);
    if (!scene) return badInput(scene.error().message);
    if (Result<void> g = loadGridsPrintingWarnings(scene.value(), o.scenePath, o.vdbMemoryMb); !g)
        return badInput(g.error().message);
    const RendererKind kind =
        o.reference ? RendererKind::Reference : (o.cpu ? RendererKind::FroxelCpu : RendererKind::Gpu);
    RenderRequest request = requestFromOptions(scene.value(), o);
    if (!o.sequence.empty()) {
        RenderSession session(kind, o.device);
        return renderSequence(session, scene.value(), request, o, kind);
    }
    ProgressLine progress(std::string("rendering (") + rendererName(kind) + ")");
    request.progress = [&progress](float f) { progress.update(f); };
    RenderSession session(kind, o.device);
    scene.value().time_s = o.time;
    std::variant<RenderOutput, RenderFailure> result = renderFrames(session, scene.value(), request, o.orbit, o.fps);
    if (const RenderFailure* f = std::get_if<RenderFailure>(&result)) {
        progress.end();
        return f->userCanFix ? badInput(f->message) : internalFailure(f->message);
    }
    RenderOutput& out = std::get<RenderOutput>(result);
    progress.complete();
    printClusterWarning(o.scenePath, out.stats);
    // Never write an image a viewer or compositor would choke on: NaN is a renderer bug.
    if (!allFinite(out.image)) {
        return internalFailure(std::string("the ") + rendererName(kind) + " renderer produced non-finite pixels; " +
                               o.outputPath + " was not written.");
    }
    // Failing to write is about the path or the disk, which the user can fix.
    if (Result<void> w = writeOutput(out.image, o, request.debugView != shd::DEBUG_VIEW_FINAL); !w)
        return badInput(w.error().message);
    if (request.debugView != shd::DEBUG_VIEW_FINAL) 
        std::printf("debug view: %s\n", debugViewLegend(scene.value(), request).c_str());
    if (!o.statsPath.empty()) {
        if (Result<void> w = writeStatsJson(o.statsPath, kind, request, out.stats); !w) return badInput(w.error().message);
    }
    std::printf("wrote %s (%dx%d, %s renderer, quality %s, %.2f s)\n", o.outputPath.c_str(), request.width,
                request.height, rendererName(kind), toString(request.quality), out.stats.wallMs / 1000.0);
    return success();
}

}  // namespace brume::app
