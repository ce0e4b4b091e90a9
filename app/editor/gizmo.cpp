#include "gizmo.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <optional>

#include <imgui.h>

#include "editor.h"
#include "view.h"

namespace brume::editor {
namespace {

constexpr float kSnap = 0.25f;    // [m] with Ctrl held
constexpr float kHitPx = 6.0f;    // handle pick distance
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

std::optional<glm::vec3> currentPosition(const Editor& e, const std::string& path) {
    Result<std::string> t = e.doc().valueText(path);
    if (!t) return std::nullopt;
    glm::vec3 v(0.0f);
    if (std::sscanf(t.value().c_str(), "[%f,%f,%f]", &v.x, &v.y, &v.z) != 3) return std::nullopt;
    return v;
}

}  // namespace

bool translateGizmo(Editor& e, GizmoState& g, double now) {
    const Selection sel = e.selection();
    const Scene& scene = e.doc().scene();
    const std::string path = sel.kind == Kind::None ? "" : positionPath(scene, kindWord(sel.kind), sel.index);
    if (path.empty()) return g.axis = -1, false;
    const std::optional<glm::vec3> pos = currentPosition(e, path);
    const ImGuiIO& io = ImGui::GetIO();
    const ImVec2 size = io.DisplaySize;
    if (!pos || size.x <= 0 || size.y <= 0) return false;
    const Camera& cam = scene.camera;
    const float aspect = size.x / size.y;
    const std::optional<glm::vec2> o = windowFromWorld(cam, aspect, *pos);
    if (!o) return false;
    // Handles a fifth of the view height long, whatever the distance.
    const float depth = glm::dot(*pos - cam.position, glm::normalize(cam.target - cam.position));
    const float len = 0.2f * 2.0f * std::tan(glm::radians(cam.fov_y_deg) * 0.5f) * depth;
    const ImVec2 a(o->x * size.x, o->y * size.y);
    const ImU32 colors[3] = {IM_COL32(230, 60, 60, 255), IM_COL32(60, 210, 60, 255), IM_COL32(70, 110, 240, 255)};
    int hovered = -1;
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    for (int i = 0; i < 3; ++i) {
        glm::vec3 axis(0.0f);
        axis[i] = 1.0f;
        const std::optional<glm::vec2> t = windowFromWorld(cam, aspect, *pos + axis * len);
        if (!t) continue;
        const ImVec2 b(t->x * size.x, t->y * size.y);
        if (g.axis < 0 && !io.WantCaptureMouse && segmentDistance(io.MousePos, a, b) < kHitPx) hovered = i;
        const bool hot = g.axis == i || (g.axis < 0 && hovered == i);
        draw->AddLine(a, b, hot ? IM_COL32(255, 230, 80, 255) : colors[i], hot ? 4.0f : 2.5f);
        draw->AddCircleFilled(b, hot ? 6.0f : 4.5f, hot ? IM_COL32(255, 230, 80, 255) : colors[i]);
    }
    if (g.axis < 0 && hovered >= 0 && ImGui::IsMouseClicked(0)) {
        glm::vec3 axis(0.0f);
        axis[hovered] = 1.0f;
        const glm::vec3 dir = rayDirection(cam, aspect, io.MousePos.x / size.x, io.MousePos.y / size.y);
        if (std::optional<float> s0 = axisParam(*pos, axis, cam.position, dir)) {
            g = {hovered, *pos, *s0, path};
            (void)e.run("begin");
        }
    }
    if (g.axis < 0) return hovered >= 0 && !ImGui::IsAnyMouseDown();
    glm::vec3 axis(0.0f);
    axis[g.axis] = 1.0f;
    const glm::vec3 dir = rayDirection(cam, aspect, io.MousePos.x / size.x, io.MousePos.y / size.y);
    if (std::optional<float> s = axisParam(g.start, axis, cam.position, dir)) {
        const glm::vec3 p = axisDrag(g.start, axis, g.s0, *s, io.KeyCtrl ? kSnap : 0.0f);
        if (p != *pos) {
            if (Result<void> r = e.run("set " + g.path + " " + num(p.x) + " " + num(p.y) + " " + num(p.z)); !r)
                e.notify(r.error().message, now);
        }
    }
    if (!ImGui::IsMouseDown(0)) {
        (void)e.run("end");
        g.axis = -1;
    }
    return true;
}

}  // namespace brume::editor
