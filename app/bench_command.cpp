#include "bench_command.h"
#include "vdb_command.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_text.h"
#include "core/temporal.h"
#include "io/atomic_file.h"
#include "io/scene_json.h"
#include "render_command.h"

namespace brume::app {

namespace {

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// An earlier run's --json output: its wall median and per-pass medians.
struct Baseline {
    double wallMs = 0.0;
    std::map<std::string, double> passMs;
};

// Reads `path` as `brume bench --json` output; an error is one sentence naming the file and the problem.
Result<Baseline> readBaseline(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return Error{path + ": cannot read the baseline: " + std::strerror(errno) + "."};
    std::stringstream text;
    text << in.rdbuf();
    const nlohmann::json j = nlohmann::json::parse(text.str(), nullptr, false);
    if (j.is_discarded() || !j.is_object())
        return Error{path + ": the baseline is not a JSON object (expected `brume bench --json` output)."};
    const auto wall = j.find("wall_ms");
    if (wall == j.end() || !wall->is_number() || !(wall->get<double>() > 0.0) || !std::isfinite(wall->get<double>()))
        return Error{path + ": the baseline's \"wall_ms\" is missing or not a positive number."};
    Baseline b;
    b.wallMs = wall->get<double>();
    const auto passes = j.find("pass_ms");
    if (passes == j.end() || !passes->is_object())
        return Error{path + ": the baseline's \"pass_ms\" is missing or not an object of pass names to milliseconds."};
    for (auto it = passes->begin(); it != passes->end(); ++it) {
        if (!it->is_number() || !(it->get<double>() >= 0.0) || !std::isfinite(it->get<double>()))
            return Error{path + ": the baseline's \"pass_ms\"." + it.key() + " is not a non-negative number."};
        b.passMs[it.key()] = it->get<double>();
    }
    return b;
}

// "1.23x" (this run / baseline), or "-" where the baseline has no such pass or it took 0 ms.
std::string ratioText(double now, const std::optional<Baseline>& base, const std::string& pass) {
    if (!base) return "";
    double before = base->wallMs;
    if (!pass.empty()) {
        const auto it = base->passMs.find(pass);
        if (it == base->passMs.end()) return "         -";
        before = it->second;
    }
    if (!(before > 0.0)) return "         -";
    char buf[32];
    std::snprintf(buf, sizeof buf, " %8.3fx", now / before);
    return buf;
}

}  // namespace

CLI::App* addBenchCommand(CLI::App& app, BenchOptions& o) {
    CLI::App* cmd = app.add_subcommand(
        "bench", "Time repeated renders of a scene after a warm-up and print per-pass medians (a benchmark, not a test).");
    cmd->add_option("SCENE", o.scenePath, "Scene file (JSON; see docs/scene-format.md).")->required();
    o.widthOption = cmd->add_option("--width", o.width, optionHelp(settings::render_width, "the scene's render.width"));
    o.heightOption = cmd->add_option("--height", o.height, optionHelp(settings::render_height, "the scene's render.height"));
    o.qualityOption = cmd->add_option("--quality", o.quality,
                                      optionHelp(settings::render_quality, "the scene's render.quality"));
    cmd->add_option("--frames", o.frames, "Timed renders. Default: 20. Range: 1..10000.")->check(CLI::Range(1, 10000));
    cmd->add_option("--warmup", o.warmup,
                    "Untimed renders first (the first dispatch pays shader compilation). Default: 3. Range: 0..1000.")
        ->check(CLI::Range(0, 1000));
    o.orbit = settings::cli_orbit.f();
    // The same camera path as `brume render --orbit`, over every render (warm-ups included): the timed
    // frames are then in motion, where the temporal pass reprojects (at rest it dispatches nothing).
    cmd->add_option("--orbit", o.orbit, optionHelp(settings::cli_orbit));
    cmd->add_flag("--cpu", o.cpu, "Time the CPU froxel renderer instead of the GPU. Default: off.");
    cmd->add_flag("--no-light-culling", o.noLightCulling,
                  "Light pass loops over every light, not its cluster's list (to measure culling). Default: off.");
    cmd->add_flag("--no-vdb-culling", o.noVdbCulling,
                  "vdb volumes walk their grid wherever sampled, not only in occupied cells (to measure culling). Default: off.");
    cmd->add_option("--device", o.device, "GPU renderer: Vulkan device whose name contains this text. Default: automatic.");
    cmd->add_option("--json", o.jsonPath,
                    "Also write the medians (wall and per pass, in ms) to this JSON file, for a later --baseline. "
                    "Written atomically; its folder must exist. Default: none.");
    cmd->add_option("--baseline", o.baselinePath,
                    "An earlier run's --json file: print each median's ratio to it (this run / baseline; "
                    "below 1 is faster). Default: none.");
    return cmd;
}

CommandResult runBench(const BenchOptions& o) {
    // Both files and --orbit are checked before the scene's grids are read: a typo should not cost a
    // benchmark's minutes.
    if (!std::isfinite(o.orbit) || o.orbit < settings::cli_orbit.min || o.orbit > settings::cli_orbit.max)
        return badInput("--orbit " + formatNumber(o.orbit) + " is out of range: expected " +
                        formatRange(settings::cli_orbit) + ".");
    std::optional<Baseline> baseline;
    if (!o.baselinePath.empty()) {
        Result<Baseline> b = readBaseline(o.baselinePath);
        if (!b) return badInput(b.error().message);
        baseline = b.value();
    }
    if (!o.jsonPath.empty()) {
        const std::filesystem::path dir = std::filesystem::path(o.jsonPath).parent_path().empty()
                                              ? std::filesystem::path(".")
                                              : std::filesystem::path(o.jsonPath).parent_path();
        std::error_code ec;
        if (!std::filesystem::is_directory(dir, ec))
            return badInput(o.jsonPath + ": --json folder '" + dir.string() + "' does not exist.");
    }
    Result<Scene> scene = loadSceneFile(o.scenePath);
    if (!scene) return badInput(scene.error().message);
    if (Result<void> g = loadGridsPrintingWarnings(scene.value(), o.scenePath, settings::cli_vdb_memory.i()); !g)
        return badInput(g.error().message);
    RenderRequest request = requestFromScene(scene.value());
    if (o.widthOption->count() > 0) request.width = o.width;
    if (o.heightOption->count() > 0) request.height = o.height;
    if (request.width < settings::render_width.min || request.width > settings::render_width.max ||
        request.height < settings::render_height.min || request.height > settings::render_height.max) {
        return badInput("--width/--height out of range: expected " + formatRange(settings::render_width) + ".");
    }
    if (o.qualityOption->count() > 0 && !parseQuality(o.quality, request.quality)) {
        return badInput("--quality '" + o.quality + "' is not one of " + std::string(settings::render_quality.choices) + ".");
    }
    request.lightCulling = !o.noLightCulling;
    request.vdbCulling = !o.noVdbCulling;
    const RendererKind kind = o.cpu ? RendererKind::FroxelCpu : RendererKind::Gpu;

    // One session for every frame: what an editor pays per frame, not per start-up; the frames form
    // one temporal sequence, so the temporal pass reads its history as it does in an editor.
    request.history = HistoryMode::Continue;
    RenderSession session(kind, o.device);
    if (session.startFailure()) return badInput(session.startFailure()->message);
    std::map<std::string, std::vector<double>> passMs;
    std::vector<std::string> order;
    std::vector<double> wall;
    RenderStats last;
    Scene frameScene = scene.value();
    for (int i = 0; i < o.warmup + o.frames; ++i) {
        if (o.orbit != 0.0f) frameScene.camera = orbitCamera(scene.value().camera, o.orbit * static_cast<float>(i));
        std::variant<RenderOutput, RenderFailure> r = session.render(frameScene, request);
        if (const RenderFailure* f = std::get_if<RenderFailure>(&r)) return internalFailure(f->message);
        if (i < o.warmup) continue;
        last = std::get<RenderOutput>(r).stats;
        wall.push_back(last.wallMs);
        for (const PassTime& p : last.passes) {
            if (!passMs.count(p.name)) order.push_back(p.name);
            passMs[p.name].push_back(p.gpuMs);
        }
    }
    const double wallMedian = median(wall);
    const std::string motion = o.orbit != 0.0f ? ", camera orbiting " + formatNumber(o.orbit) + " deg per frame" : "";
    std::printf("brume bench: %s, %s renderer%s%s, %dx%d, quality %s, froxels %dx%dx%d, %d frames after %d warm-up%s\n",
                o.scenePath.c_str(), rendererName(kind), last.device.empty() ? "" : " on ", last.device.c_str(),
                request.width, request.height, toString(request.quality), last.froxelDims.x, last.froxelDims.y,
                last.froxelDims.z, o.frames, o.warmup, motion.c_str());
    double passSum = 0.0;
    for (const std::string& name : order) passSum += median(passMs[name]);
    // The first column as wide as the longest pass name ("composite all far").
    int w = 12;
    for (const std::string& name : order) w = std::max(w, static_cast<int>(name.size()));
    if (!order.empty()) {
        std::printf("%-*s %10s %10s %10s %8s%s\n", w, "pass", "median ms", "min ms", "max ms", "share",
                    baseline ? "  /baseline" : "");
        for (const std::string& name : order) {
            const std::vector<double>& v = passMs[name];
            const double m = median(v);
            std::printf("%-*s %10.3f %10.3f %10.3f %7.1f%%%s\n", w, name.c_str(), m, *std::min_element(v.begin(), v.end()),
                        *std::max_element(v.begin(), v.end()), passSum > 0.0 ? 100.0 * m / passSum : 0.0,
                        ratioText(m, baseline, name).c_str());
        }
        std::printf("%-*s %10.3f   (sum of pass medians; wall/GPU ratio %.2f)\n", w, "gpu total", passSum,
                    passSum > 0.0 ? wallMedian / passSum : 0.0);
    }
    std::printf("%-*s %10.3f   (median wall clock per render)\n", w, "wall", wallMedian);
    if (baseline) {
        std::printf("baseline %s: wall %.3f ms, this run / baseline %.3fx (below 1 is faster)\n", o.baselinePath.c_str(),
                    baseline->wallMs, wallMedian / baseline->wallMs);
    }
    std::printf("lit froxels %zu, skipped %zu (%.1f%% skipped)\n", last.litFroxels, last.skippedFroxels,
                100.0 * static_cast<double>(last.skippedFroxels) /
                    static_cast<double>(std::max<size_t>(1, last.litFroxels + last.skippedFroxels)));
    printClusterWarning(o.scenePath, last);
    if (!o.jsonPath.empty()) {
        nlohmann::ordered_json j;
        j["brume_bench"] = 1;
        j["scene"] = o.scenePath;
        j["renderer"] = rendererName(kind);
        if (!last.device.empty()) j["device"] = last.device;
        j["width"] = request.width;
        j["height"] = request.height;
        j["quality"] = toString(request.quality);
        j["frames"] = o.frames;
        j["warmup"] = o.warmup;
        j["orbit_deg"] = o.orbit;
        j["wall_ms"] = wallMedian;
        nlohmann::ordered_json passes = nlohmann::ordered_json::object();
        for (const std::string& name : order) passes[name] = median(passMs[name]);
        j["pass_ms"] = passes;
        if (Result<void> w = writeTextFileAtomic(o.jsonPath, j.dump(2) + "\n"); !w) return badInput(w.error().message);
    }
    return success();
}

}  // namespace brume::app
