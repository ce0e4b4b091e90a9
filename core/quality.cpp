#include "quality.h"

#include <algorithm>
#include <array>

#include "../shaders/shared/froxel.h"

namespace brume {

// Budgets at 1280x720: low 80x45x32 = 115k froxels, medium 107x60x64 = 411k, high 160x90x96 = 1.38M,
// ultra 320x180x128 = 7.4M.
static constexpr std::array<QualityPreset, 4> kPresets = {{
    {Quality::Low, 16, 32, 2.0f, 48.0f},
    {Quality::Medium, 12, 64, 2.0f, 64.0f},
    {Quality::High, 8, 96, 2.0f, 96.0f},
    {Quality::Ultra, 4, 128, 2.0f, 128.0f},
}};

const QualityPreset& qualityPreset(Quality q) { return kPresets[static_cast<size_t>(q)]; }

FroxelSettings resolveFroxelSettings(const Scene& scene, Quality quality) {
    const QualityPreset& p = qualityPreset(quality);
    const FroxelOverrides& o = scene.froxels;
    FroxelSettings s;
    s.tile_px = o.tile_px.value_or(p.tile_px);
    s.slices = o.slices.value_or(p.slices);
    s.distribution = o.distribution.value_or(p.distribution);
    s.near = o.near.value_or(scene.camera.near);
    s.far = std::min(o.far.value_or(p.far), scene.camera.far);
    // The slice mapping divides by (far - near): keep a positive span even for odd overrides.
    s.far = std::max(s.far, s.near * (1.0f + 1e-3f) + 1e-4f);
    return s;
}

glm::ivec3 froxelGridDims(int width, int height, const FroxelSettings& s) {
    return {shd::brumeDivRoundUp(width, s.tile_px), shd::brumeDivRoundUp(height, s.tile_px), s.slices};
}

bool parseQuality(const std::string& text, Quality& out) {
    for (const QualityPreset& p : kPresets) {
        if (text == toString(p.quality)) {
            out = p.quality;
            return true;
        }
    }
    return false;
}

}  // namespace brume
