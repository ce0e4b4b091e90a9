#include "tradeoff_measure.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/quality.h"
#include "core/settings.h"
#include "io/atomic_file.h"
#include "io/image_io.h"
#include "io/scene_json.h"

namespace brume::measure {

namespace fs = std::filesystem;

namespace {

// Bump when the reference renderer's output changes, so that old cache entries are not reused.
constexpr const char* kReferenceVersion = "brume reference 1";

uint64_t fnv1a(uint64_t h, std::string_view bytes) {
    for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
    return h;
}

// The froxel settings (render block, froxels, temporal) do not reach the reference, so editing
// them keeps the entry.
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

bool cancelled(const std::atomic<bool>* cancel) { return cancel && cancel->load(); }

}  // namespace

std::string defaultCacheDir() {
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::string(xdg) + "/brume/references";
    if (const char* home = std::getenv("HOME"); home && *home) return std::string(home) + "/.cache/brume/references";
    return ".brume-cache/references";
}

std::string referenceCachePath(const Scene& scene, int width, int height, const std::string& cacheDir) {
    char name[64];
    std::snprintf(name, sizeof(name), "reference-%016llx.exr",
                  static_cast<unsigned long long>(referenceKey(scene, width, height)));
    return (fs::path(cacheDir) / name).string();
}

Result<ReferenceResult> referenceImage(const Scene& scene, const RenderRequest& base, const std::string& cacheDir,
                                       const ProgressFn& progress, const std::atomic<bool>* cancel) {
    ReferenceResult out;
    out.path = referenceCachePath(scene, base.width, base.height, cacheDir);
    std::error_code ec;
    if (fs::exists(out.path, ec)) {
        Result<Image> img = readExr(out.path);
        if (img && img.value().width == base.width && img.value().height == base.height) {
            out.image = std::move(img.value());
            out.cached = true;
            return out;
        }
    }
    RenderRequest req = base;
    req.progress = progress;
    req.cancel = cancel;
    out.image = renderReference(scene, req);
    // An image cut short by a cancel is thrown away: it never reaches the cache.
    if (cancelled(cancel)) return Error{kCancelled};
    // Written whole or not at all (temporary file, then rename): an interrupted reference leaves
    // no cache entry. A cache that cannot be written costs the next run a render, nothing more.
    fs::create_directories(cacheDir, ec);
    const Image& ref = out.image;
    if (Result<void> w = writeFileAtomic(out.path, [&ref](const std::string& tmp) { return writeExr(ref, tmp); }); !w)
        out.warning = "reference not cached: " + w.error().message;
    return out;
}

Result<TradeoffPlan> parsePlan(const std::string& qualities, const std::string& frames,
                               const std::vector<std::string>& grids) {
    auto bad = [](std::string text) { return Error{std::move(text), true}; };
    TradeoffPlan plan;
    for (const std::string& q : splitList(qualities)) {
        Quality parsed;
        if (!parseQuality(q, parsed))
            return bad("--quality '" + q + "' is not one of " + std::string(settings::render_quality.choices) + ".");
        plan.qualities.push_back(parsed);
    }
    for (const std::string& f : splitList(frames)) {
        const bool digits = !f.empty() && f.size() <= 4 && std::all_of(f.begin(), f.end(), ::isdigit);
        const int n = digits ? std::stoi(f) : 0;
        if (n < settings::cli_frames.min || n > settings::cli_frames.max)
            return bad("--frames '" + f + "' is not a whole number in " + std::to_string(int(settings::cli_frames.min)) + ".." +
                       std::to_string(int(settings::cli_frames.max)) + ".");
        plan.frames.push_back(n);
    }
    for (const std::string& g : grids) {
        int tile = 0, slices = 0;
        if (!parseGrid(g, tile, slices))
            return bad("--grid '" + g + "' is not TILExSLICES with tile 1..64 px and slices 1..1024 (e.g. 8x96).");
        plan.grids.push_back({tile, slices});
    }
    if (plan.qualities.empty() && plan.grids.empty())
        return bad("--quality is empty and no --grid given: nothing to measure.");
    if (plan.frames.empty()) return bad("--frames is empty: nothing to measure.");
    return plan;
}

std::vector<TradeoffCandidate> plannedCandidates(const TradeoffPlan& plan, Quality gridQuality) {
    std::vector<TradeoffCandidate> cands;
    auto add = [&cands](Quality q, int f, int tile, int slices) {
        TradeoffCandidate c;
        c.quality = q;
        c.frames = f;
        c.tilePx = tile;
        c.slices = slices;
        cands.push_back(c);
    };
    for (Quality q : plan.qualities)
        for (int f : plan.frames) add(q, f, 0, 0);
    for (auto [tile, slices] : plan.grids)
        for (int f : plan.frames) add(gridQuality, f, tile, slices);
    return cands;
}

std::pair<Scene, RenderRequest> candidateRender(const Scene& scene, const RenderRequest& base,
                                                const TradeoffCandidate& c) {
    Scene s = scene;
    s.temporal.enabled = true;
    if (c.tilePx > 0) {
        s.froxels.tile_px = c.tilePx;
        s.froxels.slices = c.slices;
    }
    RenderRequest req = base;
    req.quality = c.quality;
    req.frames = c.frames;
    req.history = HistoryMode::Restart;
    req.progress = nullptr;
    req.cancel = nullptr;
    return {std::move(s), req};
}

Result<void> measureCandidates(const Scene& scene, const RenderRequest& base, const Image& reference,
                               std::vector<TradeoffCandidate>& candidates, int warmup, int repeats,
                               const CandidateRender& render, const std::function<void(size_t)>& done,
                               const std::atomic<bool>* cancel) {
    for (size_t i = 0; i < candidates.size(); ++i) {
        TradeoffCandidate& c = candidates[i];
        const auto [s, req] = candidateRender(scene, base, c);
        std::vector<double> ms;
        Image last;
        for (int r = 0; r < warmup + std::max(repeats, 1); ++r) {
            if (cancelled(cancel)) return Error{kCancelled};
            const auto start = std::chrono::steady_clock::now();
            Result<Image> img = render(s, req);
            const double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
            if (!img) return img.error();
            if (r >= warmup) ms.push_back(wall);
            last = std::move(img.value());
        }
        c.ms = median(ms);
        c.error = measureImageError(last, reference);
        if (done) done(i + 1);
    }
    markParetoFront(candidates);
    return {};
}

}  // namespace brume::measure
