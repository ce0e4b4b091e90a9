#include "editor.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "core/debug_view.h"
#include "core/quality.h"
#include "preset_shelf.h"
#include "quality_panel.h"
#include "gpu/vk_check.h"
#include "tonemap.h"
#include "view.h"

namespace brume::editor {
namespace {

bool number(const std::string& s, double& out) {
    const char* end = s.data() + s.size();
    auto r = std::from_chars(s.data(), end, out);
    return r.ec == std::errc() && r.ptr == end && std::isfinite(out);
}

std::string vec3Words(glm::vec3 v) {
    auto f = [](float x) {
        char buf[32];
        auto r = std::to_chars(buf, buf + sizeof buf, x);
        return std::string(buf, r.ptr);
    };
    return f(v.x) + " " + f(v.y) + " " + f(v.z);
}

}  // namespace

Editor::Editor(Document doc, Autosave autosave, Quality quality, double interactiveScale, double frameBudgetMs)
    : doc_(std::move(doc)), autosave_(std::move(autosave)), quality_(quality), interaction_(interactiveScale, frameBudgetMs) {}

Result<void> Editor::run(const std::string& line) {
    Result<Action> a = parseAction(line);
    if (!a) return a.error();
    if (a.value().verb.empty()) return {};
    return run(a.value());
}

Result<void> Editor::run(const Action& a) {
    Result<void> r = dispatch(a);
    if (r && recorder) recorder(a);
    return r;
}

Result<void> Editor::dispatch(const Action& a) {
    if (Files::isFileVerb(a.verb)) return fileAction(a);
    if (a.verb == "drop") {
        for (const std::string& path : a.args) drop(path);
        return {};
    }
    if (Document::isDocumentVerb(a.verb)) {
        Result<void> r = doc_.apply(a);
        if (r && a.verb == "save") files_.noteRecent(doc_.path());
        // Deleting can leave the selection past the end of its list.
        const Scene& s = doc_.scene();
        const size_t n = selection_.kind == Kind::Volume ? s.volumes.size()
                         : selection_.kind == Kind::Light ? s.lights.size()
                         : selection_.kind == Kind::Influencer ? s.influencers.size()
                                                          : s.geometry.size();
        if (selection_.kind != Kind::None && selection_.index >= n) selection_.kind = Kind::None;
        return r;
    }
    double v = 0.0;
    if (a.verb == "select") {
        if (a.args.size() == 1 && a.args[0] == "none") return selection_.kind = Kind::None, Result<void>();
        if (a.args.size() != 2 || !number(a.args[1], v) || v < 0) return Error{"select takes: select volume|light|geometry|influencer INDEX."};
        const Kind k = a.args[0] == "volume" ? Kind::Volume : a.args[0] == "light" ? Kind::Light
                     : a.args[0] == "geometry" ? Kind::Geometry : a.args[0] == "influencer" ? Kind::Influencer : Kind::None;
        if (k == Kind::None) return Error{"select takes: select volume|light|geometry|influencer INDEX."};
        selection_ = {k, static_cast<size_t>(v)};
        return {};
    }
    if (a.verb == "orbit" || a.verb == "pan" || a.verb == "zoom") return camera(a);
    if (a.verb == "fly" || a.verb == "look" || a.verb == "frame" || a.verb == "pick") return viewAction(a);
    if (a.verb == "quality") {
        Quality q;
        if (a.args.size() != 1 || !parseQuality(a.args[0], q)) return Error{"quality takes one of: low, medium, high, ultra."};
        quality_ = q;
        return {};
    }
    if (a.verb == "debug") {
        Result<void> r = runDebugAction(debug_, a, resolveFroxelSettings(doc_.scene(), quality_));
        if (r && debug_.errorMap) requestHeatMap(*this);  // debug error: the heat map (quality_panel.h)
        return r;
    }
    if (a.verb == "tradeoff") return runQualityAction(*this, a);
    if (a.verb == "wait") {
        if (a.args.size() != 1 || !number(a.args[0], v) || v < 0) return Error{"wait takes a number of seconds."};
        waitSeconds = v;
        return {};
    }
    if (a.verb == "screenshot") {
        if (a.args.size() != 1) return Error{"screenshot takes: screenshot FILE.png."};
        screenshotRequest = a.args[0];
        return {};
    }
    if (a.verb == "time" || a.verb == "play") return timeAction(a);
    if (a.verb == "preset") return runPresetAction(doc_, a);  // preset_shelf.h
    if (a.verb == "quit") return quitRequested = true, Result<void>();
    if (a.verb == "gizmo") {
        const std::string m = a.args.size() == 1 ? a.args[0] : "";
        if (m != "translate" && m != "rotate" && m != "scale") return Error{"gizmo takes one of: translate, rotate, scale."};
        gizmoMode = m == "translate" ? GizmoMode::Translate : m == "rotate" ? GizmoMode::Rotate : GizmoMode::Scale;
        return {};
    }
    return Error{"Unknown action \"" + a.verb + "\"."};
}

// time SECONDS, play on|off: view state, so no undo step and nothing for the document to save.
Result<void> Editor::timeAction(const Action& a) {
    double t = 0.0;
    if (a.verb == "time") {
        if (a.args.size() != 1 || !number(a.args[0], t) || std::abs(t) > 1.0e6)
            return Error{"time takes a number of seconds (-1e6..1e6)."};
        time_.set(t);
        return {};
    }
    if (a.args.size() != 1 || (a.args[0] != "on" && a.args[0] != "off")) return Error{"play takes: play on|off."};
    time_.play(a.args[0] == "on");
    return {};
}

// New and Open start a new document: nothing selected, the autosave beside the new file. An
// import selects the new volume.
Result<void> Editor::fileAction(const Action& a) {
    Result<void> r = files_.apply(doc_, a);
    if (!r) return r;
    if (a.verb == "import") {
        selection_ = {Kind::Volume, doc_.scene().volumes.size() - 1};
    } else {
        selection_.kind = Kind::None;
        autosave_.retarget(recoveryPathFor(doc_.path()));
    }
    return {};
}

// A file dropped on the window. Not an edit itself: what it leads to runs as its own action
// (unrecorded: replaying the drop replays it), and a failure is a notification.
void Editor::drop(const std::string& path) {
    const std::string ext = std::filesystem::path(path).extension().string();
    Result<void> r;
    if (ext == ".vdb") r = fileAction({"import", {"vdb", path}});
    else if (ext == ".obj" || ext == ".ply") r = fileAction({"import", {"mesh", path}});
    else if (ext == ".json" && doc_.dirty()) pendingOpen = path;
    else if (ext == ".json") r = fileAction({"open", {path}});
    else r = Error{path + ": drop a scene (.json), an OpenVDB file (.vdb) or a closed mesh (.obj, .ply)."};
    if (!r) files_.message(r.error().message);
}

Result<void> Editor::setCamera(const Camera& c) {
    // Position and target move together: one undo step (nested in a drag's group, if any).
    auto words = [](const std::string& path, glm::vec3 v) {
        Result<Action> a = parseAction("set " + path + " " + vec3Words(v));
        return a.value();
    };
    (void)doc_.apply({"begin", {}});
    Result<void> r = doc_.apply(words("camera.position", c.position));
    if (r) r = doc_.apply(words("camera.target", c.target));
    (void)doc_.apply({"end", {}});
    return r;
}

Result<void> Editor::camera(const Action& a) {
    double x = 0.0, y = 0.0;
    const size_t want = a.verb == "zoom" ? 1 : 2;
    if (a.args.size() != want || !number(a.args[0], x) || (want == 2 && !number(a.args[1], y)))
        return Error{"Camera actions take: orbit YAW_DEG PITCH_DEG, pan RIGHT UP, zoom FACTOR."};
    Camera c = doc_.scene().camera;
    const glm::vec3 up = glm::normalize(c.up);
    glm::vec3 offset = c.position - c.target;
    const float dist = glm::length(offset);
    const glm::vec3 forward = -offset / dist;
    const glm::vec3 right = glm::normalize(glm::cross(forward, up));
    const glm::vec3 camUp = glm::cross(right, forward);
    if (a.verb == "orbit") {
        glm::mat4 yaw = glm::rotate(glm::mat4(1.0f), glm::radians(static_cast<float>(x)), up);
        offset = glm::vec3(yaw * glm::vec4(offset, 0.0f));
        // Pitch stops 1 degree short of the poles, where the view would flip about `up`.
        const float elevation = std::asin(std::clamp(glm::dot(glm::normalize(offset), up), -1.0f, 1.0f));
        const float limit = glm::radians(89.0f);
        const float pitch = std::clamp(elevation + glm::radians(static_cast<float>(y)), -limit, limit) - elevation;
        const glm::vec3 r = glm::normalize(glm::cross(up, offset));
        offset = glm::vec3(glm::rotate(glm::mat4(1.0f), pitch, r) * glm::vec4(offset, 0.0f));
        c.position = c.target + offset;
    } else if (a.verb == "pan") {
        const glm::vec3 d = (right * static_cast<float>(x) + camUp * static_cast<float>(y)) * dist;
        c.position += d;
        c.target += d;
    } else {
        if (x <= 0.0) return Error{"zoom takes a factor above 0."};
        c.position = c.target + offset * static_cast<float>(x);
    }
    return setCamera(c);
}

static const char* kindWord(Kind k) {
    return k == Kind::Volume ? "volume" : k == Kind::Light ? "light" : k == Kind::Geometry ? "geometry"
         : k == Kind::Influencer ? "influencer" : "none";
}

// fly RIGHT UP FORWARD [m], look YAW PITCH [deg], frame (the selection), pick U V (window
// fractions from the top-left; selects what is under it, or nothing).
Result<void> Editor::viewAction(const Action& a) {
    std::vector<float> n;
    for (const std::string& w : a.args) {
        double x = 0.0;
        if (!number(w, x)) return Error{a.verb + ": \"" + w + "\" is not a number."};
        n.push_back(static_cast<float>(x));
    }
    const Camera& c = doc_.scene().camera;
    if (a.verb == "fly") {
        if (n.size() != 3) return Error{"fly takes: fly RIGHT UP FORWARD (metres)."};
        return setCamera(flyCamera(c, {n[0], n[1], n[2]}));
    }
    if (a.verb == "look") {
        if (n.size() != 2) return Error{"look takes: look YAW_DEG PITCH_DEG."};
        return setCamera(lookCamera(c, n[0], n[1]));
    }
    if (a.verb == "frame") {
        if (!n.empty()) return Error{"frame takes no arguments: it frames the selection."};
        if (selection_.kind == Kind::None) return Error{"Select an object to frame first."};
        Result<Bounds> b = objectBounds(doc_.scene(), kindWord(selection_.kind), selection_.index);
        if (!b) return b.error();
        return setCamera(frameCamera(c, b.value()));
    }
    if (n.size() != 2 || n[0] < 0.0f || n[0] > 1.0f || n[1] < 0.0f || n[1] > 1.0f)
        return Error{"pick takes: pick U V (window fractions in [0, 1] from the top-left)."};
    const float aspect = viewSize_.y > 0 ? static_cast<float>(viewSize_.x) / static_cast<float>(viewSize_.y) : viewAspect;
    const std::optional<Picked> p = pick(doc_.scene(), aspect, n[0], n[1]);
    if (!p) selection_.kind = Kind::None;
    else selection_ = {p->kind == "light" ? Kind::Light : Kind::Volume, p->index};
    return {};
}

std::pair<Scene, RenderRequest> Editor::frameFor(const ViewPlan& plan) const {
    RenderRequest request;
    request.width = plan.width;
    request.height = plan.height;
    request.quality = plan.quality;
    request.history = plan.restartHistory ? HistoryMode::Restart : HistoryMode::Continue;
    request.debugView = debug_.view;
    request.debugSlice = debug_.slice;
    request.reuseSurfaces = true;  // at rest the surfaces do not change from frame to frame
    // Where the pipelines for this frame's surface lights or volumes in reach are not made yet (a light
    // or a volume crossing the view's reach mid-drag), their fallbacks: the same image, no compile on
    // this frame. At rest too, so that the first full-preset frame after such a drag does not compile
    // either: the next preparation (renderIfNeeded) makes the pipelines of the new reach.
    request.pipelineFallbacks = true;
    Scene shown = visibleScene(doc_.scene());
    shown.time_s = static_cast<float>(time_.seconds());
    if (plan.coarse) shown.froxels.tile_px = coarseTilePx(resolveFroxelSettings(shown, Quality::Low).tile_px, plan.scale);
    return {std::move(shown), request};
}

Result<void> Editor::renderIfNeeded(gpu::GpuRenderer& renderer, int width, int height, bool force) {
    if (std::exchange(measureFrame_, false)) interaction_.measured(frameMs);
    const ViewPlan plan = interaction_.plan(doc_.revision(), doc_.grouping(), quality_, width, height);
    if (std::exchange(prepareAtRest_, false) && !plan.moving) {
        // The frame after one at rest: the pipelines of the next drag's coarse frame are made now, while
        // the view rests, not on that frame (a new set of lights or volumes, or the session's first),
        // with the fallbacks it takes where a light or a volume crosses the view's reach mid-drag.
        // Without coarse frames (maxScale 1) the frames in motion are the rest plan's.
        const bool coarse = interaction_.maxScale() < 1.0;
        const ViewPlan next = coarse ? interaction_.coarsePlan(width, height) : plan;
        const PreparedKey k{doc_.revision(), next.width, next.height, debug_.view};
        if (!(k == prepared_)) {
            prepared_ = k;
            // And those of this view's frames at rest: after a drag that took a volume or a light across
            // the view's reach, the frames at rest took the fallbacks (the same image, slower) until now.
            // One batch: what both lack compiles together.
            std::vector<std::pair<Scene, RenderRequest>> renders{frameFor(plan)};
            if (coarse) renders.push_back(frameFor(next));
            (void)renderer.preparePipelines(renders);  // a failure is the frame's to report
            preparedVolumes_ = renders.front().first.volumes;
        }
    }
    const ViewKey key{doc_.revision(), plan.quality, plan.width, plan.height, debug_.view, debug_.slice, time_.seconds()};
    if (!accumulation_.wantsFrame(key, doc_.scene(), force)) return {};
    auto [shown, request] = frameFor(plan);
    if (shown.volumes.size() < preparedVolumes_.size()) {
        // A volume hidden or deleted since the last preparation: where this scene's pipelines are not
        // made (its volume list is new: 0.4-1 s of compiling on lavapipe) but those of the list with
        // the missing volumes as dark stand-ins are (the list of before), the stand-ins: the same
        // image. The next preparation at rest makes this scene's, and the frames after it render it.
        const Result<bool> ready = renderer.hasPipelines(shown, request);
        if (ready && !ready.value()) {
            std::optional<Scene> standIns = withStandIns(shown, preparedVolumes_);
            if (standIns) {
                const Result<bool> standInsReady = renderer.hasPipelines(*standIns, request);
                if (standInsReady && standInsReady.value()) shown = std::move(*standIns);
            }
        }
    }
    Result<gpu::GpuRender> out = renderer.renderOnDevice(shown, request);
    accumulation_.rendered(key);  // also after an error: a failing scene is not retried every frame
    hasImage_ = out.ok();
    if (!out && gpu::isGpuFault(out.error()) && quality_ != Quality::Low) {
        // Out of GPU memory or device lost (gpu/vk_check.h): the next frame tries the preset below.
        quality_ = static_cast<Quality>(static_cast<int>(quality_) - 1);
        return Error{out.error().message + " The viewport falls back to quality " + toString(quality_) + "."};
    }
    if (!out) return out.error();
    viewSize_ = glm::ivec2(width, height);
    coarse_ = plan.coarse;
    prepareAtRest_ = !plan.moving;
    // A frame that compiled pipelines or allocated memory is no measure of the next ones: it must not
    // shrink the coarse scale for the rest of the interaction (accumulation.h Interaction::measured).
    measureFrame_ = plan.steady && !out.value().compiled && !out.value().allocated;
    shownScale_ = plan.scale;
    ++renders_;
    if (debug_.view != shd::DEBUG_VIEW_FINAL) debug_.legend = debugViewLegend(visibleScene(doc_.scene()), request);
    last_ = std::move(out.value());
    return {};
}

void Editor::rendererReplaced() {
    hasImage_ = false;
    last_.reset();
    accumulation_ = Accumulation();
    prepared_ = PreparedKey{};  // the new renderer has made no pipeline yet
}

gpu::OutputImage Editor::viewportImage(const gpu::GpuRenderer& renderer) const {
    return hasImage_ ? renderer.outputImage() : gpu::OutputImage{};
}

void Editor::notify(const std::string& text, double now) {
    notifications_.push_back({text, now + 6.0});
    while (notifications_.size() > 5) notifications_.pop_front();
}

}  // namespace brume::editor
