// The sun shadow map on the host (shaders/shared/sun_shadow.h): built by ray casting the preview
// geometry into the fitted map's texel centres, sampled with the shared PCF. The CPU froxel
// renderer samples it directly; the GPU renderer uploads the same map, so both see the same bits.
#pragma once

#include <array>
#include <vector>

#include "compile.h"
#include "geometry.h"
#include "quality.h"

namespace brume {

// Texels per side of the sun shadow map at this quality (docs/shadows.md, "Sun shadow map").
int sunShadowMapResolution(Quality q);

// The light the map serves: the first directional light with shadows = true; -1 when none.
int sunShadowLight(const CompiledScene& cs);

struct SunShadowMap {
    shd::SunShadowFit fit{};
    std::vector<float> depth;  // 2 layers of N x N, row-major (shd::sunShadowIndex, shd::sunShadowFroxelIndex); empty: none
};

// Sets frame.sunShadowLight (the mapped light) for the scene: call after applyShadowSettings.
void applySunShadowSettings(shd::FrameUniforms& frame, const CompiledScene& cs);

// The map for frame (empty when frame.sunShadowLight is 0). Independent of the frame's jitter.
// Each texel's rays test only the primitives whose bounds project onto it (the ground plane and the
// few solids in its footprint, not every solid of the scene); cullByFootprint false tests every
// primitive, the same map bit for bit (tests/test_sun_shadow.cpp holds them equal).
SunShadowMap buildSunShadowMap(const CompiledScene& cs, const GeometrySet& geometry, const shd::FrameUniforms& frame,
                               int resolution, int threads, bool cullByFootprint = true);

// The last two maps built, each kept while its geometry and fit (camera, froxel range, light
// direction, resolution) do not change; a request that matches neither rebuilds the older one. The
// GPU renderer keeps one cache, so that edits of fog and lights in the editor do not pay for the
// host ray cast again, and the editor's coarse frames while dragging (a lower resolution) do not
// evict the map of its full-quality frames at rest.
class SunShadowCache {
public:
    const SunShadowMap& get(const CompiledScene& cs, const std::vector<Geometry>& geometry,
                            const shd::FrameUniforms& frame, int resolution, int threads);
    int builds() const { return builds_; }

private:
    struct Entry {
        SunShadowMap map;
        std::vector<Geometry> geometry;
        bool valid = false;
    };
    std::array<Entry, 2> entries_;  // [0]: the one used last
    int builds_ = 0;
};

// Visibility of light `light` at p through the map: 1 for lights the map does not serve.
float sunShadowVisibility(const SunShadowMap& map, const shd::FrameUniforms& frame, int light, glm::vec3 p);

// The same for a froxel's sample point (the light pass): the map's froxel layer, which shadows the
// fog inside solids (shared/sun_shadow.h).
float sunShadowFroxelVisibility(const SunShadowMap& map, const shd::FrameUniforms& frame, int light, glm::vec3 p);

}  // namespace brume
