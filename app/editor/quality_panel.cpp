#include "quality_panel.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <utility>

#include <imgui.h>

#include "core/quality.h"
#include "core/settings.h"
#include "view.h"

namespace brume::editor {
namespace {

double seconds() {
    using namespace std::chrono;
    return duration<double>(steady_clock::now().time_since_epoch()).count();
}

std::string percent(double f) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f%%", 100.0 * f);
    return buf;
}

// The scene the viewport renders now (renderIfNeeded), with its render block at the defaults:
// what a measurement is of.
MeasuredView currentView(Editor& e) {
    MeasuredView v;
    v.valid = true;
    v.scene = visibleScene(e.doc().scene());
    v.scene.time_s = static_cast<float>(e.sceneTime().seconds());
    v.scene.render = RenderBlock{};
    v.quality = e.quality();
    return v;
}

// The measured size: the viewport's (the window's before the first frame) over the divisor.
glm::ivec2 measuredSize(Editor& e) {
    glm::ivec2 view = e.viewSize();
    if (view.x <= 0 || view.y <= 0) view = {e.doc().scene().render.width, e.doc().scene().render.height};
    const int d = std::max(e.qualityTool.divisor, 1);
    return glm::max(view / d, glm::ivec2(1));
}

// Takes a finished job's results into the tool: what they were measured on, and a notification
// when it failed or was cancelled.
void sync(Editor& e) {
    QualityTool& t = e.qualityTool;
    const uint64_t g = t.job.generation();
    if (g == t.seenGeneration) return;
    t.seenGeneration = g;
    const JobProgress p = t.job.progress();
    const JobResult r = t.job.result();
    if (p.phase == JobPhase::Done) {
        if (t.runningCandidates) t.measured = t.running, t.selected = -1;
        if (t.runningHeatMap) t.heatMapView = t.running;
    }
    if (!r.message.empty()) e.notify(r.message, seconds());
}

Result<void> startJob(Editor& e, glm::ivec2 size, bool candidates, bool heatMap) {
    QualityTool& t = e.qualityTool;
    sync(e);
    QualityJobSpec spec;
    if (candidates) {
        Result<measure::TradeoffPlan> plan = measure::parsePlan(t.qualities, t.frames);
        if (!plan) return plan.error();
        spec.plan = plan.value();
    }
    if (size.x < settings::render_width.min || size.x > settings::render_width.max ||
        size.y < settings::render_height.min || size.y > settings::render_height.max)
        return Error{"tradeoff run: the size must be 1..16384 px each way."};
    t.running = currentView(e);
    t.runningCandidates = candidates;
    t.runningHeatMap = heatMap;
    spec.scene = visibleScene(e.doc().scene());
    spec.scene.time_s = static_cast<float>(e.sceneTime().seconds());
    spec.width = size.x;
    spec.height = size.y;
    spec.cacheDir = t.cacheDir;
    spec.heatMap = heatMap;
    spec.heatQuality = e.quality();
    spec.heatFrames = convergedFrames(e.doc().scene());
    t.job.start(std::move(spec), t.cpu || !t.gpu ? cpuRendererFactory(0) : t.gpu);
    return {};
}

bool whole(const std::string& s, int& out) {
    const char* end = s.data() + s.size();
    auto r = std::from_chars(s.data(), end, out);
    return r.ec == std::errc() && r.ptr == end;
}

Result<void> apply(Editor& e, const std::string& word) {
    sync(e);
    const JobResult r = e.qualityTool.job.result();
    int i = -1;
    if (!whole(word, i) || i < 0 || static_cast<size_t>(i) >= r.candidates.size())
        return Error{r.candidates.empty() ? "tradeoff apply: nothing measured yet (tradeoff run)."
                                          : "tradeoff apply takes a row of the table, 0.." +
                                                std::to_string(r.candidates.size() - 1) + "."};
    const TradeoffCandidate& c = r.candidates[static_cast<size_t>(i)];
    // One undo step: the preset and frames (and a grid's override) into the render block, then the
    // viewport's preset. Recorded as this one action: a replay must not apply it twice.
    const auto recorder = std::exchange(e.recorder, nullptr);
    (void)e.run("begin");
    Result<void> done = e.run(std::string("set render.quality ") + toString(c.quality));
    if (done) done = e.run("set render.frames " + std::to_string(c.frames));
    if (done && c.tilePx > 0) done = e.run("set froxels.tile_px " + std::to_string(c.tilePx));
    if (done && c.tilePx > 0) done = e.run("set froxels.slices " + std::to_string(c.slices));
    (void)e.run("end");
    if (done) done = e.run(std::string("quality ") + toString(c.quality));  // the viewport shows it
    e.recorder = recorder;
    if (done) e.qualityTool.selected = i;
    return done;
}

constexpr const char* kUsage =
    "tradeoff takes: show|hide, plan QUALITIES FRAMES, renderer gpu|cpu, size 1|2|4, run [WIDTH HEIGHT], cancel, "
    "wait, apply INDEX.";

}  // namespace

Result<void> runQualityAction(Editor& e, const Action& a) {
    QualityTool& t = e.qualityTool;
    const std::vector<std::string>& w = a.args;
    const std::string verb = w.empty() ? "" : w[0];
    if ((verb == "show" || verb == "hide") && w.size() == 1) return t.show = verb == "show", Result<void>();
    if (verb == "plan" && w.size() == 3) {
        Result<measure::TradeoffPlan> plan = measure::parsePlan(w[1], w[2]);
        if (!plan) return Error{"tradeoff plan: " + plan.error().message};
        t.qualities = w[1];
        t.frames = w[2];
        return {};
    }
    if (verb == "renderer" && w.size() == 2 && (w[1] == "gpu" || w[1] == "cpu")) return t.cpu = w[1] == "cpu", Result<void>();
    if (verb == "size" && w.size() == 2 && (w[1] == "1" || w[1] == "2" || w[1] == "4"))
        return t.divisor = w[1][0] - '0', Result<void>();
    if (verb == "run" && (w.size() == 1 || w.size() == 3)) {
        glm::ivec2 size = measuredSize(e);
        if (w.size() == 3 && (!whole(w[1], size.x) || !whole(w[2], size.y)))
            return Error{"tradeoff run takes: tradeoff run [WIDTH HEIGHT] (pixels)."};
        return startJob(e, size, true, true);
    }
    if (verb == "cancel" && w.size() == 1) return t.job.cancel(), Result<void>();
    if (verb == "wait" && w.size() == 1) {
        e.waitUntil = [&e] {
            if (e.qualityTool.job.running()) return false;
            sync(e);
            return true;
        };
        return {};
    }
    if (verb == "apply" && w.size() == 2) return apply(e, w[1]);
    return Error{kUsage};
}

void requestHeatMap(Editor& e) {
    QualityTool& t = e.qualityTool;
    sync(e);
    if (t.job.running() || (t.heatMapView.valid && t.heatMapView == currentView(e))) return;
    if (Result<void> r = startJob(e, measuredSize(e), false, true); !r) e.notify(r.error().message, seconds());
}

namespace {

ImU32 rampColor(float t) {
    const glm::vec3 c = heatMapColor(t);
    return ImGui::GetColorU32(ImVec4(c.x, c.y, c.z, 1.0f));
}

void progressRows(const JobProgress& p, bool candidates) {
    if (p.referenceCached) {
        ImGui::TextUnformatted("reference: cached");
    } else {
        char label[96];
        if (p.referenceEtaSeconds >= 0.0)
            std::snprintf(label, sizeof label, "reference %.0f%%, %.0f s left", 100.0 * p.referenceFraction,
                          p.referenceEtaSeconds);
        else
            std::snprintf(label, sizeof label, "reference %.0f%%", 100.0 * p.referenceFraction);
        ImGui::ProgressBar(p.referenceFraction, ImVec2(-1.0f, 0.0f), label);
    }
    if (candidates && p.phase != JobPhase::Reference) {
        const size_t k = std::min(p.candidatesDone + 1, p.candidates);
        char label[64];
        std::snprintf(label, sizeof label, "candidate %zu of %zu", k, p.candidates);
        const float f = p.candidates ? static_cast<float>(p.candidatesDone) / static_cast<float>(p.candidates) : 1.0f;
        ImGui::ProgressBar(f, ImVec2(-1.0f, 0.0f), p.phase == JobPhase::HeatMap ? "heat map" : label);
    }
}

// Error against ms on log axes (the axes of `brume tradeoff --svg`), the front drawn, each point
// labelled; the chosen row ringed.
void chart(const std::vector<TradeoffCandidate>& cands, int selected) {
    const TradeoffChartAxes axes = tradeoffChartAxes(cands);
    const float width = std::max(ImGui::GetContentRegionAvail().x, 200.0f), height = 220.0f;
    const ImVec2 o = ImGui::GetCursorScreenPos();
    const float left = 52.0f, right = 12.0f, top = 8.0f, bottom = 34.0f;
    auto px = [&](double ms) { return o.x + left + static_cast<float>(axes.x(ms)) * (width - left - right); };
    auto py = [&](double e) { return o.y + height - bottom - static_cast<float>(axes.y(e)) * (height - top - bottom); };
    ImDrawList* d = ImGui::GetWindowDrawList();
    d->AddRectFilled(o, ImVec2(o.x + width, o.y + height), IM_COL32(250, 250, 250, 255));
    const ImU32 grid = IM_COL32(215, 215, 215, 255), ink = IM_COL32(40, 40, 40, 255);
    char text[64];
    for (double k = axes.msLog0; k <= axes.msLog1; k += 1.0) {
        const float x = px(std::pow(10.0, k));
        d->AddLine(ImVec2(x, o.y + top), ImVec2(x, o.y + height - bottom), grid);
        std::snprintf(text, sizeof text, "%g", std::pow(10.0, k));
        d->AddText(ImVec2(x - 8.0f, o.y + height - bottom + 2.0f), ink, text);
    }
    for (double k = axes.errorLog0; k <= axes.errorLog1; k += 1.0) {
        const float y = py(std::pow(10.0, k));
        d->AddLine(ImVec2(o.x + left, y), ImVec2(o.x + width - right, y), grid);
        std::snprintf(text, sizeof text, "%g%%", 100.0 * std::pow(10.0, k));
        d->AddText(ImVec2(o.x + 2.0f, y - 7.0f), ink, text);
    }
    d->AddText(ImVec2(o.x + left, o.y + height - 16.0f), ink, "ms per image (log)   vs   rel. mean abs error (log)");
    std::vector<ImVec2> front;
    for (size_t i : paretoFrontByMs(cands)) front.push_back(ImVec2(px(cands[i].ms), py(cands[i].error.relMae)));
    const ImU32 red = IM_COL32(214, 39, 40, 255), blue = IM_COL32(31, 119, 180, 255);
    if (front.size() > 1) d->AddPolyline(front.data(), static_cast<int>(front.size()), red, ImDrawFlags_None, 1.5f);
    for (size_t i = 0; i < cands.size(); ++i) {
        const ImVec2 p(px(cands[i].ms), py(cands[i].error.relMae));
        d->AddCircleFilled(p, 3.5f, cands[i].pareto ? red : blue);
        if (static_cast<int>(i) == selected) d->AddCircle(p, 7.0f, ink, 0, 1.5f);
        d->AddText(ImVec2(p.x + 5.0f, p.y - 14.0f), ink, candidateLabel(cands[i]).c_str());
    }
    ImGui::Dummy(ImVec2(width, height));
}

// Columns as `brume tradeoff`'s table, and a button per row that applies it.
void table(Editor& e, const std::vector<TradeoffCandidate>& cands, double now) {
    if (!ImGui::BeginTable("candidates", 6, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) return;
    for (const char* h : {"candidate", "ms", "error", "p99 tile", "front", ""}) ImGui::TableSetupColumn(h);
    ImGui::TableHeadersRow();
    for (size_t i = 0; i < cands.size(); ++i) {
        const TradeoffCandidate& c = cands[i];
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(candidateLabel(c).c_str());
        ImGui::TableNextColumn();
        ImGui::Text("%.2f", c.ms);
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(percent(c.error.relMae).c_str());
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(percent(c.error.p99TileError).c_str());
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(c.pareto ? "*" : "");
        ImGui::TableNextColumn();
        ImGui::PushID(static_cast<int>(i));
        if (ImGui::SmallButton(static_cast<int>(i) == e.qualityTool.selected ? "applied" : "apply")) {
            if (Result<void> r = e.run("tradeoff apply " + std::to_string(i)); !r) e.notify(r.error().message, now);
        }
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("Set the document's render.quality and render.frames to this (undoable), and the viewport's preset.");
        ImGui::PopID();
    }
    ImGui::EndTable();
}

void run(Editor& e, const std::string& line, double now) {
    if (Result<void> r = e.run(line); !r) e.notify(r.error().message, now);
}

}  // namespace

void drawQualityPanel(Editor& e, double now) {
    QualityTool& t = e.qualityTool;
    sync(e);
    if (!t.show) return;
    // Over the middle of the view: it is opened to be read, then closed.
    ImGui::SetNextWindowPos(ImVec2(280, 30), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(470, 600), ImGuiCond_FirstUseEver);
    bool open = true;
    if (!ImGui::Begin("Quality", &open)) {
        ImGui::End();
        if (!open) t.show = false;
        return;
    }
    if (!open) t.show = false;
    const glm::ivec2 size = measuredSize(e);
    ImGui::TextWrapped("brume tradeoff on this view: every preset x frames timed and compared with the reference "
                       "(cached by the scene's content). docs/quality.md");
    const char* sizes[] = {"view size", "1/2 of the view", "1/4 of the view"};
    int choice = t.divisor == 1 ? 0 : t.divisor == 2 ? 1 : 2;
    if (ImGui::Combo("size", &choice, sizes, 3)) run(e, "tradeoff size " + std::to_string(1 << choice), now);
    ImGui::SameLine();
    ImGui::Text("%dx%d", size.x, size.y);
    int renderer = t.cpu ? 1 : 0;
    if (ImGui::RadioButton("GPU", &renderer, 0)) run(e, "tradeoff renderer gpu", now);
    ImGui::SameLine();
    if (ImGui::RadioButton("CPU froxel renderer", &renderer, 1)) run(e, "tradeoff renderer cpu", now);
    ImGui::Text("presets %s x frames %s", t.qualities.c_str(), t.frames.c_str());
    const bool running = t.job.running();
    if (running) {
        if (ImGui::Button("Cancel")) run(e, "tradeoff cancel", now);
        progressRows(t.job.progress(), t.runningCandidates);
    } else if (ImGui::Button("Measure")) {
        run(e, "tradeoff run", now);
    }
    const JobResult r = t.job.result();
    if (!r.candidates.empty()) {
        ImGui::Separator();
        ImGui::Text("%dx%d, %zu candidates%s", r.width, r.height, r.candidates.size(),
                    t.measured.scene == currentView(e).scene ? ""
                        : "  (measured on an earlier view)");
        chart(r.candidates, t.selected);
        table(e, r.candidates, now);
    }
    ImGui::End();
}

void heatMapOverlay(Editor& e) {
    const QualityTool& t = e.qualityTool;
    if (!e.debugView().errorMap || !t.heatMapView.valid || !(t.heatMapView == currentView(e))) return;
    // Rows of runs of one ramp colour (64 steps): a few thousand rectangles, not one per pixel.
    static uint64_t builtFor = ~uint64_t(0);
    struct Run {
        int y, x0, x1;
        int level;
    };
    static std::vector<Run> runs;
    static glm::ivec2 mapSize{0};
    constexpr int kLevels = 64;
    if (builtFor != t.job.generation()) {
        builtFor = t.job.generation();
        const JobResult r = t.job.result();
        runs.clear();
        const ErrorMap& m = r.heatMap;
        mapSize = {m.width, m.height};
        auto level = [&m](int x, int y) {
            const float v = m.values[static_cast<size_t>(y) * static_cast<size_t>(m.width) + static_cast<size_t>(x)];
            return std::clamp(static_cast<int>(v / m.scale * (kLevels - 1) + 0.5f), 0, kLevels - 1);
        };
        for (int y = 0; y < m.height; ++y) {
            for (int x = 0; x < m.width;) {
                const int l = level(x, y);
                int x1 = x + 1;
                while (x1 < m.width && level(x1, y) == l) ++x1;
                runs.push_back({y, x, x1, l});
                x = x1;
            }
        }
    }
    if (mapSize.x <= 0 || mapSize.y <= 0) return;
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    const float sx = display.x / static_cast<float>(mapSize.x), sy = display.y / static_cast<float>(mapSize.y);
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    for (const Run& run : runs)
        draw->AddRectFilled(ImVec2(static_cast<float>(run.x0) * sx, static_cast<float>(run.y) * sy),
                            ImVec2(static_cast<float>(run.x1) * sx, static_cast<float>(run.y + 1) * sy),
                            rampColor(static_cast<float>(run.level) / (kLevels - 1)));
}

void heatMapLegend(Editor& e, double now) {
    QualityTool& t = e.qualityTool;
    sync(e);
    if (t.job.running() && t.runningHeatMap) {
        ImGui::TextWrapped("Measuring the error against the reference...");
        progressRows(t.job.progress(), false);
        if (ImGui::Button("Cancel")) run(e, "tradeoff cancel", now);
        return;
    }
    const JobResult r = t.job.result();
    if (!t.heatMapView.valid || !r.hasHeatMap) {
        ImGui::TextWrapped("No heat map yet.");
    } else {
        const ErrorMap& m = r.heatMap;
        double mean = 0.0;
        float peak = 0.0f;
        for (float v : m.values) mean += v, peak = std::max(peak, v);
        mean /= std::max<double>(1.0, static_cast<double>(m.values.size()));
        ImGui::TextWrapped("Error per pixel: |image - reference| / the reference's mean, %s after %d frames at %dx%d. "
                           "Mean %s (the rel. MAE), max %s.%s",
                           toString(r.heatQuality), r.heatFrames, m.width, m.height, percent(mean).c_str(),
                           percent(peak).c_str(), t.heatMapView == currentView(e) ? "" : " The view changed since: recompute.");
        // The ramp, 0 on the left to the scale on the right, with its numbers.
        ImDrawList* draw = ImGui::GetWindowDrawList();
        const ImVec2 p = ImGui::GetCursorScreenPos();
        const float width = ImGui::GetContentRegionAvail().x, height = 10.0f;
        const int steps = 32;
        for (int i = 0; i < steps; ++i) {
            const float x0 = p.x + width * static_cast<float>(i) / steps, x1 = p.x + width * static_cast<float>(i + 1) / steps;
            draw->AddRectFilled(ImVec2(x0, p.y), ImVec2(x1, p.y + height), rampColor((static_cast<float>(i) + 0.5f) / steps));
        }
        ImGui::Dummy(ImVec2(width, height));
        for (int k = 0; k <= 4; ++k) {
            char tick[32];
            std::snprintf(tick, sizeof tick, k == 4 ? "%g%%+" : "%g%%", 100.0 * m.scale * k / 4.0);
            if (k > 0) ImGui::SameLine(width * static_cast<float>(k) / 4.0f - (k == 4 ? ImGui::CalcTextSize(tick).x : 0.0f));
            ImGui::TextUnformatted(tick);
        }
    }
    if (ImGui::Button(t.heatMapView.valid ? "Recompute" : "Compute")) {
        t.heatMapView.valid = false;
        requestHeatMap(e);
    }
}

}  // namespace brume::editor
