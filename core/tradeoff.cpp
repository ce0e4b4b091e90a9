// The arithmetic of `brume tradeoff` (core/tradeoff.h).
#include "tradeoff.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>

#include "settings.h"

namespace brume {

ImageError measureImageError(const Image& img, const Image& ref, int tilePx) {
    if (img.width != ref.width || img.height != ref.height) throw std::invalid_argument("image sizes differ");
    ImageError e;
    e.relMae = relativeMeanAbsError(img, ref);
    double refSum = 0.0;
    for (const glm::vec3& p : ref.pixels) refSum += std::abs(double(p.x)) + std::abs(double(p.y)) + std::abs(double(p.z));
    const double refMean = refSum / std::max<double>(1.0, 3.0 * static_cast<double>(ref.pixels.size()));
    const int tile = std::max(tilePx, 1);
    std::vector<double> tiles;
    for (int ty = 0; ty < ref.height; ty += tile) {
        for (int tx = 0; tx < ref.width; tx += tile) {
            double diff = 0.0;
            int count = 0;
            for (int y = ty; y < std::min(ty + tile, ref.height); ++y) {
                for (int x = tx; x < std::min(tx + tile, ref.width); ++x) {
                    const glm::vec3 d = glm::abs(img.at(x, y) - ref.at(x, y));
                    diff += double(d.x) + double(d.y) + double(d.z);
                    count += 3;
                }
            }
            tiles.push_back(refMean > 0.0 ? diff / count / refMean : diff / count);
        }
    }
    if (!tiles.empty()) {
        // Nearest rank: the smallest tile error that at least 99% of the tiles do not exceed.
        const size_t rank = static_cast<size_t>(std::ceil(0.99 * static_cast<double>(tiles.size())));
        std::nth_element(tiles.begin(), tiles.begin() + static_cast<long>(rank - 1), tiles.end());
        e.p99TileError = tiles[rank - 1];
    }
    return e;
}

std::string candidateLabel(const TradeoffCandidate& c) {
    std::string s = c.tilePx > 0 ? "grid " + std::to_string(c.tilePx) + "x" + std::to_string(c.slices)
                                 : std::string(toString(c.quality));
    return s + " x" + std::to_string(c.frames);
}

void markParetoFront(std::vector<TradeoffCandidate>& candidates) {
    for (TradeoffCandidate& c : candidates) {
        c.pareto = std::none_of(candidates.begin(), candidates.end(), [&c](const TradeoffCandidate& o) {
            const bool noWorse = o.ms <= c.ms && o.error.relMae <= c.error.relMae;
            const bool better = o.ms < c.ms || o.error.relMae < c.error.relMae;
            return noWorse && better;
        });
    }
}

int fastestUnderError(const std::vector<TradeoffCandidate>& candidates, double maxRelMae) {
    int best = -1;
    for (size_t i = 0; i < candidates.size(); ++i) {
        const TradeoffCandidate& c = candidates[i];
        if (c.error.relMae > maxRelMae) continue;
        if (best < 0 || c.ms < candidates[static_cast<size_t>(best)].ms) best = static_cast<int>(i);
    }
    return best;
}

int mostAccurateUnderBudget(const std::vector<TradeoffCandidate>& candidates, double budgetMs) {
    int best = -1;
    for (size_t i = 0; i < candidates.size(); ++i) {
        const TradeoffCandidate& c = candidates[i];
        if (c.ms > budgetMs) continue;
        if (best < 0 || c.error.relMae < candidates[static_cast<size_t>(best)].error.relMae) best = static_cast<int>(i);
    }
    return best;
}

TradeoffChartAxes tradeoffChartAxes(const std::vector<TradeoffCandidate>& cands) {
    double msLo = 1e300, msHi = 0, eLo = 1e300, eHi = 0;
    for (const TradeoffCandidate& c : cands) {
        msLo = std::min(msLo, std::max(c.ms, 1e-3));
        msHi = std::max(msHi, std::max(c.ms, 1e-3));
        eLo = std::min(eLo, std::max(c.error.relMae, 1e-6));
        eHi = std::max(eHi, std::max(c.error.relMae, 1e-6));
    }
    TradeoffChartAxes a;
    if (cands.empty()) return a;
    a.msLog0 = std::floor(std::log10(msLo));
    a.msLog1 = std::max(std::ceil(std::log10(msHi)), a.msLog0 + 1);
    a.errorLog0 = std::floor(std::log10(eLo));
    a.errorLog1 = std::max(std::ceil(std::log10(eHi)), a.errorLog0 + 1);
    return a;
}

double TradeoffChartAxes::x(double ms) const { return (std::log10(std::max(ms, 1e-3)) - msLog0) / (msLog1 - msLog0); }
double TradeoffChartAxes::y(double e) const {
    return (std::log10(std::max(e, 1e-6)) - errorLog0) / (errorLog1 - errorLog0);
}

std::vector<size_t> paretoFrontByMs(const std::vector<TradeoffCandidate>& cands) {
    std::vector<size_t> front;
    for (size_t i = 0; i < cands.size(); ++i)
        if (cands[i].pareto) front.push_back(i);
    std::sort(front.begin(), front.end(), [&cands](size_t a, size_t b) { return cands[a].ms < cands[b].ms; });
    return front;
}

ErrorMap pixelErrorMap(const Image& img, const Image& ref) {
    if (img.width != ref.width || img.height != ref.height) throw std::invalid_argument("image sizes differ");
    double refSum = 0.0;
    for (const glm::vec3& p : ref.pixels) refSum += std::abs(double(p.x)) + std::abs(double(p.y)) + std::abs(double(p.z));
    const double refMean = refSum / std::max<double>(1.0, 3.0 * static_cast<double>(ref.pixels.size()));
    ErrorMap m;
    m.width = img.width;
    m.height = img.height;
    m.values.resize(img.pixels.size());
    for (size_t i = 0; i < img.pixels.size(); ++i) {
        const glm::dvec3 d = glm::abs(glm::dvec3(img.pixels[i]) - glm::dvec3(ref.pixels[i]));
        const double e = (d.x + d.y + d.z) / 3.0;
        m.values[i] = static_cast<float>(refMean > 0.0 ? e / refMean : e);
    }
    m.scale = heatMapScale(m.values);
    return m;
}

float heatMapScale(const std::vector<float>& values) {
    double p99 = 0.0;
    if (!values.empty()) {
        std::vector<float> v = values;
        const size_t rank = static_cast<size_t>(std::ceil(0.99 * static_cast<double>(v.size())));
        std::nth_element(v.begin(), v.begin() + static_cast<long>(rank - 1), v.end());
        p99 = v[rank - 1];
    }
    p99 = std::max(p99, 1e-4);
    const double decade = std::pow(10.0, std::floor(std::log10(p99)));
    for (double step : {1.0, 2.0, 5.0, 10.0})
        if (step * decade >= p99 * (1.0 - 1e-6)) return static_cast<float>(step * decade);
    return static_cast<float>(10.0 * decade);
}

glm::vec3 heatMapColor(float t) {
    static const glm::vec3 stops[] = {{0.0f, 0.0f, 0.0f}, {0.35f, 0.05f, 0.55f}, {0.85f, 0.15f, 0.25f},
                                      {1.0f, 0.55f, 0.0f}, {1.0f, 1.0f, 0.7f}};
    constexpr int n = static_cast<int>(std::size(stops));
    const float x = std::clamp(std::isfinite(t) ? t : 1.0f, 0.0f, 1.0f) * static_cast<float>(n - 1);
    const int i = std::min(static_cast<int>(x), n - 2);
    return glm::mix(stops[i], stops[i + 1], x - static_cast<float>(i));
}

bool parseGrid(const std::string& text, int& tilePx, int& slices) {
    const size_t x = text.find('x');
    if (x == std::string::npos || x == 0 || x + 1 >= text.size()) return false;
    auto number = [](const std::string& s, int& out) {
        if (s.empty() || s.size() > 6 || !std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; }))
            return false;
        out = std::stoi(s);
        return true;
    };
    int t = 0, n = 0;
    if (!number(text.substr(0, x), t) || !number(text.substr(x + 1), n)) return false;
    if (t < settings::froxels_tile_px.min || t > settings::froxels_tile_px.max) return false;
    if (n < settings::froxels_slices.min || n > settings::froxels_slices.max) return false;
    tilePx = t;
    slices = n;
    return true;
}

}  // namespace brume
