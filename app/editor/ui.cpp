#include "ui.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <nlohmann/json.hpp>

#include "core/settings.h"
#include "debug_panel.h"
#include "gizmo.h"
#include "quality_panel.h"
#include "view.h"
#include "io/scene_json.h"

namespace brume::editor {
namespace {

using json = nlohmann::json;

void runOrNotify(Editor& e, const std::string& line, double now) {
    Result<void> r = e.run(line);
    if (!r) e.notify(r.error().message, now);
}

std::string fmt(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

const char* kindName(Kind k) {
    return k == Kind::Volume ? "volume" : k == Kind::Light ? "light" : k == Kind::Influencer ? "influencer" : "geometry";
}
const char* collectionName(Kind k) {
    return k == Kind::Volume ? "volumes" : k == Kind::Light ? "lights" : k == Kind::Influencer ? "influencers" : "geometry";
}

// The part of a setting's path below the element, if the setting applies to `collection` elements
// of `type`: "volumes[type=box].edge_fade" -> "edge_fade" for a box volume.
std::optional<std::string> relativeKey(const Setting& s, const std::string& collection, const std::string& type) {
    const std::string path(s.path);
    const size_t dot = path.find('.');
    if (dot == std::string::npos) return std::nullopt;
    const std::string head = path.substr(0, dot), rest = path.substr(dot + 1);
    if (head == "*") return rest;
    if (head.substr(0, head.find('[')) != collection || head.find('[') == std::string::npos) return std::nullopt;
    const size_t eq = head.find("[type=");
    if (eq != std::string::npos) {
        const std::string types = "|" + head.substr(eq + 6, head.size() - eq - 7) + "|";
        if (types.find("|" + type + "|") == std::string::npos) return std::nullopt;
    }
    return rest;
}

const json* at(const json& j, const std::string& dotted) {
    const json* cur = &j;
    size_t start = 0;
    while (start <= dotted.size()) {
        const size_t dot = dotted.find('.', start);
        const std::string key = dotted.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
        if (!cur->is_object() || !cur->contains(key)) return nullptr;
        cur = &(*cur)[key];
        if (dot == std::string::npos) break;
        start = dot + 1;
    }
    return cur;
}

void tooltip(const Setting& s) {
    if (!ImGui::IsItemHovered()) return;
    std::string t(s.help);
    if (s.kind == SettingKind::Number || s.kind == SettingKind::Integer || s.kind == SettingKind::Vec3)
        t += "\nRange: [" + fmt(s.min) + ", " + fmt(s.max) + "]" + (s.unit.empty() ? "" : " " + std::string(s.unit)) +
             "   Default: " + fmt(s.def[0]);
    ImGui::SetTooltip("%s", t.c_str());
}

bool isColor(const std::string& key) {
    for (const char* c : {"color", "albedo", "scattering", "absorption", "emission", "ambient"})
        if (key.size() >= std::strlen(c) && key.compare(key.size() - std::strlen(c), std::string::npos, c) == 0) return true;
    return false;
}

// One widget for one setting; an edit becomes "set PATH VALUE" (drags bracketed by begin/end).
void settingWidget(Editor& e, const Setting& s, const std::string& path, const json& value, double now) {
    const std::string key = path.substr(path.rfind('.') == std::string::npos ? 0 : path.rfind('.') + 1);
    if (key == "type") {
        ImGui::Text("type: %s", value.get<std::string>().c_str());
        return;
    }
    const std::string label = key + (s.unit.empty() ? "" : " [" + std::string(s.unit) + "]") + "##" + path;
    std::string edit;
    const float lo = static_cast<float>(s.min), hi = static_cast<float>(s.max);
    if (s.kind == SettingKind::Number && value.is_number()) {
        float f = value.get<float>();
        const float speed = std::max(0.001f, std::abs(f) * 0.01f);
        if (ImGui::DragFloat(label.c_str(), &f, speed, lo, hi, "%.4g", ImGuiSliderFlags_AlwaysClamp)) edit = fmt(f);
    } else if (s.kind == SettingKind::Integer && value.is_number()) {
        int i = value.get<int>();
        if (ImGui::DragInt(label.c_str(), &i, 1.0f, static_cast<int>(s.min), static_cast<int>(s.max))) edit = std::to_string(i);
    } else if (s.kind == SettingKind::Vec3 && value.is_array() && value.size() == 3) {
        float v[3] = {value[0].get<float>(), value[1].get<float>(), value[2].get<float>()};
        const bool changed = isColor(key)
            ? ImGui::ColorEdit3(label.c_str(), v, ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR)
            : ImGui::DragFloat3(label.c_str(), v, 0.01f, lo, hi, "%.3f");
        if (changed) edit = fmt(std::clamp(v[0], lo, hi)) + " " + fmt(std::clamp(v[1], lo, hi)) + " " + fmt(std::clamp(v[2], lo, hi));
    } else if (s.kind == SettingKind::Bool && value.is_boolean()) {
        bool b = value.get<bool>();
        if (ImGui::Checkbox(label.c_str(), &b)) edit = b ? "true" : "false";
    } else if (s.kind == SettingKind::Choice && value.is_string()) {
        const std::string cur = value.get<std::string>();
        if (ImGui::BeginCombo(label.c_str(), cur.c_str())) {
            std::string choices(s.choices);
            for (size_t start = 0; start <= choices.size();) {
                const size_t bar = std::min(choices.find('|', start), choices.size());
                const std::string c = choices.substr(start, bar - start);
                if (ImGui::Selectable(c.c_str(), c == cur) && c != cur) edit = c;
                start = bar + 1;
            }
            ImGui::EndCombo();
        }
    } else if (s.kind == SettingKind::String && value.is_string()) {
        char buf[256];
        std::snprintf(buf, sizeof buf, "%s", value.get<std::string>().c_str());
        if (ImGui::InputText(label.c_str(), buf, sizeof buf, ImGuiInputTextFlags_EnterReturnsTrue)) {
            Action a{"set", {path, buf}};
            Result<void> r = e.run(a);
            if (!r) e.notify(r.error().message, now);
        }
        tooltip(s);
        return;
    }
    if (ImGui::IsItemActivated()) (void)e.run("begin");
    if (!edit.empty()) runOrNotify(e, "set " + path + " " + edit, now);
    if (ImGui::IsItemDeactivated()) (void)e.run("end");
    tooltip(s);
}

// An influencer's path points: each one's time and position, edited like any setting (undoable; a
// time out of order is refused with the reader's sentence). The gizmo moves the point nearest the
// scene time (gizmo.cpp).
void influencerPath(Editor& e, const json& obj, const std::string& prefix, double now) {
    if (!obj.contains("path") || !obj["path"].is_array()) return;
    ImGui::Separator();
    ImGui::TextUnformatted("path");
    const json& path = obj["path"];
    for (size_t k = 0; k < path.size(); ++k) {
        const std::string at = prefix + "path[" + std::to_string(k) + "].";
        if (path[k].contains("time")) settingWidget(e, settings::influencer_path_time, at + "time", path[k]["time"], now);
        if (path[k].contains("position")) settingWidget(e, settings::influencer_path_position, at + "position", path[k]["position"], now);
    }
}

void inspector(Editor& e, double now) {
    ImGui::SetNextWindowPos(ImVec2(ImGui::GetIO().DisplaySize.x - 390, 30), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(380, 420), ImGuiCond_FirstUseEver);
    ImGui::Begin("Inspector");
    const json j = json::parse(sceneToJson(e.doc().scene()));
    const Selection sel = e.selection();
    if (sel.kind == Kind::None) {
        ImGui::TextDisabled("Scene (select an object in the Outliner to edit it)");
        for (const Setting* s : settings::kAll) {
            const std::string path(s->path);
            if (path.find('[') != std::string::npos || path[0] == '*') continue;
            if (const json* v = at(j, path)) settingWidget(e, *s, path, *v, now);
        }
    } else {
        const json& obj = j[collectionName(sel.kind)][sel.index];
        const std::string type = obj["type"].get<std::string>();
        const std::string prefix = std::string(collectionName(sel.kind)) + "[" + std::to_string(sel.index) + "].";
        ImGui::Text("%s %zu", kindName(sel.kind), sel.index);
        for (const Setting* s : settings::kAll) {
            const std::optional<std::string> rel = relativeKey(*s, collectionName(sel.kind), type);
            if (!rel) continue;
            if (const json* v = at(obj, *rel)) settingWidget(e, *s, prefix + *rel, *v, now);
        }
        if (sel.kind == Kind::Influencer) influencerPath(e, obj, prefix, now);
    }
    ImGui::End();
}

bool isHidden(const Scene& s, Kind kind, size_t i) {
    return kind == Kind::Volume ? s.volumes[i].hidden : kind == Kind::Light ? s.lights[i].hidden
         : kind == Kind::Influencer ? s.influencers[i].hidden : s.geometry[i].hidden;
}

void outlinerList(Editor& e, Kind kind, const std::vector<std::string>& names, const char* types, double now) {
    const char* kn = kindName(kind);
    if (!ImGui::CollapsingHeader(collectionName(kind), ImGuiTreeNodeFlags_DefaultOpen)) return;
    for (size_t i = 0; i < names.size(); ++i) {
        ImGui::PushID(static_cast<int>(i) + 1000 * static_cast<int>(kind));
        const bool selected = e.selection().kind == kind && e.selection().index == i;
        const std::string target = std::string(kn) + " " + std::to_string(i);
        bool visible = !isHidden(e.doc().scene(), kind, i);
        if (ImGui::Checkbox("##visible", &visible)) runOrNotify(e, (visible ? "show " : "hide ") + target, now);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("Shown in the viewport (H hides the selection; not saved).");
        ImGui::SameLine();
        if (ImGui::Selectable(names[i].c_str(), selected)) runOrNotify(e, "select " + std::string(kn) + " " + std::to_string(i), now);
        if (ImGui::BeginPopupContextItem()) {
            if (ImGui::MenuItem("Duplicate")) runOrNotify(e, "duplicate " + std::string(kn) + " " + std::to_string(i), now);
            if (ImGui::MenuItem("Delete")) runOrNotify(e, "delete " + std::string(kn) + " " + std::to_string(i), now);
            ImGui::EndPopup();
        }
        ImGui::PopID();
    }
    const std::string addId = std::string("Add ") + kn + "...";
    if (ImGui::SmallButton(addId.c_str())) ImGui::OpenPopup(addId.c_str());
    if (ImGui::BeginPopup(addId.c_str())) {
        std::string list(types);
        for (size_t start = 0; start <= list.size();) {
            const size_t bar = std::min(list.find('|', start), list.size());
            const std::string t = list.substr(start, bar - start);
            if (ImGui::MenuItem(t.c_str())) {
                runOrNotify(e, "add " + std::string(kn) + " " + t, now);
                const Scene& s = e.doc().scene();
                const size_t n = kind == Kind::Volume ? s.volumes.size() : kind == Kind::Light ? s.lights.size()
                               : kind == Kind::Influencer ? s.influencers.size() : s.geometry.size();
                runOrNotify(e, "select " + std::string(kn) + " " + std::to_string(n - 1), now);
            }
            start = bar + 1;
        }
        ImGui::EndPopup();
    }
}

template <class T>
std::vector<std::string> labels(const std::vector<T>& items) {
    std::vector<std::string> out;
    for (const T& item : items) out.push_back((item.name.empty() ? "(unnamed)" : item.name) + "  (" + toString(item.type) + ")");
    return out;
}

void outliner(Editor& e, double now) {
    ImGui::SetNextWindowPos(ImVec2(10, 30), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(260, 300), ImGuiCond_FirstUseEver);
    ImGui::Begin("Outliner");
    if (ImGui::Selectable("Scene settings", e.selection().kind == Kind::None)) runOrNotify(e, "select none", now);
    const Scene& s = e.doc().scene();
    outlinerList(e, Kind::Volume, labels(s.volumes), "box|ellipsoid|cylinder|height|depth", now);
    outlinerList(e, Kind::Light, labels(s.lights), "directional|point|spot", now);
    outlinerList(e, Kind::Geometry, labels(s.geometry), "plane|box|sphere", now);
    outlinerList(e, Kind::Influencer, labels(s.influencers), "sphere|capsule", now);
    ImGui::End();
}

// Play/Pause and the scene time: density textures scroll with it (view state, not saved).
void sceneTimeRow(Editor& e, double now) {
    SceneTime& t = e.sceneTime();
    if (ImGui::Button(t.playing() ? "Pause" : "Play")) runOrNotify(e, t.playing() ? "play off" : "play on", now);
    ImGui::SameLine();
    if (ImGui::Button("0")) runOrNotify(e, "time 0", now);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Back to scene time 0.");
    ImGui::SameLine();
    ImGui::Text("time %.2f s%s", t.seconds(), sceneScrolls(e.doc().scene()) ? "" : " (nothing scrolls)");
}

void stats(Editor& e, UiState& ui, double now) {
    if (!ui.showStats) return;
    ImGui::SetNextWindowPos(ImVec2(10, 340), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(260, 370), ImGuiCond_FirstUseEver);  // room for the Debug section
    ImGui::Begin("Stats", &ui.showStats);
    const char* names[] = {"low", "medium", "high", "ultra"};
    int q = static_cast<int>(e.quality());
    if (ImGui::Combo("quality", &q, names, 4)) runOrNotify(e, std::string("quality ") + names[q], now);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Froxel preset of the viewport (docs/quality.md); not saved in the scene.");
    ImGui::Text("frame %.1f ms%s", e.frameMs, e.coarse() ? "  (coarse: interacting)" : "");
    sceneTimeRow(e, now);
    const int converged = convergedFrames(e.doc().scene());
    ImGui::Text("temporal %d / %d frames%s", std::min(e.accumulation().frames(), converged), converged,
                e.accumulation().frames() >= converged ? " (converged)" : "");
    if (const auto& r = e.lastRender()) {
        ImGui::Text("render wall %.1f ms", r->wallMs);
        ImGui::Text("froxels %dx%dx%d", r->dims.x, r->dims.y, r->dims.z);
        ImGui::Text("lit %zu  skipped %zu", r->litFroxels, r->skippedFroxels);
        for (const gpu::PassTiming& p : r->passes) ImGui::Text("  %-10s %7.2f ms", p.name.c_str(), p.gpuMs);
    }
    debugSection(e, now);
    ImGui::End();
}

void help(UiState& ui) {
    if (!ui.showHelp) return;
    ImGui::Begin("Help", &ui.showHelp, ImGuiWindowFlags_AlwaysAutoResize);
    const char* lines[][2] = {
        {"Left drag (viewport)", "orbit the camera around its target"},
        {"Left click (viewport)", "select the volume or light under the cursor"},
        {"Right drag", "look around (fly); with W A S D / Q E flies"},
        {"Middle or Shift+left drag", "pan"},
        {"Right button + W A S D, Q E", "fly forward, left, back, right, down, up (Shift: 4x)"},
        {"W / E / R", "gizmo: translate (world axes) / rotate (world rings) / scale (own axes)"},
        {"Drag a gizmo handle", "one undo step; Ctrl snaps to 0.25 m / 15 deg / 0.1"},
        {"Scale gizmo centre square", "uniform scale (drag right or up to grow)"},
        {"F", "frame the selection"},
        {"H / Alt+H", "hide the selection / show everything"},
        {"Mouse wheel", "zoom"},
        {"Ctrl+Z / Ctrl+Shift+Z, Ctrl+Y", "undo / redo (a drag is one step)"},
        {"Ctrl+S", "save (atomic); File > Save As for a new path"},
        {"Ctrl+N / Ctrl+O", "new scene (camera, sun, ground) / open (asks about unsaved changes)"},
        {"File > Import VDB, or drop", "a .vdb dropped on the window is imported, a .json opened"},
        {"File > Import Mesh, or drop", "a closed .obj or .ply mesh becomes a fog hull (a mesh volume)"},
        {"Ctrl+D / Delete", "duplicate / delete the selection"},
        {"Escape", "select nothing (scene settings)"},
        {"F1", "this help"},
        {"Hover a field", "its unit, range, default and meaning"},
    };
    for (auto& l : lines) ImGui::BulletText("%-30s %s", l[0], l[1]);
    ImGui::End();
}

void menuBar(Editor& e, UiState& ui, double now) {
    if (ImGui::BeginMainMenuBar()) {
        if (ImGui::BeginMenu("File")) {
            fileMenuItems(e, ui.files, ui.closeRequested, now);
            ImGui::EndMenu();
        }
        if (ImGui::BeginMenu("Edit")) {
            if (ImGui::MenuItem("Undo", "Ctrl+Z", false, e.doc().canUndo())) runOrNotify(e, "undo", now);
            if (ImGui::MenuItem("Redo", "Ctrl+Shift+Z", false, e.doc().canRedo())) runOrNotify(e, "redo", now);
            ImGui::EndMenu();
        }
        if (ImGui::BeginMenu("View")) {
            ImGui::MenuItem("Stats", nullptr, &ui.showStats);
            ImGui::MenuItem("Help", "F1", &ui.showHelp);
            ImGui::MenuItem("Presets", nullptr, &ui.presets.show);
            ImGui::MenuItem("Timeline", nullptr, &ui.timeline.show);
            ImGui::MenuItem("Quality", nullptr, &e.qualityTool.show);
            ImGui::EndMenu();
        }
        const std::string title = (e.doc().path().empty() ? std::string("untitled") : e.doc().path()) + (e.doc().dirty() ? " *" : "");
        ImGui::TextDisabled("%s", title.c_str());
        ImGui::EndMainMenuBar();
    }
}

void prompts(Editor& e, UiState& ui, double now) {
    if (!ui.recoveryPath.empty() && !ImGui::IsPopupOpen("Recover unsaved changes?")) ImGui::OpenPopup("Recover unsaved changes?");
    if (ImGui::BeginPopupModal("Recover unsaved changes?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::Text("The last session ended with unsaved changes, autosaved to\n%s", ui.recoveryPath.c_str());
        if (ImGui::Button("Recover")) {
            Result<OpenedScene> s = openSceneFile(ui.recoveryPath);  // with its VDB grids
            if (s) e.doc().replaceScene(s.value().scene);
            else e.notify(s.error().message, now);
            ui.recoveryPath.clear();
            ImGui::CloseCurrentPopup();
        }
        ImGui::SameLine();
        if (ImGui::Button("Discard")) {
            e.autosave().discard();
            ui.recoveryPath.clear();
            ImGui::CloseCurrentPopup();
        }
        ImGui::EndPopup();
    }
    if (ui.closeRequested && !e.doc().dirty()) ui.closeConfirmed = true;
    if (ui.closeRequested && e.doc().dirty() && !ImGui::IsPopupOpen("Unsaved changes")) ImGui::OpenPopup("Unsaved changes");
    if (ImGui::BeginPopupModal("Unsaved changes", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::Text("Save the changes to %s before closing?", e.doc().path().empty() ? "untitled" : e.doc().path().c_str());
        if (ImGui::Button("Save")) {
            Result<void> r = e.run("save");
            if (r) ui.closeConfirmed = true;
            else e.notify(r.error().message, now);
            ui.closeRequested = false;
            ImGui::CloseCurrentPopup();
        }
        ImGui::SameLine();
        if (ImGui::Button("Discard")) ui.closeConfirmed = true, ImGui::CloseCurrentPopup();
        ImGui::SameLine();
        if (ImGui::Button("Cancel")) ui.closeRequested = false, ImGui::CloseCurrentPopup();
        ImGui::EndPopup();
    }
}

void notifications(Editor& e, double now) {
    auto& list = e.notifications();
    while (!list.empty() && list.front().untilSeconds < now) list.pop_front();
    if (list.empty()) return;
    const ImVec2 size = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(10, size.y - 10), ImGuiCond_Always, ImVec2(0, 1));
    ImGui::SetNextWindowBgAlpha(0.8f);
    ImGui::Begin("##notifications", nullptr, ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                                 ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav);
    for (const Notification& n : list) ImGui::TextColored(ImVec4(1.0f, 0.6f, 0.4f, 1.0f), "%s", n.text.c_str());
    ImGui::End();
}

}  // namespace

void drawUi(Editor& e, UiState& ui, double now) {
    menuBar(e, ui, now);
    outliner(e, now);
    inspector(e, now);
    stats(e, ui, now);
    froxelGridOverlay(e);
    heatMapOverlay(e);
    drawQualityPanel(e, now);
    drawPresetsPanel(e, ui.presets, now);
    drawTimelinePanel(e, ui.timeline, now);
    help(ui);
    drawFiles(e, ui.files, now);
    notifications(e, now);
    prompts(e, ui, now);
}

namespace {

// Alt+H: every hidden object shown again, as one undo step.
void showAll(Editor& e, double now) {
    const Scene s = e.doc().scene();
    (void)e.run("begin");
    for (size_t i = 0; i < s.volumes.size(); ++i) if (s.volumes[i].hidden) runOrNotify(e, "show volume " + std::to_string(i), now);
    for (size_t i = 0; i < s.lights.size(); ++i) if (s.lights[i].hidden) runOrNotify(e, "show light " + std::to_string(i), now);
    for (size_t i = 0; i < s.geometry.size(); ++i) if (s.geometry[i].hidden) runOrNotify(e, "show geometry " + std::to_string(i), now);
    (void)e.run("end");
}

// W A S D / Q E fly at 2 m/s (Shift: 8) while the right button is held (without it W E R pick
// the gizmo's mode, as in DCC tools); holding them is one undo step, like a drag.
void flyKeys(Editor& e, UiState& ui, double now) {
    ImGuiIO& io = ImGui::GetIO();
    if (io.KeyCtrl) return;
    const bool look = ImGui::IsMouseDown(1);
    auto down = [look](int key) { return look && ImGui::IsKeyDown(key) ? 1.0f : 0.0f; };
    const glm::vec3 dir{down(GLFW_KEY_D) - down(GLFW_KEY_A), down(GLFW_KEY_E) - down(GLFW_KEY_Q),
                        down(GLFW_KEY_W) - down(GLFW_KEY_S)};
    const bool held = look && (ImGui::IsKeyDown(GLFW_KEY_W) || ImGui::IsKeyDown(GLFW_KEY_A) || ImGui::IsKeyDown(GLFW_KEY_S) ||
                               ImGui::IsKeyDown(GLFW_KEY_D) || ImGui::IsKeyDown(GLFW_KEY_Q) || ImGui::IsKeyDown(GLFW_KEY_E));
    if (held && !ui.flying) (void)e.run("begin");
    if (!held && ui.flying) (void)e.run("end");
    ui.flying = held;
    if (glm::length(dir) == 0.0f) return;
    const glm::vec3 step = dir * (2.0f * (io.KeyShift ? 4.0f : 1.0f) * io.DeltaTime);
    runOrNotify(e, "fly " + fmt(step.x) + " " + fmt(step.y) + " " + fmt(step.z), now);
}

}  // namespace

void handleViewportInput(Editor& e, UiState& ui, double now) {
    ImGuiIO& io = ImGui::GetIO();
    if (!io.WantCaptureKeyboard) {
        const bool ctrl = io.KeyCtrl, shift = io.KeyShift;
        const Selection sel = e.selection();
        const std::string target = sel.kind == Kind::None ? "" : std::string(kindName(sel.kind)) + " " + std::to_string(sel.index);
        if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_Z)) runOrNotify(e, shift ? "redo" : "undo", now);
        if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_Y)) runOrNotify(e, "redo", now);
        if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_S)) runOrNotify(e, "save", now);
        if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_D) && !target.empty()) runOrNotify(e, "duplicate " + target, now);
        if (ImGui::IsKeyPressed(GLFW_KEY_DELETE) && !target.empty()) runOrNotify(e, "delete " + target, now);
        if (ImGui::IsKeyPressed(GLFW_KEY_ESCAPE)) runOrNotify(e, "select none", now);
        if (ImGui::IsKeyPressed(GLFW_KEY_F1)) ui.showHelp = !ui.showHelp;
        if (!ctrl && ImGui::IsKeyPressed(GLFW_KEY_F) && !target.empty()) runOrNotify(e, "frame", now);
        if (!ctrl && !io.KeyAlt && ImGui::IsKeyPressed(GLFW_KEY_H) && !target.empty()) runOrNotify(e, "hide " + target, now);
        if (!ctrl && io.KeyAlt && ImGui::IsKeyPressed(GLFW_KEY_H)) showAll(e, now);
        if (!ctrl && !ImGui::IsMouseDown(1) && ui.gizmo.axis < 0) {
            if (ImGui::IsKeyPressed(GLFW_KEY_W)) runOrNotify(e, "gizmo translate", now);
            if (ImGui::IsKeyPressed(GLFW_KEY_E)) runOrNotify(e, "gizmo rotate", now);
            if (ImGui::IsKeyPressed(GLFW_KEY_R)) runOrNotify(e, "gizmo scale", now);
        }
    }
    if (!io.WantCaptureKeyboard) flyKeys(e, ui, now);
    // Drawn even under the panels; it takes the mouse only when ImGui does not want it.
    if (transformGizmo(e, ui.gizmo, now) || io.WantCaptureMouse) return;
    // A drag is one undo step: begin on press, end on release. A click that did not move picks.
    for (int b = 0; b < 3; ++b) {
        if (ImGui::IsMouseClicked(b)) (void)e.run("begin");
        if (ImGui::IsMouseReleased(b)) (void)e.run("end");
    }
    const ImVec2 w = io.DisplaySize;
    if (ImGui::IsMouseReleased(0) && io.MouseDragMaxDistanceSqr[0] < 9.0f && w.x > 0 && w.y > 0)
        runOrNotify(e, "pick " + fmt(io.MousePos.x / w.x) + " " + fmt(io.MousePos.y / w.y), now);
    const ImVec2 d = io.MouseDelta;
    const float h = std::max(1.0f, io.DisplaySize.y);
    // The press frame's delta is the pointer's travel before the press, not a drag (found by
    // tests/test_editor_input.cpp: a click after a jump orbited the camera).
    const bool pressed = ImGui::IsMouseClicked(0) || ImGui::IsMouseClicked(1) || ImGui::IsMouseClicked(2);
    const bool moved = (d.x != 0.0f || d.y != 0.0f) && !pressed;
    if (moved && ImGui::IsMouseDown(0) && !io.KeyShift)
        runOrNotify(e, "orbit " + fmt(-d.x * 0.3) + " " + fmt(d.y * 0.3), now);
    else if (moved && ImGui::IsMouseDown(1))
        runOrNotify(e, "look " + fmt(-d.x * 0.2) + " " + fmt(-d.y * 0.2), now);
    else if (moved && (ImGui::IsMouseDown(2) || ImGui::IsMouseDown(0)))
        runOrNotify(e, "pan " + fmt(-d.x / h) + " " + fmt(d.y / h), now);
    if (io.MouseWheel != 0.0f) runOrNotify(e, "zoom " + fmt(std::pow(0.9, io.MouseWheel)), now);
}

}  // namespace brume::editor
