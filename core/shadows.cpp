#include "shadows.h"

#include <cmath>

#include "local_shadow.h"
#include "parallel.h"
#include "vdb_shadow.h"

namespace brume {

// On at every quality: off, a point light inside an opaque fog bank lit it as if it were clear air
// (the opaque-box case of tests/test_extremes.cpp: 3.8e5 instead of 0.25 at low). At low it costs
// ~25% of the light pass on lavapipe (docs/reliability.md).
bool localLightFogShadows(Quality) { return true; }

// docs/shadows.md, "Cost": 2 keeps the shadow-edge froxels' exact fallback rare enough that the
// light pass costs ~1/4 of the all-exact one, at an added error far below the froxel's own.
int shadowVolumeReduction(Quality q) { return q == Quality::Low ? 4 : 2; }

void applyShadowSettings(shd::FrameUniforms& frame, const RenderRequest& request) {
    frame.localFogShadows = localLightFogShadows(request.quality) ? 1 : 0;
    frame.shadowReduction = request.shadowReduction > 0 ? request.shadowReduction : shadowVolumeReduction(request.quality);
    frame.localShadowTexels = localShadowMapResolution(request.quality);
}

glm::vec3 lightFogTransmittance(const CompiledScene& cs, const shd::LightData& l, glm::vec3 p, glm::vec3 toLight,
                                float distance, int localLightsToo) {
    if (!shd::fogShadowsLight(l, localLightsToo)) return glm::vec3(1.0f);
    glm::vec3 tau(0.0f);
    for (const shd::VolumeData& v : cs.volumes) tau += shd::shadowOpticalDepth(v, p, toLight, distance);
    return glm::exp(-tau);
}

namespace {

size_t shadowIndex(glm::ivec3 d, int light, glm::ivec3 c) { return static_cast<size_t>(shd::shadowVolumeIndex(d, light, c)); }

// The 8 cells around lookup k, blended (fog_shadow.glsl blendShadowCells).
shd::ShadowBlend blendShadowCells(const ShadowVolume& sv, int light, const shd::ShadowLookup& k) {
    auto at = [&](int x, int y, int z) {
        const glm::ivec3 c(x ? k.upper.x : k.cell.x, y ? k.upper.y : k.cell.y, z ? k.upper.z : k.cell.z);
        return glm::vec3(sv.transmittance[shadowIndex(sv.dims, light, c)]);
    };
    return shd::shadowBlend(at(0, 0, 0), at(1, 0, 0), at(0, 1, 0), at(1, 1, 0), at(0, 0, 1), at(1, 0, 1),
                            at(0, 1, 1), at(1, 1, 1), k.weights);
}

// Light `light`'s vdb transmittance at k (fog_shadow.glsl vdbShadowBlend): never evaluated exactly
// outside the shadow volume, so it multiplies whichever analytic transmittance the caller took.
glm::vec3 vdbLayerBlend(const ShadowVolume& sv, const shd::FrameUniforms& frame, int light, const shd::ShadowLookup& k) {
    if (frame.vdbShadowSamples <= 0) return glm::vec3(1.0f);
    return shd::vdbShadowTransmittance(blendShadowCells(sv, shd::vdbShadowLayer(light, frame.counts.w), k).transmittance);
}

}  // namespace

ShadowVolume computeShadowVolume(const CompiledScene& cs, const shd::FrameUniforms& frame, int reduction,
                                 int threads, const std::vector<int>* layers, const std::vector<FroxelRegion>* cells) {
    ShadowVolume sv;
    sv.reduction = reduction;
    const glm::ivec3 froxelDims = glm::ivec3(frame.froxelDims);
    sv.dims = shd::shadowVolumeDims(froxelDims, reduction);
    const int lights = static_cast<int>(cs.lights.size());
    // With vdb shadows on (frame.vdbShadowSamples), a second layer per light after the analytic ones.
    const size_t layerCount = cs.lights.size() * (frame.vdbShadowSamples > 0 ? 2 : 1);
    sv.transmittance.assign(static_cast<size_t>(sv.dims.x * sv.dims.y * sv.dims.z) * layerCount,
                            glm::vec4(1.0f, 1.0f, 1.0f, 0.0f));
    // Each light's cells, and the box around them all.
    const FroxelRegion whole{glm::ivec3(0), sv.dims};
    auto cellsOf = [&](int light) { return cells ? (*cells)[static_cast<size_t>(light)] : whole; };
    FroxelRegion region;
    for (int i = 0; i < lights; ++i) region = regionUnion(region, cellsOf(i));
    if (region.empty()) return sv;
    const glm::ivec3 extent = region.hi - region.lo;
    // One row of cells (light, z, y) of the box per item, the light's own cells of it computed.
    parallelFor(lights * extent.z * extent.y, threads, [&](int r) {
        const int y = region.lo.y + r % extent.y, z = region.lo.z + (r / extent.y) % extent.z;
        const int light = r / (extent.y * extent.z);
        const shd::LightData& l = cs.lights[static_cast<size_t>(light)];
        if (!shd::fogShadowsLight(l, frame.localFogShadows)) return;
        if (layers && (*layers)[static_cast<size_t>(light)] == 0) return;
        const FroxelRegion own = cellsOf(light);
        if (y < own.lo.y || y >= own.hi.y || z < own.lo.z || z >= own.hi.z) return;
        for (int x = own.lo.x; x < own.hi.x; ++x) {
            const glm::ivec3 froxel = shd::shadowCellFroxel(glm::ivec3(x, y, z), froxelDims, reduction);
            const glm::vec3 p = shd::worldFromFroxelCoord(glm::vec3(froxel) + glm::vec3(frame.jitter), frame);
            const shd::LightSample ls = shd::evalLight(l, p);
            const glm::vec3 t = lightFogTransmittance(cs, l, p, ls.toLight, ls.distance, frame.localFogShadows);
            sv.transmittance[shadowIndex(sv.dims, light, glm::ivec3(x, y, z))] = glm::vec4(t, 0.0f);
            if (frame.vdbShadowSamples <= 0) continue;
            const glm::vec3 tau = vdbFogOpticalDepth(cs, frame, l, p, ls.toLight, ls.distance);
            sv.transmittance[shadowIndex(sv.dims, shd::vdbShadowLayer(light, lights), glm::ivec3(x, y, z))] =
                glm::vec4(tau, 0.0f);
        }
    });
    return sv;
}

glm::vec3 froxelFogTransmittance(const CompiledScene& cs, const ShadowVolume& sv, const shd::FrameUniforms& frame,
                                 int light, const shd::ShadowLookup& k, glm::vec3 p, glm::vec3 toLight,
                                 float distance) {
    const shd::LightData& l = cs.lights[static_cast<size_t>(light)];
    if (!shd::fogShadowsLight(l, frame.localFogShadows)) return glm::vec3(1.0f);
    const glm::vec3 vdb = vdbLayerBlend(sv, frame, light, k);
    const shd::ShadowBlend b = blendShadowCells(sv, light, k);
    if (b.trusted) return b.transmittance * vdb;
    return lightFogTransmittance(cs, l, p, toLight, distance, frame.localFogShadows) * vdb;
}

glm::vec3 surfaceFogTransmittance(const CompiledScene& cs, const ShadowVolume& sv, const shd::FrameUniforms& frame,
                                  int light, glm::vec3 p, glm::vec3 toLight, float distance) {
    const shd::LightData& l = cs.lights[static_cast<size_t>(light)];
    if (!shd::fogShadowsLight(l, frame.localFogShadows)) return glm::vec3(1.0f);
    const shd::SurfaceShadowLookup s = shd::shadowLookupAt(glm::vec3(shd::froxelCoordFromWorld(p, frame)), frame, sv.reduction);
    // The vdb layer at the clamped lookup even outside the grid's sample points (the image borders'
    // half froxel, past the froxel far): there is no exact form to fall back on.
    const glm::vec3 vdb = vdbLayerBlend(sv, frame, light, s.k);
    return lightFogTransmittance(cs, l, p, toLight, distance, frame.localFogShadows) * vdb;
}

}  // namespace brume
