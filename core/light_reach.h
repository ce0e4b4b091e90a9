// Which lights can touch anything a frame shades (docs/gpu.md, "Light reach"): the per-frame
// complement of the light clusters (core/clusters.h) for the passes the clusters do not cover.
//   surface lights   lights whose range can reach the camera frustum (near to far), fog_scale
//                    ignored: the geometry pass loops over these only;
//   shadow volume    per light, whether its layer of the transmittance volume is computed: it is
//                    fog-shadowed (shd::fogShadowsLight) and a reader needs it: the light pass (the
//                    light is in a cluster's list) or the surfaces (its range reaches the view
//                    frustum up to the froxel far, where surfaces read the volume).
// Both are conservative: a light left out contributes exactly 0 wherever it is left out, so the
// image is the unculled one, bit for bit on the CPU. Uploaded after the cluster records
// (shd::lightReachOffset).
#pragma once

#include <vector>

#include "clusters.h"
#include "compile.h"
#include "media_region.h"

namespace brume {

struct LightReach {
    // Light indices: the directional ones ascending, then the others ascending. The composite's
    // distant fog needs only the directional lights and stops at the first other one: on lavapipe
    // a loop trip costs the same whether its body is skipped or not (docs/performance.md).
    std::vector<int> surfaceLights;
    std::vector<int> shadowVolume;   // per light: 1 = its transmittance layer is computed
    // Lights whose glow (shared/glow.h) the glow pass adds per pixel, ascending: a glow radius in this
    // frame, and (with culling) a range that reaches some volume's bounds; elsewhere the glow is 0.
    std::vector<int> glowLights;
};

// The reach for `frame`, whose light pass reads `clusters`. culling = false: every light is a surface
// light and every fog-shadowed light gets its layer. surfaces = false: the frame shades no surface
// (no geometry), so only the light pass reads the transmittance volume. lightPassFroxels: the
// froxels the light pass runs (the GPU's media region, core/media_region.h), whose clusters' lists
// are the ones it reads; null = every froxel.
LightReach buildLightReach(const CompiledScene& cs, const shd::FrameUniforms& frame, const LightClusters& clusters,
                           bool culling = true, bool surfaces = true, const FroxelRegion* lightPassFroxels = nullptr);

// Whether light l's range window can reach a point of the view frustum between view depths
// nearDepth and farDepth [m] (fog_scale is not looked at).
bool lightMayReachFrustum(const shd::LightData& l, const shd::FrameUniforms& frame, float nearDepth, float farDepth);

// Per light, the box of the froxels of `froxels` whose cluster lists it (every froxel of an over-full
// cluster): the only froxels where the light passes use the light's layer of the transmittance
// volume (a froxel whose cluster does not list a light never adds its term). Empty for a light no
// such cluster lists. The shadow volume pass computes each layer's cells around its box only
// (core/media_region.h shadowCellRegion of the box; docs/gpu.md "Transmittance cells").
std::vector<FroxelRegion> listedFroxelRegions(const LightClusters& clusters, size_t lightCount,
                                              const FroxelRegion& froxels);

// The ints the GPU reads after the cluster records (shared/clusters.h lightReachOffset): the surface
// lights as a count and their indices, padded to the light count; 1 + lights ints. The layers and the
// glowing lights stay on the host, which dispatches the shadow volume pass per layer and the glow
// pass per light.
std::vector<int> lightReachRecord(const LightReach& reach, size_t lightCount);

}  // namespace brume
