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

// The chart's log axes (the SVG of `brume tradeoff --svg` and the editor's Quality panel): whole
// decades of ms and of relMae around the candidates, so the axes read as powers of ten.
struct TradeoffChartAxes {
    double msLog0 = 0.0, msLog1 = 1.0;        // log10 of the ms axis' ends
    double errorLog0 = -3.0, errorLog1 = -2.0;  // log10 of the error axis' ends
    double x(double ms) const;     // 0 at the left end, 1 at the right
    double y(double error) const;  // 0 at the bottom, 1 at the top
};
TradeoffChartAxes tradeoffChartAxes(const std::vector<TradeoffCandidate>& candidates);
// The indices of the Pareto front's candidates in order of ms (the line the chart draws).
std::vector<size_t> paretoFrontByMs(const std::vector<TradeoffCandidate>& candidates);

// Where the error is (the editor's "error" debug view, docs/quality.md): per pixel, the mean over
// rgb of |img - ref| divided by the whole reference's mean |ref|, the tiles' normalisation, so the
// map's mean is the image's relMae and a value reads as "this pixel is off by x% of the scene's
// mean brightness".
struct ErrorMap {
    int width = 0;
    int height = 0;
    std::vector<float> values;  // row-major from the top-left
    float scale = 0.0f;         // the legend's top: heatMapScale(values)
};
ErrorMap pixelErrorMap(const Image& img, const Image& ref);

// The legend's top: the 99th percentile of `values` rounded up to 1, 2 or 5 times a power of ten,
// so a few hot pixels do not wash out the ramp and its end reads as a round number; at least 1e-4.
float heatMapScale(const std::vector<float>& values);

// The ramp: black at 0, through purple, red and orange, to pale yellow at t >= 1.
glm::vec3 heatMapColor(float t);

// "TILExSLICES" (e.g. "8x96") into tile and slices within the ranges of froxels.tile_px and
// froxels.slices (core/settings.h); false when malformed or out of range.
bool parseGrid(const std::string& text, int& tilePx, int& slices);

}  // namespace brume
