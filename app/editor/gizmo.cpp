#include "gizmo.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

#include <imgui.h>

#include "core/influence.h"
#include "core/settings.h"
#include "editor.h"
#include "view.h"

namespace brume::editor {
namespace {

constexpr float kSnapMetres = 0.25f;  // translate, Ctrl held
constexpr float kSnapDegrees = 15.0f;  // rotate, Ctrl held
constexpr float kSnapScale = 0.1f;     // scale, Ctrl held
constexpr float kHitPx = 6.0f;         // handle pick distance
constexpr int kRingSegments = 64;
const ImU32 kAxisColors[3] = {IM_COL32(230, 60, 60, 255), IM_COL32(60, 210, 60, 255), IM_COL32(70, 110, 240, 255)};
const ImU32 kHot = IM_COL32(255, 230, 80, 255);
const ImU32 kCentre = IM_COL32(220, 220, 220, 255);

const char* kindWord(Kind k) { return k == Kind::Volume ? "volume" : k == Kind::Light ? "light" : "geometry"; }

std::string num(float x) {
    char buf[32];
    auto r = std::to_chars(buf, buf + sizeof buf, x);
    return std::string(buf, r.ptr);
}

float segmentDistance(ImVec2 p, ImVec2 a, ImVec2 b) {
    const glm::vec2 ab(b.x - a.x, b.y - a.y), ap(p.x - a.x, p.y - a.y);
    const float t = std::clamp(glm::dot(ap, ab) / std::max(glm::dot(ab, ab), 1e-6f), 0.0f, 1.0f);
    return glm::length(ap - ab * t);
}

std::optional<glm::vec3> currentVec3(const Editor& e, const std::string& path) {
    if (path.empty()) return std::nullopt;
    Result<std::string> t = e.doc().valueText(path);
    if (!t) return std::nullopt;
    glm::vec3 v(0.0f);
    if (std::sscanf(t.value().c_str(), "[%f,%f,%f]", &v.x, &v.y, &v.z) != 3) return std::nullopt;
    return v;
}

glm::vec3 unit(int i) {
    glm::vec3 a(0.0f);
    a[i] = 1.0f;
    return a;
}

// What every mode needs this frame: the view, the pivot on screen, the cursor's ray.
struct View {
    const Camera* cam = nullptr;
    float aspect = 1.0f;
    ImVec2 size, pivotPx;
    glm::vec3 pivot{0.0f}, ray{0.0f};
    float len = 1.0f;  // handle length [m]: a fifth of the view height at the pivot
    ImDrawList* draw = nullptr;
    bool canHover = false;

    std::optional<ImVec2> px(glm::vec3 p) const {
        const std::optional<glm::vec2> w = windowFromWorld(*cam, aspect, p);
        if (!w) return std::nullopt;
        return ImVec2(w->x * size.x, w->y * size.y);
    }
};

std::optional<View> viewOf(const Camera& cam, glm::vec3 pivot, bool dragging) {
    const ImGuiIO& io = ImGui::GetIO();
    View v;
    v.cam = &cam;
    v.size = io.DisplaySize;
    if (v.size.x <= 0 || v.size.y <= 0) return std::nullopt;
    v.aspect = v.size.x / v.size.y;
    v.pivot = pivot;
    const std::optional<glm::vec2> o = windowFromWorld(cam, v.aspect, pivot);
    if (!o) return std::nullopt;
    v.pivotPx = ImVec2(o->x * v.size.x, o->y * v.size.y);
    const float depth = glm::dot(pivot - cam.position, glm::normalize(cam.target - cam.position));
    v.len = 0.2f * 2.0f * std::tan(glm::radians(cam.fov_y_deg) * 0.5f) * depth;
    v.ray = rayDirection(cam, v.aspect, io.MousePos.x / v.size.x, io.MousePos.y / v.size.y);
    v.draw = ImGui::GetBackgroundDrawList();
    v.canHover = !dragging && !io.WantCaptureMouse;
    return v;
}

void setVec3(Editor& e, const std::string& path, glm::vec3 v, glm::vec3 current, double now) {
    if (v == current) return;
    if (Result<void> r = e.run("set " + path + " " + num(v.x) + " " + num(v.y) + " " + num(v.z)); !r)
        e.notify(r.error().message, now);
}

// Starts a drag on the hovered handle (`begin`), ends it on release (`end`); true while dragging.
// The release frame still belongs to the gizmo (callers return true), so the viewport neither
// picks nor ends a group it did not begin.
bool pressAndRelease(Editor& e, GizmoState& g, int hovered, const std::string& path, glm::vec3 value) {
    if (g.axis < 0 && hovered >= 0 && ImGui::IsMouseClicked(0)) {
        const ImVec2 m = ImGui::GetIO().MousePos;
        g.axis = hovered, g.start = value, g.path = path, g.pressPx = {m.x, m.y};
        (void)e.run("begin");
    }
    if (g.axis >= 0 && !ImGui::IsMouseDown(0)) {
        (void)e.run("end");
        g.axis = -1;
    }
    return g.axis >= 0;
}

// Arrows (translate) or square-tipped lines (scale) from the pivot along `axes`; the hovered one is
// found before any is drawn, so only it lights up (they all meet at the pivot). `centre`: the scale
// gizmo's uniform square, which wins near the pivot.
int axisHandles(const View& v, const GizmoState& g, const glm::vec3 (&axes)[3], bool centre) {
    const ImVec2 m = ImGui::GetIO().MousePos;
    std::optional<ImVec2> tips[3];
    int hovered = -1;
    const bool nearPivot = std::abs(m.x - v.pivotPx.x) < 2.0f * kHitPx && std::abs(m.y - v.pivotPx.y) < 2.0f * kHitPx;
    if (centre && v.canHover && nearPivot) hovered = 3;
    for (int i = 0; i < 3; ++i) {
        tips[i] = v.px(v.pivot + axes[i] * v.len);
        if (tips[i] && hovered < 0 && v.canHover && segmentDistance(m, v.pivotPx, *tips[i]) < kHitPx) hovered = i;
    }
    for (int i = 0; i < 3; ++i) {
        if (!tips[i]) continue;
        const bool hot = g.axis == i || (g.axis < 0 && hovered == i);
        const ImU32 col = hot ? kHot : kAxisColors[i];
        const float r = hot ? 6.0f : 4.5f;
        v.draw->AddLine(v.pivotPx, *tips[i], col, hot ? 4.0f : 2.5f);
        if (centre) v.draw->AddRectFilled(ImVec2(tips[i]->x - r, tips[i]->y - r), ImVec2(tips[i]->x + r, tips[i]->y + r), col);
        else v.draw->AddCircleFilled(*tips[i], r, col);
    }
    if (centre) {
        const bool hot = g.axis == 3 || (g.axis < 0 && hovered == 3);
        const float r = 7.0f;
        v.draw->AddRect(ImVec2(v.pivotPx.x - r, v.pivotPx.y - r), ImVec2(v.pivotPx.x + r, v.pivotPx.y + r),
                        hot ? kHot : kCentre, 0.0f, 0, 2.5f);
    }
    return hovered;
}

int translateHandles(const View& v, const GizmoState& g) {
    const glm::vec3 axes[3] = {unit(0), unit(1), unit(2)};
    return axisHandles(v, g, axes, false);
}

bool translate(Editor& e, GizmoState& g, const View& v, const std::string& path, double now) {
    const int hovered = translateHandles(v, g);
    const bool wasIdle = g.axis < 0;
    if (!pressAndRelease(e, g, hovered, path, v.pivot)) return !wasIdle || (hovered >= 0 && !ImGui::IsAnyMouseDown());
    const glm::vec3 axis = unit(g.axis);
    if (wasIdle) {
        const std::optional<float> s0 = axisParam(v.pivot, axis, v.cam->position, v.ray);
        if (!s0) return (void)e.run("end"), g.axis = -1, false;  // along the view: no stable drag
        g.s0 = *s0;
    }
    if (std::optional<float> s = axisParam(g.start, axis, v.cam->position, v.ray))
        setVec3(e, g.path, axisDrag(g.start, axis, g.s0, *s, ImGui::GetIO().KeyCtrl ? kSnapMetres : 0.0f), v.pivot, now);
    return true;
}

int rotateHandles(const View& v, const GizmoState& g) {
    int hovered = -1;
    std::vector<ImVec2> rings[3];
    for (int i = 0; i < 3; ++i) {
        const glm::vec3 u = unit((i + 1) % 3), w = unit((i + 2) % 3);
        for (int k = 0; k <= kRingSegments; ++k) {
            const float t = 6.2831853f * static_cast<float>(k) / kRingSegments;
            if (std::optional<ImVec2> p = v.px(v.pivot + (u * std::cos(t) + w * std::sin(t)) * v.len)) rings[i].push_back(*p);
        }
        for (size_t k = 1; k < rings[i].size() && v.canHover && hovered < 0; ++k)
            if (segmentDistance(ImGui::GetIO().MousePos, rings[i][k - 1], rings[i][k]) < kHitPx) hovered = i;
    }
    for (int i = 0; i < 3; ++i) {
        const bool hot = g.axis == i || (g.axis < 0 && hovered == i);
        v.draw->AddPolyline(rings[i].data(), static_cast<int>(rings[i].size()), hot ? kHot : kAxisColors[i], 0, hot ? 4.0f : 2.5f);
    }
    return hovered;
}

bool rotate(Editor& e, GizmoState& g, const View& v, const std::string& path, glm::vec3 value, bool isDirection,
            double now) {
    const int hovered = rotateHandles(v, g);
    const bool wasIdle = g.axis < 0;
    if (!pressAndRelease(e, g, hovered, path, value)) return !wasIdle || (hovered >= 0 && !ImGui::IsAnyMouseDown());
    const std::optional<float> a = ringAngle(v.pivot, unit(g.axis), v.cam->position, v.ray);
    if (wasIdle) {
        if (!a) return (void)e.run("end"), g.axis = -1, false;  // the ring is edge-on
        g.prevAngle = *a, g.totalAngle = 0.0f;
    } else if (a) {
        g.totalAngle += wrapDegrees(*a - g.prevAngle);
        g.prevAngle = *a;
    }
    const float angle = snapped(g.totalAngle, ImGui::GetIO().KeyCtrl ? kSnapDegrees : 0.0f);
    // A direction stays a unit vector; its components within the setting's [-1, 1].
    const glm::vec3 next = isDirection ? glm::clamp(rotateDirection(g.start, g.axis, angle), -1.0f, 1.0f)
                                       : rotateEuler(g.start, g.axis, angle);
    setVec3(e, g.path, next, value, now);
    return true;
}

int scaleHandles(const View& v, const GizmoState& g, glm::vec3 rotationDeg) {
    const glm::vec3 axes[3] = {localAxis(rotationDeg, 0), localAxis(rotationDeg, 1), localAxis(rotationDeg, 2)};
    return axisHandles(v, g, axes, true);
}

bool scale(Editor& e, GizmoState& g, const View& v, const std::string& path, glm::vec3 value, glm::vec3 rotationDeg,
           double now) {
    const int hovered = scaleHandles(v, g, rotationDeg);
    const bool wasIdle = g.axis < 0;
    if (!pressAndRelease(e, g, hovered, path, value)) return !wasIdle || (hovered >= 0 && !ImGui::IsAnyMouseDown());
    std::optional<float> factor;
    const ImVec2 m = ImGui::GetIO().MousePos;
    if (g.axis == 3) {
        const glm::vec2 pivotPx(v.pivotPx.x, v.pivotPx.y);
        const std::optional<ImVec2> tip = v.px(v.pivot + glm::normalize(v.cam->up) * v.len);
        const float lenPx = tip ? glm::length(glm::vec2(tip->x, tip->y) - pivotPx) : 100.0f;
        factor = uniformScaleFactor(m.x - g.pressPx.x, g.pressPx.y - m.y, lenPx);
    } else {
        const glm::vec3 axis = localAxis(rotationDeg, g.axis);
        const std::optional<float> s = axisParam(v.pivot, axis, v.cam->position, v.ray);
        if (wasIdle) {
            if (!s) return (void)e.run("end"), g.axis = -1, false;
            g.s0 = *s;
        }
        if (s) factor = axisScaleFactor(g.s0, *s);
    }
    if (factor) {
        const float snap = ImGui::GetIO().KeyCtrl ? kSnapScale : 0.0f;
        setVec3(e, g.path, scaleDrag(g.start, g.axis, *factor, snap, static_cast<float>(settings::transform_scale.min)), value, now);
    }
    return true;
}

// The selected volume's shape, thin, under the handles (view.h volumeWireframe).
void outline(const View& v, const Volume& vol) {
    for (const std::array<glm::vec3, 2>& seg : volumeWireframe(vol)) {
        const std::optional<ImVec2> a = v.px(seg[0]), b = v.px(seg[1]);
        if (a && b) v.draw->AddLine(*a, *b, kCentre, 1.0f);
    }
}

// The influencer's path (sampled over its points' time span and held beyond), a dot per point, and
// its shape at the scene time: a ring of its radius facing the camera (a capsule: two, ends of its axis).
void drawInfluencer(const View& v, const Influencer& f, float time) {
    const ImU32 pathColor = IM_COL32(120, 200, 255, 200);
    if (!f.path.keys.empty()) {
        const float t0 = f.path.keys.front().time, t1 = f.path.keys.back().time;
        constexpr int kSteps = 96;
        std::optional<ImVec2> prev;
        for (int k = 0; k <= kSteps; ++k) {
            const float t = t0 + (t1 - t0) * static_cast<float>(k) / kSteps;
            const std::optional<ImVec2> p = v.px(influencerPosition(f, t));
            if (p && prev) v.draw->AddLine(*prev, *p, pathColor, 1.5f);
            prev = p;
        }
        for (const Keyframe& key : f.path.keys)
            if (const std::optional<ImVec2> p = v.px(key.value)) v.draw->AddCircleFilled(*p, 3.5f, pathColor);
    }
    const glm::vec3 centre = influencerPosition(f, time);
    const glm::vec3 right = glm::normalize(glm::cross(v.cam->target - v.cam->position, v.cam->up));
    const glm::vec3 up = glm::normalize(glm::cross(right, v.cam->target - v.cam->position));
    const float half = f.type == InfluencerType::Capsule ? 0.5f * f.length : 0.0f;
    for (float end : {-half, half}) {
        std::vector<ImVec2> ring;
        for (int k = 0; k <= kRingSegments; ++k) {
            const float a = 6.2831853f * static_cast<float>(k) / kRingSegments;
            const glm::vec3 p = centre + glm::vec3(0.0f, end, 0.0f) + (right * std::cos(a) + up * std::sin(a)) * f.radius;
            if (const std::optional<ImVec2> q = v.px(p)) ring.push_back(*q);
        }
        v.draw->AddPolyline(ring.data(), static_cast<int>(ring.size()), kCentre, 0, 1.5f);
        if (half == 0.0f) break;
    }
}

// The influencer's gizmo: translate moves the path point nearest the scene time (an undoable set of
// influencers[i].path[k].position); the handles sit on that point.
bool influencerGizmo(Editor& e, GizmoState& g, const Influencer& f, size_t index, double now) {
    if (f.path.keys.empty()) return false;
    const float time = static_cast<float>(e.sceneTime().seconds());
    size_t nearest = 0;
    for (size_t k = 1; k < f.path.keys.size(); ++k)
        if (std::abs(f.path.keys[k].time - time) < std::abs(f.path.keys[nearest].time - time)) nearest = k;
    const std::string path = "influencers[" + std::to_string(index) + "].path[" + std::to_string(nearest) + "].position";
    const std::optional<glm::vec3> pivot = currentVec3(e, path);
    const std::optional<View> v = pivot ? viewOf(e.doc().scene().camera, *pivot, g.axis >= 0) : std::nullopt;
    if (!v) {
        if (g.axis >= 0) (void)e.run("end");
        g.axis = -1;
        return false;
    }
    drawInfluencer(*v, f, time);
    if (e.gizmoMode != GizmoMode::Translate) return false;
    return translate(e, g, *v, path, now);
}

}  // namespace

bool transformGizmo(Editor& e, GizmoState& g, double now) {
    const Selection sel = e.selection();
    const Scene& scene = e.doc().scene();
    if (sel.kind == Kind::Influencer) {
        if (sel.index < scene.influencers.size()) return influencerGizmo(e, g, scene.influencers[sel.index], sel.index, now);
        if (g.axis >= 0) (void)e.run("end");
        g.axis = -1;
        return false;
    }
    const std::string kind = sel.kind == Kind::None ? "" : kindWord(sel.kind);
    const std::optional<glm::vec3> pivot = kind.empty() ? std::nullopt : currentVec3(e, positionPath(scene, kind, sel.index));
    const std::optional<View> v = pivot ? viewOf(scene.camera, *pivot, g.axis >= 0) : std::nullopt;
    if (!v) {
        if (g.axis >= 0) (void)e.run("end");  // the object went away mid-drag (undo, delete)
        g.axis = -1;
        return false;
    }
    if (sel.kind == Kind::Volume && sel.index < scene.volumes.size()) outline(*v, scene.volumes[sel.index]);
    if (e.gizmoMode == GizmoMode::Translate) return translate(e, g, *v, positionPath(scene, kind, sel.index), now);
    const std::string rotPath = rotationPath(scene, kind, sel.index);
    const std::optional<glm::vec3> rot = currentVec3(e, rotPath);
    if (!rot) return false;
    if (e.gizmoMode == GizmoMode::Rotate) return rotate(e, g, *v, rotPath, *rot, sel.kind == Kind::Light, now);
    const std::string sPath = scalePath(scene, kind, sel.index);
    const std::optional<glm::vec3> s = currentVec3(e, sPath);
    return s && scale(e, g, *v, sPath, *s, *rot, now);
}

}  // namespace brume::editor
