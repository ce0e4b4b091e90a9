#include "debug_panel.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <imgui.h>

#include "core/debug_view.h"
#include "core/quality.h"
#include "quality_panel.h"

namespace brume::editor {
namespace {

void run(Editor& e, const std::string& line, double now) {
    if (Result<void> r = e.run(line); !r) e.notify(r.error().message, now);
}

// The ramp as a strip of colour, low values on the left.
void rampStrip(int view) {
    ImDrawList* draw = ImGui::GetWindowDrawList();
    const ImVec2 p = ImGui::GetCursorScreenPos();
    const float width = ImGui::GetContentRegionAvail().x, height = 10.0f;
    const int steps = 32;
    for (int i = 0; i < steps; ++i) {
        const float t = (static_cast<float>(i) + 0.5f) / steps;
        const glm::vec2 range = shd::debugViewRange(view);
        // The value at ramp position t (inverse of debugRampPosition).
        const float v = view == shd::DEBUG_VIEW_TRANSMITTANCE ? t : range.x * std::pow(range.y / range.x, t);
        const glm::vec3 c = shd::debugViewColor(glm::vec4(v), view);
        const float x0 = p.x + width * static_cast<float>(i) / steps, x1 = p.x + width * static_cast<float>(i + 1) / steps;
        draw->AddRectFilled(ImVec2(x0, p.y), ImVec2(x1, p.y + height), ImGui::GetColorU32(ImVec4(c.x, c.y, c.z, 1.0f)));
    }
    ImGui::Dummy(ImVec2(width, height));
}

}  // namespace

void debugSection(Editor& e, double now) {
    DebugViewState& d = e.debugView();
    ImGui::Separator();
    ImGui::TextUnformatted("Debug");
    const char* views[] = {"final", "density slice", "scattering slice", "transmittance slice", "error heat map"};
    constexpr int kErrorEntry = 4;  // the final image under its error against the reference (quality_panel.h)
    int view = d.errorMap ? kErrorEntry : d.view;
    if (ImGui::Combo("view", &view, views, 5))
        run(e, view == kErrorEntry ? std::string("debug error") : std::string("debug ") + debugViewName(view), now);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("One depth slice of a froxel volume instead of the image, or where the image differs from "
                          "the reference (docs/editor.md, Debug views).");
    const int slices = e.lastRender() ? e.lastRender()->dims.z : 1;
    int slice = std::min(d.slice, slices - 1);
    if (ImGui::SliderInt("slice", &slice, 0, slices - 1)) run(e, "debug slice " + std::to_string(slice), now);
    // The same choice by view depth: the slider shows the chosen slice's far side.
    const FroxelSettings fs = resolveFroxelSettings(e.doc().scene(), e.quality());
    float depth = shd::viewDepthFromSliceT(static_cast<float>(std::min(slice, fs.slices - 1) + 1) / static_cast<float>(fs.slices),
                                           fs.near, fs.far, fs.distribution);
    if (ImGui::SliderFloat("depth [m]", &depth, 0.0f, fs.far, "%.2f")) run(e, "debug depth " + std::to_string(depth), now);
    bool grid = d.grid;
    if (ImGui::Checkbox("froxel grid", &grid)) run(e, std::string("debug grid ") + (grid ? "on" : "off"), now);
    if (d.errorMap) heatMapLegend(e, now);
    if (d.view != shd::DEBUG_VIEW_FINAL) {
        ImGui::TextWrapped("%s", d.legend.c_str());
        rampStrip(d.view);
    }
}

void froxelGridOverlay(Editor& e) {
    const DebugViewState& d = e.debugView();
    const glm::ivec2 vp = e.viewSize();
    if (!d.grid || vp.x <= 0 || vp.y <= 0) return;
    const FroxelSettings fs = resolveFroxelSettings(e.doc().scene(), e.quality());
    const int tile = fs.tile_px;
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    // The viewport image fills the window: image pixels to window points.
    const float sx = display.x / static_cast<float>(vp.x), sy = display.y / static_cast<float>(vp.y);
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    const ImU32 line = IM_COL32(255, 255, 255, 70);
    for (int x = tile; x < vp.x; x += tile)
        draw->AddLine(ImVec2(static_cast<float>(x) * sx, 0.0f), ImVec2(static_cast<float>(x) * sx, display.y), line);
    for (int y = tile; y < vp.y; y += tile)
        draw->AddLine(ImVec2(0.0f, static_cast<float>(y) * sy), ImVec2(display.x, static_cast<float>(y) * sy), line);
    // The slice's depths (slice 0 starts at the camera), as debugSliceDepths.
    const int s = std::clamp(d.slice, 0, fs.slices - 1);
    auto depth = [&](int k) {
        return shd::viewDepthFromSliceT(static_cast<float>(k) / static_cast<float>(fs.slices), fs.near, fs.far,
                                        fs.distribution);
    };
    char text[96];
    std::snprintf(text, sizeof text, "froxels %d px, slice %d of %d: %.2f-%.2f m", tile, s, fs.slices,
                  s == 0 ? 0.0 : static_cast<double>(depth(s)), static_cast<double>(depth(s + 1)));
    // Bottom right: the panels float on the left.
    const ImVec2 size = ImGui::CalcTextSize(text);
    draw->AddText(ImVec2(display.x - size.x - 8.0f, display.y - size.y - 8.0f), IM_COL32(255, 255, 255, 230), text);
}

}  // namespace brume::editor
