// The editor's state beside the document: selection, viewport quality, the camera verbs, the last
// render's statistics and the notifications. Editor::run() is the single entry point for every
// action, from the mouse, the keyboard or a --script file; document verbs go on to Document.
#pragma once

#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "accumulation.h"
#include "autosave.h"
#include "debug_view.h"
#include "document.h"
#include "files.h"
#include "gizmo_math.h"
#include "gpu/gpu_renderer.h"
#include "quality_job.h"
#include "scene_time.h"

namespace brume::editor {

enum class Kind { None, Volume, Light, Geometry, Influencer };

struct Selection {
    Kind kind = Kind::None;
    size_t index = 0;
};

struct Notification {
    std::string text;
    double untilSeconds = 0.0;
};

class Editor {
public:
    // interactiveScale, frameBudgetMs: Interaction's (accumulation.h), settings::editor_interactive_scale
    // and settings::editor_frame_budget_ms.
    Editor(Document doc, Autosave autosave, Quality quality, double interactiveScale = 1.0, double frameBudgetMs = 0.0);

    // Every action goes through here. Editor verbs (the rest are Document's):
    //   select volume|light|geometry|influencer INDEX | select none
    //   orbit YAW_DEG PITCH_DEG, pan RIGHT UP (fractions of the target distance), zoom FACTOR
    //   fly RIGHT UP FORWARD [m], look YAW_DEG PITCH_DEG (fly camera), frame (the selection),
    //   pick U V (select the volume or light under window fractions U, V from the top-left)
    //   quality low|medium|high|ultra (the viewport's preset; not saved in the scene)
    //   debug ... (the viewport's debug view, debug_view.h)
    //   wait SECONDS, screenshot PATH, quit    (script pacing and output; see main.cpp)
    //   gizmo translate|rotate|scale (the gizmo's mode: W / E / R)
    //   time SECONDS, play on|off   (the view's scene time and its clock; scene_time.h)
    //   preset apply FILE replace|add, preset save NAME [DESCRIPTION [TAG...]]   (preset_shelf.h)
    //   new [--discard], open PATH [--discard], import vdb PATH   (files.h; Save goes on to Document)
    //   tradeoff ... (the Quality panel and its measurement, quality_panel.h)
    //   drop PATH...   (files dropped on the window: a .vdb is imported, a .json opened, after the
    //                  unsaved-changes prompt; failures become notifications, never a script error)
    Result<void> run(const Action& action);
    Result<void> run(const std::string& line);

    Document& doc() { return doc_; }
    const Document& doc() const { return doc_; }
    Autosave& autosave() { return autosave_; }
    Files& files() { return files_; }
    Selection& selection() { return selection_; }
    Quality quality() const { return quality_; }
    DebugViewState& debugView() { return debug_; }
    SceneTime& sceneTime() { return time_; }

    // Call once per frame. Renders when the document, quality or size changed since the last
    // render, or while the temporal accumulation of a resting view has not converged (or always
    // with `force`), with the renderer's history carried on (see accumulation.h); coarse while the
    // user interacts (Interaction), at the scale the frame time of earlier coarse frames (frameMs, set
    // by the caller after each frame) allows. The image stays on the renderer's device (viewportImage).
    Result<void> renderIfNeeded(gpu::GpuRenderer& renderer, int width, int height, bool force);
    // The renderer was replaced (a lost device recreated): nothing is shown until the next render,
    // which happens on the next frame.
    void rendererReplaced();
    const Accumulation& accumulation() const { return accumulation_; }
    // The last render's output, or none (nothing rendered yet, or the last render failed).
    gpu::OutputImage viewportImage(const gpu::GpuRenderer& renderer) const;
    // The window area the viewport image is shown at (its size, or the window's for a coarse frame).
    glm::ivec2 viewSize() const { return viewSize_; }
    // Whether the viewport shows a coarse frame (Interaction, accumulation.h).
    bool coarse() const { return coarse_; }
    // The fraction of the window's size the viewport image was rendered at (1 at rest).
    double shownScale() const { return shownScale_; }
    // Successful renders so far (a frame rendered when this grew).
    uint64_t renders() const { return renders_; }
    const std::optional<gpu::GpuRender>& lastRender() const { return last_; }

    void notify(const std::string& text, double now);
    std::deque<Notification>& notifications() { return notifications_; }

    // Called with every action that succeeded (--record writes them as a replayable script).
    std::function<void(const Action&)> recorder;

    // Pending editor-side requests a script or the UI made (consumed by main.cpp).
    bool quitRequested = false;
    double waitSeconds = 0.0;
    std::string screenshotRequest;
    GizmoMode gizmoMode = GizmoMode::Translate;
    std::string pendingOpen;  // a dropped scene waiting for the unsaved-changes prompt
    // Set by an action a script must wait on (tradeoff wait): the script resumes once it returns true.
    std::function<bool()> waitUntil;
    QualityTool qualityTool;  // the Quality panel's measurement (quality_panel.h)
    double frameMs = 0.0;
    float viewAspect = 16.0f / 9.0f;  // for pick before the first render

private:
    Result<void> dispatch(const Action& a);
    Result<void> camera(const Action& a);
    Result<void> viewAction(const Action& a);
    Result<void> setCamera(const Camera& c);
    Result<void> fileAction(const Action& a);
    Result<void> timeAction(const Action& a);
    void drop(const std::string& path);

    Document doc_;
    Autosave autosave_;
    Files files_{RecentFiles(recentFilesPath())};
    Selection selection_;
    Quality quality_;
    DebugViewState debug_;
    SceneTime time_{true};
    glm::ivec2 viewSize_{0};
    bool hasImage_ = false;
    bool coarse_ = false;
    uint64_t renders_ = 0;
    Interaction interaction_;
    double shownScale_ = 1.0;
    // After a frame at rest, the next frame makes the pipelines of the next coarse frame (when there are
    // coarse frames) and of the frames at rest, with their fallbacks (gpu::GpuRenderer::preparePipelines),
    // unless they were made for this document and size.
    struct PreparedKey {
        uint64_t revision = ~uint64_t(0);
        int width = 0, height = 0, debugView = 0;
        bool operator==(const PreparedKey&) const = default;
    };
    bool prepareAtRest_ = false;
    PreparedKey prepared_;
    std::pair<Scene, RenderRequest> frameFor(const ViewPlan& plan) const;
    // The volumes of the scene the last preparation made pipelines for: after a hide or a delete since,
    // a frame whose pipelines are not made renders the missing volumes as dark stand-ins if the
    // pipelines for that list are (view.h withStandIns): the same image, without compiling on that frame.
    std::vector<Volume> preparedVolumes_;
    bool measureFrame_ = false;  // the last frame rendered a steady coarse plan: frameMs times it
    std::optional<gpu::GpuRender> last_;
    Accumulation accumulation_;
    std::deque<Notification> notifications_;
};

}  // namespace brume::editor
