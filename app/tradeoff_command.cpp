#include "tradeoff_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <sstream>
#include <variant>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "cli_text.h"
#include "core/tradeoff.h"
#include "tradeoff_measure.h"
#include "io/atomic_file.h"
#include "io/scene_json.h"
#include "progress.h"
#include "render_command.h"
#include "vdb_command.h"

namespace brume::app {

namespace fs = std::filesystem;

namespace {

// Whether a file can be created at `path` (its folder exists and is writable), checked before the
// long work so that a bad path fails in a second, not after the renders.
bool writableOutput(const std::string& path) {
    const fs::path p = fs::absolute(path);
    std::error_code ec;
    if (fs::is_directory(p, ec)) return false;
    const fs::path dir = p.parent_path();
    return fs::is_directory(dir, ec) && access(dir.c_str(), W_OK) == 0;
}

std::string percent(double f) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%.2f%%", 100.0 * f);
    return buf;
}

// Error against milliseconds on log axes; the front drawn as a line, every point labelled.
std::string chartSvg(const std::vector<TradeoffCandidate>& cands, const std::string& title) {
    const double W = 720, H = 480, left = 70, right = 20, top = 40, bottom = 60;
    const TradeoffChartAxes axes = tradeoffChartAxes(cands);
    const double x0 = axes.msLog0, x1 = axes.msLog1, y0 = axes.errorLog0, y1 = axes.errorLog1;
    auto px = [&](double ms) { return left + axes.x(ms) * (W - left - right); };
    auto py = [&](double e) { return H - bottom - axes.y(e) * (H - top - bottom); };
    std::ostringstream s;
    s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
      << "\" font-family=\"sans-serif\" font-size=\"11\">\n";
    s << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    s << "<text x=\"" << W / 2 << "\" y=\"20\" text-anchor=\"middle\" font-size=\"13\">" << title << "</text>\n";
    for (double d = x0; d <= x1; d += 1) {
        s << "<line x1=\"" << px(std::pow(10, d)) << "\" y1=\"" << top << "\" x2=\"" << px(std::pow(10, d)) << "\" y2=\""
          << H - bottom << "\" stroke=\"#ddd\"/>\n";
        s << "<text x=\"" << px(std::pow(10, d)) << "\" y=\"" << H - bottom + 16 << "\" text-anchor=\"middle\">"
          << std::pow(10, d) << "</text>\n";
    }
    for (double d = y0; d <= y1; d += 1) {
        s << "<line x1=\"" << left << "\" y1=\"" << py(std::pow(10, d)) << "\" x2=\"" << W - right << "\" y2=\""
          << py(std::pow(10, d)) << "\" stroke=\"#ddd\"/>\n";
        s << "<text x=\"" << left - 6 << "\" y=\"" << py(std::pow(10, d)) + 4 << "\" text-anchor=\"end\">"
          << 100.0 * std::pow(10, d) << "%</text>\n";
    }
    s << "<text x=\"" << (left + W - right) / 2 << "\" y=\"" << H - 15
      << "\" text-anchor=\"middle\">time per image [ms] (log)</text>\n";
    s << "<text x=\"15\" y=\"" << (top + H - bottom) / 2 << "\" text-anchor=\"middle\" transform=\"rotate(-90 15 "
      << (top + H - bottom) / 2 << ")\">relative mean abs error (log)</text>\n";
    s << "<polyline class=\"pareto-front\" fill=\"none\" stroke=\"#d62728\" stroke-width=\"1.5\" points=\"";
    for (size_t i : paretoFrontByMs(cands)) s << px(cands[i].ms) << "," << py(cands[i].error.relMae) << " ";
    s << "\"/>\n";
    for (const TradeoffCandidate& c : cands) {
        const double x = px(c.ms), y = py(c.error.relMae);
        s << "<circle cx=\"" << x << "\" cy=\"" << y << "\" r=\"4\" fill=\"" << (c.pareto ? "#d62728" : "#1f77b4")
          << "\"/>\n";
        s << "<text x=\"" << x + 6 << "\" y=\"" << y - 6 << "\">" << candidateLabel(c) << "</text>\n";
    }
    s << "</svg>\n";
    return s.str();
}

std::string candidatesJson(const std::vector<TradeoffCandidate>& cands, const std::string& scenePath,
                           const RenderRequest& base, const std::string& renderer) {
    nlohmann::json list = nlohmann::json::array();
    for (const TradeoffCandidate& c : cands) {
        nlohmann::json j = {{"label", candidateLabel(c)},
                            {"quality", toString(c.quality)},
                            {"frames", c.frames},
                            {"ms", c.ms},
                            {"rel_mae", c.error.relMae},
                            {"p99_tile_error", c.error.p99TileError},
                            {"pareto", c.pareto}};
        if (c.tilePx > 0) j["grid"] = {{"tile_px", c.tilePx}, {"slices", c.slices}};
        list.push_back(j);
    }
    nlohmann::json root = {{"scene", scenePath},
                           {"width", base.width},
                           {"height", base.height},
                           {"renderer", renderer},
                           {"tile_px_of_p99", kTradeoffTilePx},
                           {"candidates", list}};
    return root.dump(2) + "\n";
}

}  // namespace

CLI::App* addTradeoffCommand(CLI::App& app, TradeoffOptions& o) {
    CLI::App* cmd = app.add_subcommand(
        "tradeoff",
        "Measure speed against accuracy on a scene: each quality preset x temporal frames (and --grid) timed and "
        "compared with the reference; a table with the Pareto front and a recommendation (docs/quality.md).");
    cmd->add_option("SCENE", o.scenePath, "Scene file (JSON; see docs/scene-format.md).")->required();
    o.widthOption = cmd->add_option("--width", o.width, optionHelp(settings::render_width, "the scene's render.width"));
    o.heightOption = cmd->add_option("--height", o.height, optionHelp(settings::render_height, "the scene's render.height"));
    cmd->add_option("--quality", o.qualities,
                    "Presets to measure, comma separated, each one of " + std::string(settings::render_quality.choices) +
                        ". Default: low,medium,high,ultra.");
    cmd->add_option("--frames", o.frames,
                    "Temporal frames per candidate, comma separated, each 1..1024. Default: 1,4,16.");
    cmd->add_option("--grid", o.grids,
                    "Also measure this froxel grid, TILExSLICES (tile 1..64 px, slices 1..1024; the rest from the "
                    "scene's quality), at each --frames; repeatable.");
    cmd->add_option("--repeats", o.repeats, "Timed renders per candidate (the median is reported). Default: 3. Range: 1..100.")
        ->check(CLI::Range(1, 100));
    cmd->add_option("--warmup", o.warmup, "Untimed renders before each candidate's timed ones. Default: 1. Range: 0..100.")
        ->check(CLI::Range(0, 100));
    cmd->add_flag("--cpu", o.cpu, "Time the CPU froxel renderer instead of the GPU. Default: off.");
    cmd->add_option("--threads", o.threads, optionHelp(settings::cli_threads))->check(CLI::Range(0, 1024));
    cmd->add_option("--device", o.device, "GPU renderer: Vulkan device whose name contains this text. Default: automatic.");
    cmd->add_option("--max-error", o.maxErrorPercent,
                    "Recommend the fastest candidate whose error is at most this [%]. Range: 0..1000.")
        ->check(CLI::Range(0.0, 1000.0));
    cmd->add_option("--budget-ms", o.budgetMs,
                    "Recommend the most accurate candidate that takes at most this [ms]. Range: 0..1e7.")
        ->check(CLI::Range(0.0, 1e7));
    cmd->add_option("--svg", o.svgPath, "Write the chart (error against ms, log axes, front drawn) to this SVG file.");
    cmd->add_option("--json", o.jsonPath, "Write the candidates to this JSON file.");
    cmd->add_option("--cache", o.cacheDir,
                    "Folder of cached references. Default: $XDG_CACHE_HOME/brume/references, else ~/.cache/brume/references.");
    return cmd;
}

CommandResult runTradeoff(const TradeoffOptions& o) {
    // Every argument is checked before the first render.
    Result<measure::TradeoffPlan> parsed = measure::parsePlan(o.qualities, o.frames, o.grids);
    if (!parsed) return badInput(parsed.error().message);
    measure::TradeoffPlan plan = std::move(parsed.value());
    plan.repeats = o.repeats;
    plan.warmup = o.warmup;
    for (const std::string* out : {&o.svgPath, &o.jsonPath}) {
        if (!out->empty() && !writableOutput(*out))
            return badInput(*out + ": cannot be written (its folder does not exist or is not writable).");
    }

    Result<Scene> loaded = loadSceneFile(o.scenePath);
    if (!loaded) return badInput(loaded.error().message);
    Scene scene = std::move(loaded.value());
    if (Result<void> g = loadGridsPrintingWarnings(scene, o.scenePath, settings::cli_vdb_memory.i()); !g)
        return badInput(g.error().message);
    RenderRequest base = requestFromScene(scene);
    if (o.widthOption->count() > 0) base.width = o.width;
    if (o.heightOption->count() > 0) base.height = o.height;
    if (base.width < settings::render_width.min || base.width > settings::render_width.max ||
        base.height < settings::render_height.min || base.height > settings::render_height.max) {
        return badInput("--width/--height out of range: expected " + formatRange(settings::render_width) + ".");
    }
    base.threads = o.threads;
    base.history = HistoryMode::Restart;

    const std::string cacheDir = o.cacheDir.empty() ? measure::defaultCacheDir() : o.cacheDir;
    const std::string cachePath = measure::referenceCachePath(scene, base.width, base.height, cacheDir);
    std::error_code ec;
    std::optional<ProgressLine> refLine;
    if (fs::exists(cachePath, ec)) {
        std::fprintf(stderr, "reference: cached (%s)\n", cachePath.c_str());
    } else {
        std::fprintf(stderr, "reference: not cached, rendering %dx%d\n", base.width, base.height);
        refLine.emplace("rendering the reference (once; cached by the scene's content)", true);
    }
    Result<measure::ReferenceResult> ref = measure::referenceImage(
        scene, base, cacheDir, refLine ? ProgressFn([&refLine](float f) { refLine->update(f); }) : ProgressFn());
    if (refLine) ref ? refLine->complete() : refLine->end();
    if (!ref) return internalFailure(ref.error().message);
    if (!ref.value().warning.empty()) std::fprintf(stderr, "warning: %s\n", ref.value().warning.c_str());

    const RendererKind kind = o.cpu ? RendererKind::FroxelCpu : RendererKind::Gpu;
    RenderSession session(kind, o.device);
    if (session.startFailure()) return badInput(session.startFailure()->message);

    std::vector<TradeoffCandidate> cands = measure::plannedCandidates(plan, base.quality);
    ProgressLine line("timing " + std::to_string(cands.size()) + " candidates", true);
    std::string device;
    auto render = [&](const Scene& s, const RenderRequest& req) -> Result<Image> {
        std::variant<RenderOutput, RenderFailure> out = session.render(s, req);
        if (const RenderFailure* f = std::get_if<RenderFailure>(&out)) return Error{f->message, f->userCanFix};
        device = std::get<RenderOutput>(out).stats.device;
        return std::move(std::get<RenderOutput>(out).image);
    };
    Result<void> measured = measure::measureCandidates(scene, base, ref.value().image, cands, o.warmup, o.repeats, render,
                                                       [&](size_t k) { line.update(float(k) / float(cands.size())); });
    if (!measured) return measured.error().badInput ? badInput(measured.error().message) : internalFailure(measured.error().message);
    line.complete();

    std::printf("brume tradeoff: %s, %dx%d, %s renderer%s%s, median of %d after %d warm-up; error against the reference\n",
                o.scenePath.c_str(), base.width, base.height, rendererName(kind), device.empty() ? "" : " on ",
                device.c_str(), o.repeats, o.warmup);
    std::printf("%-18s %10s %10s %12s  %s\n", "candidate", "ms", "error", "p99 tile", "Pareto front");
    for (const TradeoffCandidate& c : cands) {
        std::printf("%-18s %10.2f %10s %12s  %s\n", candidateLabel(c).c_str(), c.ms, percent(c.error.relMae).c_str(),
                    percent(c.error.p99TileError).c_str(), c.pareto ? "*" : "");
    }
    // Where more frames do not help, say so: the table shows it, the sentence names it.
    for (const TradeoffCandidate& c : cands) {
        if (c.frames <= 1) continue;
        for (const TradeoffCandidate& one : cands) {
            if (one.frames == 1 && one.quality == c.quality && one.tilePx == c.tilePx && one.slices == c.slices &&
                c.error.relMae >= one.error.relMae) {
                std::printf("note: %s is no more accurate than %s: this scene's error is not one that temporal "
                            "frames average away (docs/temporal.md)\n",
                            candidateLabel(c).c_str(), candidateLabel(one).c_str());
            }
        }
    }
    if (o.maxErrorPercent >= 0.0) {
        const int i = fastestUnderError(cands, o.maxErrorPercent / 100.0);
        if (i < 0)
            std::printf("recommendation: no candidate is within %.2f%%\n", o.maxErrorPercent);
        else
            std::printf("recommendation: fastest within %.2f%%: %s (%.2f ms, %s)\n", o.maxErrorPercent,
                        candidateLabel(cands[static_cast<size_t>(i)]).c_str(), cands[static_cast<size_t>(i)].ms,
                        percent(cands[static_cast<size_t>(i)].error.relMae).c_str());
    }
    if (o.budgetMs >= 0.0) {
        const int i = mostAccurateUnderBudget(cands, o.budgetMs);
        if (i < 0)
            std::printf("recommendation: no candidate takes %.2f ms or less\n", o.budgetMs);
        else
            std::printf("recommendation: most accurate within %.2f ms: %s (%.2f ms, %s)\n", o.budgetMs,
                        candidateLabel(cands[static_cast<size_t>(i)]).c_str(), cands[static_cast<size_t>(i)].ms,
                        percent(cands[static_cast<size_t>(i)].error.relMae).c_str());
    }
    const std::string title = fs::path(o.scenePath).filename().string() + ", " + std::to_string(base.width) + "x" +
                              std::to_string(base.height) + ", " + rendererName(kind);
    if (!o.svgPath.empty()) {
        if (Result<void> w = writeTextFileAtomic(o.svgPath, chartSvg(cands, title)); !w) return badInput(w.error().message);
    }
    if (!o.jsonPath.empty()) {
        if (Result<void> w = writeTextFileAtomic(o.jsonPath, candidatesJson(cands, o.scenePath, base, rendererName(kind)));
            !w)
            return badInput(w.error().message);
    }
    return success();
}

}  // namespace brume::app
