#include "timeline_panel.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <imgui.h>

#include "core/animate.h"

namespace brume::editor {
namespace {

constexpr float kRowHeight = 18.0f;
constexpr float kLabelWidth = 150.0f;

std::string seconds(double t) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", t);
    return buf;
}

void runOrNotify(Editor& e, const std::string& line, double now) {
    Result<void> r = e.run(line);
    if (!r) e.notify(r.error().message, now);
}

// The selected object's path prefix ("volumes[2]"), its tracks and keyable settings; empty prefix
// when nothing keyable is selected.
struct Keyed {
    std::string prefix;
    const std::vector<KeyTrack>* tracks = nullptr;
    std::vector<std::string> targets;
};

Keyed selectedKeyed(Editor& e) {
    Keyed k;
    const Selection sel = e.selection();
    const Scene& s = e.doc().scene();
    if (sel.kind == Kind::Volume && sel.index < s.volumes.size()) {
        const Volume& v = s.volumes[sel.index];
        k.prefix = "volumes[" + std::to_string(sel.index) + "]";
        k.tracks = &v.keys;
        for (std::string& t : volumeKeyTargets(v.type))
            if (v.density_texture || t.rfind("density_texture.", 0) != 0) k.targets.push_back(std::move(t));
    } else if (sel.kind == Kind::Light && sel.index < s.lights.size()) {
        const Light& l = s.lights[sel.index];
        k.prefix = "lights[" + std::to_string(sel.index) + "]";
        k.tracks = &l.keys;
        k.targets = lightKeyTargets(l.type);
    }
    return k;
}

void diamond(ImDrawList* dl, ImVec2 c, float r, ImU32 col) {
    dl->AddQuadFilled(ImVec2(c.x, c.y - r), ImVec2(c.x + r, c.y), ImVec2(c.x, c.y + r), ImVec2(c.x - r, c.y), col);
}

// The scrub bar: ticks each second, the playhead; click or drag sets the time.
void scrubBar(Editor& e, double length, float width, double now) {
    ImGui::InvisibleButton("scrub", ImVec2(width, kRowHeight));
    const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
    ImDrawList* dl = ImGui::GetWindowDrawList();
    dl->AddRectFilled(a, b, IM_COL32(45, 45, 50, 255));
    for (int s = 0; s <= static_cast<int>(length); ++s) {
        const float x = a.x + width * static_cast<float>(s / length);
        dl->AddLine(ImVec2(x, b.y - 6), ImVec2(x, b.y), IM_COL32(150, 150, 150, 255));
    }
    if (ImGui::IsItemActive()) {
        const double t = timelineTimeAt(ImGui::GetIO().MousePos.x - a.x, width, length);
        if (std::abs(t - e.sceneTime().seconds()) > 1e-9) runOrNotify(e, "time " + seconds(t), now);
    }
}

void playhead(double time, double length, float x0, float width, float y0, float y1) {
    if (time < 0.0 || time > length) return;
    const float x = x0 + width * static_cast<float>(time / length);
    ImGui::GetWindowDrawList()->AddLine(ImVec2(x, y0), ImVec2(x, y1), IM_COL32(255, 170, 60, 255), 2.0f);
}

// One row per keyed setting: its keys as diamonds; click: go to the key; right click: delete it.
void trackRows(Editor& e, const Keyed& k, double length, float width, double now) {
    for (const KeyTrack& track : *k.tracks) {
        ImGui::PushID(track.target.c_str());
        const ImVec2 row = ImGui::GetCursorScreenPos();
        // The key list's interpolation: a click switches linear <-> smooth (one undo step).
        const bool smooth = track.interpolation == Interpolation::Smooth;
        if (ImGui::SmallButton(smooth ? "S" : "L"))
            runOrNotify(e, "interpolate " + k.prefix + "." + track.target + (smooth ? " linear" : " smooth"), now);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("%s: %s between keys; click for %s", track.target.c_str(), smooth ? "smooth (Catmull-Rom)" : "linear",
                              smooth ? "linear" : "smooth");
        ImGui::SameLine();
        ImGui::TextUnformatted(track.target.c_str());
        ImGui::SameLine(kLabelWidth);
        const ImVec2 a = ImGui::GetCursorScreenPos();
        ImGui::Dummy(ImVec2(width, kRowHeight));
        ImDrawList* dl = ImGui::GetWindowDrawList();
        dl->AddRectFilled(a, ImVec2(a.x + width, a.y + kRowHeight), IM_COL32(35, 35, 40, 255));
        for (size_t i = 0; i < track.keys.size(); ++i) {
            const double t = track.keys[i].time;
            if (t < 0.0 || t > length) continue;
            const ImVec2 c(a.x + width * static_cast<float>(t / length), a.y + kRowHeight * 0.5f);
            ImGui::SetCursorScreenPos(ImVec2(c.x - 6, a.y + 2));
            ImGui::PushID(static_cast<int>(i));
            ImGui::InvisibleButton("key", ImVec2(12, kRowHeight - 4));
            const bool hovered = ImGui::IsItemHovered();
            diamond(dl, c, 6.0f, hovered ? IM_COL32(255, 230, 120, 255) : IM_COL32(230, 190, 60, 255));
            if (hovered) ImGui::SetTooltip("%s at %.3f s\nclick: go there; right click: delete the key", track.target.c_str(), t);
            if (ImGui::IsItemClicked(0)) runOrNotify(e, "time " + seconds(t), now);
            if (ImGui::IsItemClicked(1)) runOrNotify(e, "unkey " + k.prefix + "." + track.target + " " + seconds(t), now);
            ImGui::PopID();
        }
        ImGui::SetCursorScreenPos(ImVec2(row.x, a.y + kRowHeight + ImGui::GetStyle().ItemSpacing.y));
        ImGui::PopID();
    }
}

double lastKeyTime(const Scene& s) {
    double t = 0.0;
    for (const Volume& v : s.volumes)
        for (const KeyTrack& k : v.keys) t = std::max(t, static_cast<double>(k.keys.back().time));
    for (const Light& l : s.lights)
        for (const KeyTrack& k : l.keys) t = std::max(t, static_cast<double>(k.keys.back().time));
    for (const Influencer& f : s.influencers)
        if (!f.path.keys.empty()) t = std::max(t, static_cast<double>(f.path.keys.back().time));
    return t;
}

}  // namespace

double timelineTimeAt(float x, float width, double length) {
    if (width <= 0.0f) return 0.0;
    return std::clamp(static_cast<double>(x / width), 0.0, 1.0) * length;
}

void drawTimelinePanel(Editor& e, TimelineState& st, double now) {
    if (!st.show) return;
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(280, display.y - 170), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(std::max(300.0f, display.x - 620), 160), ImGuiCond_FirstUseEver);
    ImGui::Begin("Timeline", &st.show);
    SceneTime& time = e.sceneTime();
    const double length = std::max(static_cast<double>(st.lengthS), std::ceil(lastKeyTime(e.doc().scene()) + 0.5));
    if (st.loop && time.playing() && time.seconds() > length) runOrNotify(e, "time 0", now);

    if (ImGui::Button(time.playing() ? "Pause" : "Play")) runOrNotify(e, time.playing() ? "play off" : "play on", now);
    ImGui::SameLine();
    if (ImGui::Button("|<")) runOrNotify(e, "time 0", now);
    ImGui::SameLine();
    float t = static_cast<float>(time.seconds());
    ImGui::SetNextItemWidth(90);
    if (ImGui::DragFloat("s", &t, 0.01f, 0.0f, 1.0e6f, "%.3f")) runOrNotify(e, "time " + seconds(t), now);
    ImGui::SameLine();
    ImGui::Checkbox("loop", &st.loop);
    ImGui::SameLine();
    ImGui::SetNextItemWidth(70);
    ImGui::DragFloat("length", &st.lengthS, 0.1f, 0.5f, 3600.0f, "%.1f s");

    const Keyed k = selectedKeyed(e);
    if (!k.prefix.empty() && !k.targets.empty()) {
        st.target = std::clamp(st.target, 0, static_cast<int>(k.targets.size()) - 1);
        ImGui::SameLine();
        ImGui::SetNextItemWidth(170);
        if (ImGui::BeginCombo("##target", k.targets[static_cast<size_t>(st.target)].c_str())) {
            for (size_t i = 0; i < k.targets.size(); ++i)
                if (ImGui::Selectable(k.targets[i].c_str(), static_cast<int>(i) == st.target)) st.target = static_cast<int>(i);
            ImGui::EndCombo();
        }
        ImGui::SameLine();
        const std::string path = k.prefix + "." + k.targets[static_cast<size_t>(st.target)];
        if (ImGui::Button("Set key")) runOrNotify(e, "key " + path + " " + seconds(time.seconds()), now);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("Key %s at %.3f s with its value in the inspector (one undo step).", path.c_str(), time.seconds());
    } else {
        ImGui::SameLine();
        ImGui::TextDisabled("select a volume or light to key its settings");
    }

    const float width = std::max(50.0f, ImGui::GetContentRegionAvail().x - kLabelWidth);
    ImGui::TextUnformatted("time");
    ImGui::SameLine(kLabelWidth);
    const ImVec2 top = ImGui::GetCursorScreenPos();
    scrubBar(e, length, width, now);
    if (k.tracks) trackRows(e, k, length, width, now);
    playhead(time.seconds(), length, top.x, width, top.y, ImGui::GetCursorScreenPos().y);
    ImGui::End();
}

}  // namespace brume::editor
