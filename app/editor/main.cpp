// brume-editor [SCENE.json]: the interactive fog editor (GLFW window, Vulkan swapchain, Dear ImGui).
// Testing hooks: --script replays actions (one per frame, the same Editor::run the UI uses),
// --screenshot/--frames renders N frames, saves the window image and exits.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <imgui.h>
#include <stb/stb_image_write.h>

#include "core/settings.h"
#include "editor.h"
#include "frame_pacing.h"
#include "frame_stats.h"
#include "gpu/vk_check.h"
#include "io/atomic_file.h"
#include "io/scene_json.h"
#include "presenter.h"
#include "ui.h"

namespace fs = std::filesystem;
using namespace brume;
using namespace brume::editor;

namespace {

struct Options {
    std::string scene;
    std::string script;
    std::string record;
    std::string screenshot;
    int frames = 0;
    int width = 1280;
    int height = 720;
    std::string quality;
    bool hideUi = false;
    bool recover = false;
    bool discardRecovery = false;
    double autosaveSeconds = settings::editor_autosave_seconds.value();
    bool validation = false;
    std::string device;
    double interactiveScale = settings::editor_interactive_scale.value();
    double frameBudgetMs = settings::editor_frame_budget_ms.value();
    bool bench = false;
};

double seconds() {
    using namespace std::chrono;
    return duration<double>(steady_clock::now().time_since_epoch()).count();
}

Result<void> writeScreenshot(const Rgba8& img, const std::string& path) {
    return writeFileAtomic(path, [&](const std::string& tmp) -> Result<void> {
        if (!stbi_write_png(tmp.c_str(), img.width, img.height, 4, img.pixels.data(), img.width * 4))
            return Error{"Could not write the screenshot " + path + "."};
        return {};
    });
}

struct Script {
    std::vector<std::string> lines;
    size_t next = 0;
    double resumeAt = 0.0;
};

Result<Script> readScript(const std::string& path) {
    Script s;
    if (path.empty()) return s;
    std::ifstream f(path);
    if (!f) return Error{path + ": cannot open the script file."};
    for (std::string line; std::getline(f, line);) s.lines.push_back(line);
    return s;
}

int fail(const std::string& message, int code) {
    std::fprintf(stderr, "error: %s\n", message.c_str());
    return code;
}

struct Window {
    GLFWwindow* handle = nullptr;
    ~Window() {
        if (handle) glfwDestroyWindow(handle);
        glfwTerminate();
    }
};

}  // namespace

int runEditor(const Options& o);

int main(int argc, char** argv) {
    Options o;
    CLI::App app{"brume-editor: place, shape and light volumetric fog live."};
    app.add_option("scene", o.scene, "Scene file to open (JSON); none: a new, untitled scene.");
    app.add_option("--script", o.script, "Run these actions, one per line and one per frame (see docs/editor.md).");
    app.add_option("--record", o.record, "Append every action to this file (a replayable --script).");
    app.add_option("--screenshot", o.screenshot, "After --frames frames, save the window image (PNG) and exit.");
    app.add_option("--frames", o.frames, "Render this many frames (each re-rendering the scene), then exit.")->check(CLI::Range(1, 100000));
    app.add_option("--width", o.width, "Window width [px].")->check(CLI::Range(64, 16384));
    app.add_option("--height", o.height, "Window height [px].")->check(CLI::Range(36, 16384));
    app.add_option("--quality", o.quality, "Viewport quality preset (default: the scene's render.quality).");
    app.add_flag("--hide-ui", o.hideUi, "Show only the viewport (screenshots comparable with brume render).");
    app.add_flag("--recover", o.recover, "Recover an autosave left by a crash without asking.");
    app.add_flag("--discard-recovery", o.discardRecovery, "Delete an autosave left by a crash without asking.");
    const Setting& autosave = settings::editor_autosave_seconds;
    app.add_option("--autosave-seconds", o.autosaveSeconds, std::string(autosave.help) + " [s]")
        ->check(CLI::Range(autosave.min, autosave.max));
    app.add_flag("--validation", o.validation, "Enable the Vulkan validation layer; exit 1 if it reports anything.");
    app.add_option("--device", o.device,
                   "Vulkan device whose name contains this text (case-insensitive); it renders and draws the window. "
                   "Default: the BRUME_DEVICE environment variable, else a discrete GPU, an integrated GPU, a virtual "
                   "GPU, then a CPU device (lavapipe).");
    const Setting& scale = settings::editor_interactive_scale;
    app.add_option("--interactive-scale", o.interactiveScale, std::string(scale.help))
        ->check(CLI::Range(scale.min, scale.max));
    const Setting& budget = settings::editor_frame_budget_ms;
    app.add_option("--frame-budget-ms", o.frameBudgetMs, std::string(budget.help) + " [ms]")
        ->check(CLI::Range(budget.min, budget.max));
    app.add_flag("--bench", o.bench, "At exit, print the median, p95 and slowest frame time and the per-pass times (use with --script or --frames).");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : 2;
    }
    return runEditor(o);
}

namespace {

// The document to edit: the scene file with its VDB grids (scene errors exit 2 like `brume`; a
// grid that cannot be read is a notification, see files.h), or an empty scene.
Result<Document> openDocument(const Options& o, std::vector<std::string>& warnings) {
    if (o.scene.empty()) return Document(Scene{}, "");
    Result<OpenedScene> s = openSceneFile(o.scene);
    if (!s) return s.error();
    warnings = s.value().warnings;
    return Document(s.value().scene, s.value().path);
}

// Files dropped on the window, run as `drop PATH` actions by the loop (GLFW calls back from
// glfwPollEvents on this thread, with no context to spare).
std::vector<std::string> droppedPaths;
void onDrop(GLFWwindow*, int count, const char** paths) {
    for (int i = 0; i < count; ++i) droppedPaths.emplace_back(paths[i]);
}

// Runs script lines until one asks to wait or the script ends; one document action per frame, so
// each edit is rendered like a user's. Returns an error naming the script line.
Result<void> stepScript(Script& script, Editor& editor, double now) {
    while (script.next < script.lines.size() && now >= script.resumeAt) {
        if (editor.waitUntil && !editor.waitUntil()) break;  // tradeoff wait: the measurement runs on
        editor.waitUntil = nullptr;
        const size_t n = script.next++;
        const std::string& line = script.lines[n];
        editor.waitSeconds = 0.0;
        Result<void> r = editor.run(line);
        if (!r) return Error{"script line " + std::to_string(n + 1) + ": " + r.error().message};
        if (editor.waitSeconds > 0.0) script.resumeAt = now + editor.waitSeconds;
        Result<Action> a = parseAction(line);
        if (a && !a.value().verb.empty()) break;  // one action per frame
    }
    return {};
}

void offerRecovery(Editor& editor, UiState& ui, const Options& o, double now) {
    const std::string path = editor.autosave().path();
    if (!fs::exists(path)) return;
    if (o.discardRecovery) return editor.autosave().discard();
    if (!o.recover) return void(ui.recoveryPath = path);
    Result<OpenedScene> s = openSceneFile(path);  // with its VDB grids
    if (s) editor.doc().replaceScene(s.value().scene);
    else editor.notify("The autosave could not be recovered: " + s.error().message, now);
}


// What the loop keeps when runEditor re-enters it with a recreated device (a lost device).
struct LoopState {
    bool started = false;
    FrameStats stats;
    UiState ui;
    std::string offeredFor;
    double frameStart = 0.0, totalMs = 0.0, lastNow = 0.0;
    double lastCoarseStart = -1.0;  // --bench: the start of the latest coarse frame, until the view settles
    int frame = 0;
    std::string shownTitle;
    FramePacer pacer;
    double sleepSeconds = 0.0;  // before the next frame (FramePacer)
};
// editorLoop's answer when the device was lost: runEditor recreates it and calls the loop again.
constexpr int kDeviceLost = -1;

// One iteration per frame: input, script, UI, autosave, render (when something changed, or every
// frame with --frames so frame times measure the renderer), present.
int editorLoop(const Options& o, Editor& editor, Presenter& presenter, gpu::GpuRenderer& renderer, Script& script,
               LoopState& st) {
    FrameStats& stats = st.stats;
    UiState& ui = st.ui;
    std::string& offeredFor = st.offeredFor;
    // Scripted and screenshot runs get a frame-count clock that starts paused (scene_time.h).
    const bool fixedClock = !o.script.empty() || !o.screenshot.empty() || o.frames > 0;
    if (!st.started) {
        st.started = true;
        offerRecovery(editor, ui, o, seconds());
        offeredFor = editor.autosave().path();
        if (fixedClock) editor.sceneTime().play(false);
        st.frameStart = st.lastNow = seconds();
    }
    double &frameStart = st.frameStart, &totalMs = st.totalMs, &lastNow = st.lastNow;
    int& frame = st.frame;
    std::string& shownTitle = st.shownTitle;
    double& lastCoarseStart = st.lastCoarseStart;
    while (true) {
        // The title follows New / Open / Save As.
        const std::string title = "brume-editor - " + (editor.doc().path().empty() ? std::string("untitled") : editor.doc().path());
        if (title != shownTitle) glfwSetWindowTitle(presenter.window(), title.c_str()), shownTitle = title;
        // Nothing to do since a few frames: sleep until an event or the pacer's timeout.
        bool woken = false;
        if (st.sleepSeconds > 0.0) {
            const double sleepStart = seconds();
            glfwWaitEventsTimeout(st.sleepSeconds);
            woken = seconds() - sleepStart < 0.9 * st.sleepSeconds;
            // A frame's time is its work, not the sleep before it: the coarse scale adapts to the
            // frame time (Interaction::measured), and a drag resumed after a pause must not shrink it.
            frameStart = seconds();
        } else {
            glfwPollEvents();
        }
        const double now = seconds();
        if (!droppedPaths.empty()) {
            (void)editor.run(Action{"drop", std::exchange(droppedPaths, {})});  // failures are notifications
        }
        if (glfwWindowShouldClose(presenter.window())) {
            glfwSetWindowShouldClose(presenter.window(), GLFW_FALSE);
            ui.closeRequested = true;
        }
        if (Result<void> r = stepScript(script, editor, now); !r) return fail(r.error().message, 2);
        editor.sceneTime().advance(editor.doc().scene(), fixedClock ? kScriptedFrameSeconds : now - lastNow);
        lastNow = now;
        presenter.newFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        if (!o.hideUi) {
            drawUi(editor, ui, now);
            handleViewportInput(editor, ui, now);
        } else if (ui.closeRequested) {
            ui.closeConfirmed = true;
        }
        ImGui::Render();
        // New or Open moved the autosave: a recovery file already there is a crashed session's.
        if (editor.autosave().path() != offeredFor) {
            offeredFor = editor.autosave().path();
            offerRecovery(editor, ui, o, now);
        }
        // The last frame's time stands for the wait until the next tick (a render follows), plus the
        // longest sleep the loop may take before it (FramePacer).
        if (Result<void> r = editor.autosave().tick(editor.doc(), now, editor.frameMs / 1000.0 + FramePacer::kIdleWaitSeconds); !r)
            editor.notify(r.error().message, now);
        offeredFor = editor.autosave().path();  // where a Save As moved it: our own file
        int w = 0, h = 0;
        glfwGetFramebufferSize(presenter.window(), &w, &h);
        const uint64_t rendersBefore = editor.renders();
        const double renderStart = seconds();
        if (w > 0 && h > 0) {
            if (Result<void> r = presenter.waitForFrame(); !r) {
                if (gpu::isDeviceLost(r.error())) return std::fprintf(stderr, "%s\n", r.error().message.c_str()), kDeviceLost;
                return fail(r.error().message, 1);
            }
            if (Result<void> r = editor.renderIfNeeded(renderer, w, h, o.frames > 0); !r) {
                editor.notify(r.error().message, now);
                std::fprintf(stderr, "%s\n", r.error().message.c_str());  // also in logs and tests
                if (gpu::isDeviceLost(r.error())) return kDeviceLost;
            }
        }
        const double renderEnd = seconds();
        ++frame;
        const bool last = o.frames > 0 && frame >= o.frames;
        const bool capture = (last && !o.screenshot.empty()) || !editor.screenshotRequest.empty();
        Rgba8 shot;
        const double presentStart = seconds();
        if (Result<void> r = presenter.present(editor.viewportImage(renderer), editor.viewSize(), editor.renders(), ImGui::GetDrawData(),
                                               capture ? &shot : nullptr);
            !r) {
            if (gpu::isDeviceLost(r.error())) return std::fprintf(stderr, "%s\n", r.error().message.c_str()), kDeviceLost;
            return fail(r.error().message, 1);
        }
        const double presentMs = (seconds() - presentStart) * 1000.0;
        if (capture) {
            const std::string path = editor.screenshotRequest.empty() ? o.screenshot : editor.screenshotRequest;
            editor.screenshotRequest.clear();
            if (Result<void> r = writeScreenshot(shot, path); !r) return fail(r.error().message, 1);
        }
        const double end = seconds();
        editor.frameMs = (end - frameStart) * 1000.0;
        frameStart = end;
        if (frame > 1) totalMs += editor.frameMs;  // the first frame also compiles the shaders
        if (o.bench) {
            const bool rendered = editor.renders() != rendersBefore;
            const char* kind = !rendered ? "ui" : editor.coarse() ? "coarse" : "rest";
            if (rendered && editor.coarse()) {
                stats.addCoarseScale(editor.shownScale());
                lastCoarseStart = end - editor.frameMs / 1000.0;
            } else if (rendered && lastCoarseStart >= 0.0) {
                stats.addSettle((end - lastCoarseStart) * 1000.0);
                lastCoarseStart = -1.0;
            }
            // Besides the GPU passes, the frame's CPU-side parts: input, script and UI before the
            // render; the render call (waiting for the previous window frame, compiling the scene,
            // recording, submitting, waiting for the device).
            std::vector<gpu::PassTiming> parts = rendered ? editor.lastRender()->passes : std::vector<gpu::PassTiming>{};
            parts.push_back({"before render (cpu)", (renderStart - (end - editor.frameMs / 1000.0)) * 1000.0});
            parts.push_back({"render call", (renderEnd - renderStart) * 1000.0});
            if (Result<std::vector<gpu::PassTiming>> pp = presenter.lastParts(); pp)
                parts.insert(parts.end(), pp.value().begin(), pp.value().end());
            stats.add(kind, editor.frameMs, parts, presentMs);
            if (rendered && editor.lastRender()->compiled) stats.addCompiled();
        }
        if (last) {
            if (frame > 1) std::printf("frames: %d, mean frame time (after the first): %.1f ms\n", frame, totalMs / (frame - 1));
            break;
        }
        if (editor.quitRequested || ui.closeConfirmed) break;
        FrameActivity activity;
        activity.rendered = editor.renders() != rendersBefore;
        const bool scriptLeft = script.next < script.lines.size();
        const double after = seconds();
        // A `tradeoff wait` holds the script while the job runs: its progress paces the loop then.
        const bool scriptHeld = editor.waitUntil && editor.qualityTool.job.running();
        activity.scriptStepDue = scriptLeft && after >= script.resumeAt && !scriptHeld;
        activity.scriptWaitLeft = scriptLeft && after < script.resumeAt ? script.resumeAt - after : -1.0;
        activity.playing = editor.sceneTime().playing() && sceneScrolls(editor.doc().scene());
        activity.jobRunning = editor.qualityTool.job.running();
        activity.fixedFrames = o.frames > 0;
        activity.woken = woken;
        st.sleepSeconds = st.pacer.next(activity);
    }
    if (o.bench) std::printf("%s", stats.report().c_str());
    editor.autosave().discard();  // an orderly exit: saved, or the user chose to discard
    return 0;
}

// The Quality panel's GPU renderer: its own device (the same choice and validation as the
// window's), created, used and destroyed on the panel's worker thread (quality_job.h).
RendererFactory qualityPanelGpu(const Options& o) {
    return [device = o.device, validation = o.validation]() -> Result<measure::CandidateRender> {
        Result<std::unique_ptr<gpu::GpuRenderer>> made = gpu::GpuRenderer::create(gpu::GpuOptions{device, validation, {}});
        if (!made) return made.error();
        std::shared_ptr<gpu::GpuRenderer> r = std::move(made.value());
        return measure::CandidateRender([r](const Scene& s, const RenderRequest& q) -> Result<Image> {
            Result<gpu::GpuRender> out = r->render(s, q);
            if (!out) return out.error();
            if (const std::vector<std::string> m = r->validationMessages(); !m.empty())
                return Error{"The Quality panel's renderer: validation: " + m.front()};
            return std::move(out.value().image);
        });
    };
}

}  // namespace

int runEditor(const Options& o) {
    std::vector<std::string> warnings;
    Result<Document> doc = openDocument(o, warnings);
    if (!doc) return fail(doc.error().message, 2);
    Quality quality = doc.value().scene().render.quality;
    if (!o.quality.empty() && !parseQuality(o.quality, quality))
        return fail("--quality: \"" + o.quality + "\" is not one of low, medium, high, ultra.", 2);
    Result<Script> script = readScript(o.script);
    if (!script) return fail(script.error().message, 2);
    const std::string recoveryPath = recoveryPathFor(doc.value().path());
    Editor editor(std::move(doc.value()), Autosave(recoveryPath, o.autosaveSeconds), quality, o.interactiveScale,
                  o.frameBudgetMs);
    for (std::string& w : editor.files().recent().load()) editor.files().message(std::move(w));
    for (std::string& w : warnings) editor.files().message(std::move(w));
    editor.files().noteRecent(editor.doc().path());
    std::ofstream record;
    if (!o.record.empty()) {
        record.open(o.record, std::ios::app);
        if (!record) return fail(o.record + ": cannot open the record file.", 2);
        editor.recorder = [&record](const Action& a) { record << formatAction(a) << "\n" << std::flush; };
    }

    if (!glfwInit()) return fail("brume-editor needs a display: set DISPLAY or run it under xvfb-run.", 1);
    Window window;
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    const std::string title = "brume-editor - " + (o.scene.empty() ? std::string("untitled") : o.scene);
    window.handle = glfwCreateWindow(o.width, o.height, title.c_str(), nullptr, nullptr);
    if (!window.handle) return fail("brume-editor could not open a window on this display.", 1);
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // panel layout is not persisted (tests stay reproducible)
    ImGui_ImplGlfw_InitForVulkan(window.handle, true);
    glfwSetDropCallback(window.handle, onDrop);
    int code = 0;
    // A lost device (gpu::isDeviceLost: a driver crash or a timeout) cannot be used again: the renderer
    // and the presenter are created anew, as at start, and the loop goes on with the same document
    // (the viewport already fell back to the preset below, Editor::renderIfNeeded). A device lost
    // again and again ends the editor with a sentence; the autosave keeps the edits (--recover).
    constexpr int kMaxRecreations = 3;
    LoopState loop;
    for (int recreations = 0;; ++recreations) {
        if (recreations > kMaxRecreations) {
            code = fail("The GPU device was lost " + std::to_string(recreations) +
                            " times; brume-editor stops (your edits are in the autosave: restart with --recover).",
                        1);
            break;
        }
        if (recreations > 0) {
            editor.rendererReplaced();
            const std::string note = "The GPU device was lost: brume-editor recreated it.";
            editor.notify(note, seconds());
            std::fprintf(stderr, "%s\n", note.c_str());
        }
        // One device renders and draws the window (the renderer outlives the presenter).
        Result<gpu::PresentTarget> target = windowPresentTarget(window.handle);
        if (!target) return fail(target.error().message, 1);
        gpu::GpuOptions options{o.device, o.validation, std::move(target.value())};
        Result<std::unique_ptr<gpu::GpuRenderer>> renderer = gpu::GpuRenderer::create(options);
        // A named device that is not there is bad input (as for `brume render --device`).
        const bool named = !o.device.empty() || std::getenv("BRUME_DEVICE");
        if (!renderer) return fail(renderer.error().message, named ? 2 : 1);
        editor.qualityTool.gpu = qualityPanelGpu(o);
        Result<std::unique_ptr<Presenter>> presenter = Presenter::create(window.handle, renderer.value()->device());
        if (!presenter) return fail(presenter.error().message, 1);
        presenter.value()->measureParts(o.bench);
        code = editorLoop(o, editor, *presenter.value(), *renderer.value(), script.value(), loop);
        presenter.value().reset();
        if (o.validation) {
            const std::vector<std::string> messages = renderer.value()->validationMessages();
            for (const std::string& m : messages) std::fprintf(stderr, "validation: %s\n", m.c_str());
            if (!messages.empty() && (code == 0 || code == kDeviceLost)) {
                code = 1;
                break;
            }
        }
        if (code != kDeviceLost) break;
    }
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    return code;
}
