#include "tradeoff_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "cli_text.h"
#include "core/tradeoff.h"
#include "io/atomic_file.h"
#include "io/image_io.h"
#include "io/scene_json.h"
#include "progress.h"
#include "render_command.h"
#include "vdb_command.h"

namespace brume::app {

namespace fs = std::filesystem;

namespace {

// Bump when the reference renderer's output changes, so that old cache entries are not reused.
constexpr const char* kReferenceVersion = "brume reference 1";

uint64_t fnv1a(uint64_t h, std::string_view bytes) {
    for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
    return h;
}

// The scene's content: its canonical JSON, the image size, the reference's version and the bytes
// of every file it reads (vdb volumes, density textures). The froxel settings (render block, froxels,
// temporal) do not reach the reference, so editing them keeps the entry.
uint64_t referenceKey(const Scene& scene, int width, int height) {
    Scene content = scene;
    content.render = Scene().render;
    content.froxels = FroxelOverrides{};
    content.temporal = Scene().temporal;
    uint64_t h = 14695981039346656037ull;
    h = fnv1a(h, kReferenceVersion);
    h = fnv1a(h, sceneToJson(content));
    h = fnv1a(h, std::to_string(width) + "x" + std::to_string(height));
    auto addFile = [&](const std::string& file) {
        if (file.empty()) return;
        fs::path p(file);
        if (p.is_relative()) p = fs::path(scene.baseDir) / p;
        std::ifstream in(p, std::ios::binary);
        std::ostringstream bytes;
        bytes << in.rdbuf();
        h = fnv1a(h, bytes.str());
    };
    for (const Volume& v : scene.volumes) {
        addFile(v.file);
        if (v.density_texture) addFile(v.density_texture->file);
        if (v.density_texture && v.density_texture->detail) addFile(v.density_texture->detail->file);
    }
    return h;
}

std::string defaultCacheDir() {
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::string(xdg) + "/brume/references";
    if (const char* home = std::getenv("HOME"); home && *home) return std::string(home) + "/.cache/brume/references";
    return ".brume-cache/references";
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n == 0 ? 0.0 : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::vector<std::string> splitList(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream ss(text);
    for (std::string item; std::getline(ss, item, ',');) out.push_back(item);
    return out;
}

// Whether a file can be created at `path` (its folder exists and is writable), checked before the
// long work so that a bad path fails in a second, not after the renders.
bool writableOutput(const std::string& path) {
    const fs::path p = fs::absolute(path);
    std::error_code ec;
    if (fs::is_directory(p, ec)) return false;
    const fs::path dir = p.parent_path();
    return fs::is_directory(dir, ec) && access(dir.c_str(), W_OK) == 0;
}

Result<Image> referenceImage(const Scene& scene, const RenderRequest& base, const std::string& cacheDir) {
    char name[64];
    std::snprintf(name, sizeof(name), "reference-%016llx.exr",
                  static_cast<unsigned long long>(referenceKey(scene, base.width, base.height)));
    const fs::path cached = fs::path(cacheDir) / name;
    std::error_code ec;
    if (fs::exists(cached, ec)) {
        Result<Image> img = readExr(cached.string());
        if (img && img.value().width == base.width && img.value().height == base.height) {
            std::fprintf(stderr, "reference: cached (%s)\n", cached.string().c_str());
            return img;
        }
    }
    std::fprintf(stderr, "reference: not cached, rendering %dx%d\n", base.width, base.height);
    RenderRequest req = base;
    ProgressLine line("rendering the reference (once; cached by the scene's content)", true);
    req.progress = [&line](float f) { line.update(f); };
    Image ref = renderReference(scene, req);
    line.complete();
    // Written whole or not at all (temporary file, then rename): an interrupted reference leaves
    // no cache entry. A cache that cannot be written costs the next run a render, nothing more.
    fs::create_directories(cacheDir, ec);
    if (Result<void> w = writeFileAtomic(cached.string(), [&ref](const std::string& tmp) { return writeExr(ref, tmp); });
        !w) {
        std::fprintf(stderr, "warning: reference not cached: %s\n", w.error().message.c_str());
    }
    return ref;
}

std::string percent(double f) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%.2f%%", 100.0 * f);
    return buf;
}

// Error against milliseconds on log axes; the front drawn as a line, every point labelled.
std::string chartSvg(const std::vector<TradeoffCandidate>& cands, const std::string& title) {
    const double W = 720, H = 480, left = 70, right = 20, top = 40, bottom = 60;
    double msLo = 1e300, msHi = 0, eLo = 1e300, eHi = 0;
    for (const TradeoffCandidate& c : cands) {
        msLo = std::min(msLo, std::max(c.ms, 1e-3));
        msHi = std::max(msHi, std::max(c.ms, 1e-3));
        eLo = std::min(eLo, std::max(c.error.relMae, 1e-6));
        eHi = std::max(eHi, std::max(c.error.relMae, 1e-6));
    }
    // Whole decades around the data, so the axes read as powers of ten.
    const double x0 = std::floor(std::log10(msLo)), x1 = std::max(std::ceil(std::log10(msHi)), x0 + 1);
    const double y0 = std::floor(std::log10(eLo)), y1 = std::max(std::ceil(std::log10(eHi)), y0 + 1);
    auto px = [&](double ms) { return left + (std::log10(std::max(ms, 1e-3)) - x0) / (x1 - x0) * (W - left - right); };
    auto py = [&](double e) { return H - bottom - (std::log10(std::max(e, 1e-6)) - y0) / (y1 - y0) * (H - top - bottom); };
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
    std::vector<const TradeoffCandidate*> front;
    for (const TradeoffCandidate& c : cands)
        if (c.pareto) front.push_back(&c);
    std::sort(front.begin(), front.end(), [](auto* a, auto* b) { return a->ms < b->ms; });
    s << "<polyline class=\"pareto-front\" fill=\"none\" stroke=\"#d62728\" stroke-width=\"1.5\" points=\"";
    for (const TradeoffCandidate* c : front) s << px(c->ms) << "," << py(c->error.relMae) << " ";
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
    std::vector<Quality> qualities;
    for (const std::string& q : splitList(o.qualities)) {
        Quality parsed;
        if (!parseQuality(q, parsed))
            return badInput("--quality '" + q + "' is not one of " + std::string(settings::render_quality.choices) + ".");
        qualities.push_back(parsed);
    }
    std::vector<int> frames;
    for (const std::string& f : splitList(o.frames)) {
        const bool digits = !f.empty() && f.size() <= 4 && std::all_of(f.begin(), f.end(), ::isdigit);
        const int n = digits ? std::stoi(f) : 0;
        if (n < settings::cli_frames.min || n > settings::cli_frames.max)
            return badInput("--frames '" + f + "' is not a whole number in " + formatRange(settings::cli_frames) + ".");
        frames.push_back(n);
    }
    std::vector<std::pair<int, int>> grids;
    for (const std::string& g : o.grids) {
        int tile = 0, slices = 0;
        if (!parseGrid(g, tile, slices))
            return badInput("--grid '" + g + "' is not TILExSLICES with tile 1..64 px and slices 1..1024 (e.g. 8x96).");
        grids.push_back({tile, slices});
    }
    if (qualities.empty() && grids.empty()) return badInput("--quality is empty and no --grid given: nothing to measure.");
    if (frames.empty()) return badInput("--frames is empty: nothing to measure.");
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

    Result<Image> ref = referenceImage(scene, base, o.cacheDir.empty() ? defaultCacheDir() : o.cacheDir);
    if (!ref) return internalFailure(ref.error().message);

    const RendererKind kind = o.cpu ? RendererKind::FroxelCpu : RendererKind::Gpu;
    RenderSession session(kind, o.device);
    if (session.startFailure()) return badInput(session.startFailure()->message);

    std::vector<TradeoffCandidate> cands;
    auto add = [&cands](Quality q, int f, int tile, int slices) {
        TradeoffCandidate c;
        c.quality = q;
        c.frames = f;
        c.tilePx = tile;
        c.slices = slices;
        cands.push_back(c);
    };
    for (Quality q : qualities)
        for (int f : frames) add(q, f, 0, 0);
    for (auto [tile, slices] : grids)
        for (int f : frames) add(base.quality, f, tile, slices);
    ProgressLine line("timing " + std::to_string(cands.size()) + " candidates", true);
    std::string device;
    for (size_t i = 0; i < cands.size(); ++i) {
        TradeoffCandidate& c = cands[i];
        Scene s = scene;
        s.temporal.enabled = true;
        if (c.tilePx > 0) {
            s.froxels.tile_px = c.tilePx;
            s.froxels.slices = c.slices;
        }
        RenderRequest req = base;
        req.quality = c.quality;
        req.frames = c.frames;
        std::vector<double> ms;
        Image last;
        for (int r = 0; r < o.warmup + o.repeats; ++r) {
            std::variant<RenderOutput, RenderFailure> out = session.render(s, req);
            if (const RenderFailure* f = std::get_if<RenderFailure>(&out))
                return f->userCanFix ? badInput(f->message) : internalFailure(f->message);
            RenderOutput& got = std::get<RenderOutput>(out);
            device = got.stats.device;
            if (r >= o.warmup) ms.push_back(got.stats.wallMs);
            last = std::move(got.image);
        }
        c.ms = median(ms);
        c.error = measureImageError(last, ref.value());
        line.update(static_cast<float>(i + 1) / static_cast<float>(cands.size()));
    }
    line.complete();
    markParetoFront(cands);

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
