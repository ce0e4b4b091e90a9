// The speed/accuracy trade of the froxel renderers on one scene (`brume tradeoff`, docs/quality.md):
// how far an image is from the reference, which candidates no other beats on both time and error
// (the Pareto front), and which to recommend under an error or a time budget. The rendering and
// timing live in app/tradeoff_command.cpp; this is the arithmetic, so tests can check it alone.
#pragma once

#include <string>
#include <vector>

#include "image.h"
#include "quality.h"

namespace brume {

// Side of the square pixel tiles of the local error [px]: small enough that a light's halo or a
// shaft's edge fills a good part of one, large enough that a tile's error is not one pixel's noise.
inline constexpr int kTradeoffTilePx = 16;

struct ImageError {
    double relMae = 0.0;        // relativeMeanAbsError against the reference
    double p99TileError = 0.0;  // 99th percentile over tiles of mean |a - ref| / the image's mean |ref|
};

// Both measures of `img` against `ref` (same size). A tile's error is normalised by the mean of the
// whole reference, not the tile's own, so that dark tiles do not swamp the percentile with noise.
ImageError measureImageError(const Image& img, const Image& ref, int tilePx = kTradeoffTilePx);

struct TradeoffCandidate {
    Quality quality = Quality::Medium;
    int frames = 1;
    int tilePx = 0;  // --grid override of the preset's tile [px], 0 = the preset's
    int slices = 0;  // --grid override of the preset's slices, 0 = the preset's
    double ms = 0.0;          // median wall time of the render that produces the image (all its frames)
    ImageError error;
    bool pareto = false;      // no other candidate is at least as fast and as accurate, and better in one
};

// "medium x4" or "grid 8x96 x16": how tables, charts and JSON name a candidate.
std::string candidateLabel(const TradeoffCandidate& c);

// Sets `pareto` on every candidate (by ms and relMae).
void markParetoFront(std::vector<TradeoffCandidate>& candidates);

// Index of the fastest candidate whose relMae <= maxRelMae, or -1 when none is.
int fastestUnderError(const std::vector<TradeoffCandidate>& candidates, double maxRelMae);
// Index of the most accurate candidate whose ms <= budgetMs, or -1 when none is.
int mostAccurateUnderBudget(const std::vector<TradeoffCandidate>& candidates, double budgetMs);

// "TILExSLICES" (e.g. "8x96") into tile and slices within the ranges of froxels.tile_px and
// froxels.slices (core/settings.h); false when malformed or out of range.
bool parseGrid(const std::string& text, int& tilePx, int& slices);

}  // namespace brume
