// The arithmetic of `brume tradeoff` (core/tradeoff.h).
#include "tradeoff.h"

#include <algorithm>
#include <cmath>
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
