// The CPU froxel renderer (Hillaire 2015): the GPU passes' oracle. Five passes, each a loop over
// independent items writing only its own outputs, so any thread count gives the same bits:
//   voxelize   froxel (x, y, s) -> mediaScatteringG, mediaExtinction, mediaEmission
//   light      froxel           -> source (sigma_t = 0 froxels skip lighting: S = emission)
//   temporal   froxel           -> source, mediaExtinction blended with the history (core/temporal.cpp)
//   integrate  column (x, y)    -> integratedScattering, integratedTransmittance (front to back)
//   composite  pixel            -> image (surface or sky behind the fog read from the integrated volume)
// Every formula comes from shaders/shared/, which the GPU passes include too.
#include <atomic>
#include <cmath>
#include <mutex>

#include "clusters.h"
#include "debug_view.h"
#include "froxel_frame.h"
#include "geometry.h"
#include "light_reach.h"
#include "local_shadow.h"
#include "parallel.h"
#include "progress.h"
#include "render.h"
#include "shadows.h"
#include "sun_shadow.h"
#include "vdb_shadow.h"
#include "shaders/shared/distant_table.h"

namespace brume {
namespace {

using glm::ivec3;
using glm::vec2;
using glm::vec3;
using glm::vec4;

size_t froxelIndex(ivec3 dims, int x, int y, int s) {
    return (static_cast<size_t>(s) * static_cast<size_t>(dims.y) + static_cast<size_t>(y)) *
               static_cast<size_t>(dims.x) +
           static_cast<size_t>(x);
}

// Pass 1. One row of froxels (y, s) per item: the media at each froxel's sample point.
void voxelizeRow(const CompiledScene& cs, FroxelVolumes& v, int y, int s) {
    for (int x = 0; x < v.dims.x; ++x) {
        const vec3 coord = vec3(static_cast<float>(x), static_cast<float>(y), static_cast<float>(s));
        const vec3 p = shd::worldFromFroxelCoord(coord + vec3(v.frame.jitter), v.frame);
        const shd::MediaSample m = mediaAt(cs, p);
        const size_t i = froxelIndex(v.dims, x, y, s);
        v.mediaScatteringG[i] = vec4(m.sigmaS, shd::mediaPhaseG(m));
        v.mediaExtinction[i] = vec4(m.sigmaT, 0.0f);
        v.mediaEmission[i] = vec4(m.emission, 0.0f);
    }
}

// Pass 2. Source term S = sigma_s (sum of lights' in-scattering x fog transmittance toward the
// light x the sun's and the point/spot shadow maps' visibility + ambient) + emission, over the lights of the froxel's
// cluster. Returns how many froxels of the row were lit.
size_t lightRow(const CompiledScene& cs, const ShadowVolume& sv, const LightClusters& clusters, const SunShadowMap& sun,
                const LocalShadowMaps& local, FroxelVolumes& v, int y, int s) {
    size_t lit = 0;
    for (int x = 0; x < v.dims.x; ++x) {
        const size_t i = froxelIndex(v.dims, x, y, s);
        const vec3 sigmaT = vec3(v.mediaExtinction[i]);
        // Nothing scatters where nothing extinguishes, but a purely emissive medium still glows.
        if (sigmaT == vec3(0.0f)) {
            v.source[i] = vec4(vec3(v.mediaEmission[i]), 0.0f);
            continue;
        }
        ++lit;
        const vec3 coord = vec3(static_cast<float>(x), static_cast<float>(y), static_cast<float>(s));
        const vec3 p = shd::worldFromFroxelCoord(coord + vec3(v.frame.jitter), v.frame);
        const vec3 viewDir = glm::normalize(p - vec3(v.frame.cameraPosition));
        const float g = v.mediaScatteringG[i].w;
        vec3 perSigmaS = vec3(v.frame.ambient);
        const shd::ShadowLookup shadow = shd::shadowLookup(ivec3(x, y, s), v.dims, sv.reduction);
        const float nearest = shd::FROXEL_LIGHT_CLAMP * shd::froxelRadius(s, v.frame);
        // Only the lights of this froxel's cluster (core/clusters.h), in the GPU's order.
        const int* cluster = &clusters.records[static_cast<size_t>(shd::clusterRecord(ivec3(x, y, s), v.dims))];
        const bool all = cluster[0] == shd::CLUSTER_ALL_LIGHTS;
        const size_t count = all ? cs.lights.size() : static_cast<size_t>(cluster[0]);
        for (size_t k = 0; k < count; ++k) {
            const size_t li = all ? k : static_cast<size_t>(cluster[1 + k]);
            const shd::LightData& l = cs.lights[li];
            const shd::LightSample ls = shd::evalLightFroxel(l, p, nearest, v.frame);
            const vec3 inScatter = shd::inScatterPerSigmaS(l, ls, viewDir, g);
            // Outside the range window or the cone, or fog_scale 0: the shadow cannot matter.
            if (inScatter == vec3(0.0f)) continue;
            perSigmaS += inScatter * froxelFogTransmittance(cs, sv, v.frame, static_cast<int>(li), shadow, p,
                                                            ls.toLight, ls.distance) *
                         sunShadowFroxelVisibility(sun, v.frame, static_cast<int>(li), p) *
                         localShadowVisibility(local, l, p);
        }
        const vec3 sourceRgb = vec3(v.mediaScatteringG[i]) * perSigmaS + vec3(v.mediaEmission[i]);
        v.source[i] = vec4(sourceRgb, 0.0f);
    }
    return lit;
}

// Pass 3. Front to back along one column; entry s holds camera -> far boundary of slice s.
void integrateColumn(FroxelVolumes& v, int x, int y) {
    const float tile = static_cast<float>(v.frame.froxelDims.w);
    const vec2 pixel = (vec2(static_cast<float>(x), static_cast<float>(y)) + vec2(0.5f)) * tile;
    shd::Accumulated acc = shd::emptyAccumulated();
    for (int s = 0; s < v.dims.z; ++s) {
        const size_t i = froxelIndex(v.dims, x, y, s);
        const float d = shd::sliceRayLength(s, pixel, v.frame);
        acc = shd::accumulateSlab(acc, vec3(v.source[i]), vec3(v.mediaExtinction[i]), d);
        v.integratedScattering[i] = vec4(acc.scattering, 0.0f);
        v.integratedTransmittance[i] = vec4(acc.transmittance, 0.0f);
    }
}

shd::Accumulated integratedAt(const FroxelVolumes& v, int x, int y, int s) {
    const size_t i = froxelIndex(v.dims, x, y, s);
    shd::Accumulated a;
    a.scattering = vec3(v.integratedScattering[i]);
    a.transmittance = vec3(v.integratedTransmittance[i]);
    return a;
}

// Step 1 of the lookup rule: entry s blended between lookup k's four columns.
shd::Accumulated integratedEntry(const FroxelVolumes& v, const shd::IntegratedLookup& k, int s) {
    const shd::Accumulated row0 = shd::mixAccumulated(integratedAt(v, k.columns.x, k.columns.y, s),
                                                      integratedAt(v, k.columns.z, k.columns.y, s), k.weights.x);
    const shd::Accumulated row1 = shd::mixAccumulated(integratedAt(v, k.columns.x, k.columns.w, s),
                                                      integratedAt(v, k.columns.z, k.columns.w, s), k.weights.x);
    return shd::mixAccumulated(row0, row1, k.weights.y);
}

// The composite's lookup rule, in the order written beside shd::integratedLookup.
shd::Accumulated sampleIntegrated(const FroxelVolumes& v, vec2 pixel, float viewDepth) {
    const shd::IntegratedLookup k = shd::integratedLookup(pixel, viewDepth, v.frame);
    const shd::Accumulated entries =
        shd::mixAccumulated(integratedEntry(v, k, k.entries.x), integratedEntry(v, k, k.entries.y), k.weights.z);
    return shd::mixAccumulated(shd::emptyAccumulated(), entries, k.entryWeight);
}

// The distant fog table (shaders/shared/distant_table.h; GPU: distant_fog.comp): per tile corner,
// entries 1..n, each the fog accumulated from the froxel far to that entry's view depth.
struct DistantTable {
    glm::ivec2 corners{0};
    int entries = 0;  // 0: no distant fog (no height or depth fog, or the froxels reach the camera far)
    std::vector<shd::Accumulated> values;  // [(corner row * corners.x + column) * n + j - 1]

    shd::Accumulated at(int x, int y, int j) const {
        if (j <= 0) return shd::emptyAccumulated();
        return values[static_cast<size_t>((y * corners.x + x) * entries + j - 1)];
    }
    // Entry j at the 4 corners c (x0, y0, x1, y1) around a pixel, blended bilinearly (w).
    shd::Accumulated entryAt(glm::ivec4 c, vec2 w, int j) const {
        const shd::Accumulated row0 = shd::mixAccumulated(at(c.x, c.y, j), at(c.z, c.y, j), w.x);
        const shd::Accumulated row1 = shd::mixAccumulated(at(c.x, c.w, j), at(c.z, c.w, j), w.x);
        return shd::mixAccumulated(row0, row1, w.y);
    }
};

DistantTable buildDistantTable(const CompiledScene& cs, const shd::FrameUniforms& frame, int threads) {
    DistantTable t;
    t.corners = shd::distantTableCorners(glm::ivec2(frame.counts));
    // A table only where height or depth fog goes on past the froxel far, as the GPU's (without, every
    // entry would be the empty fog, and a sky pixel is looked up like the others).
    t.entries = distantFogEntries(cs, frame);
    if (t.entries == 0) return t;
    const int n = t.entries;
    t.values.assign(static_cast<size_t>(t.corners.x * t.corners.y * n), shd::emptyAccumulated());
    parallelFor(t.corners.y, threads, [&](int y) {
        for (int x = 0; x < t.corners.x; ++x) {
            const vec3 viewRay = shd::viewRayFromPixel(vec2(glm::ivec2(x, y) * shd::DISTANT_TILE_PX), frame);
            const float rayPerDepth = glm::length(viewRay);
            const vec3 dir = glm::normalize(vec3(frame.worldFromView * vec4(viewRay, 0.0f)));
            shd::Accumulated a = shd::emptyAccumulated();
            for (int j = 1; j <= n; ++j) {
                a = accumulateDistantPiece(cs, a, dir, shd::distantTableDepth(frame, j - 1, n) * rayPerDepth,
                                           shd::distantTableDepth(frame, j, n) * rayPerDepth);
                t.values[static_cast<size_t>((y * t.corners.x + x) * n + j - 1)] = a;
            }
        }
    });
    return t;
}

// A sky pixel's fog (composite_body.glsl skyFogAt): the integrated volume's last entry, then the table's.
shd::Accumulated skyFogAt(const FroxelVolumes& v, const DistantTable& t, vec2 pixel) {
    const shd::IntegratedLookup k = shd::integratedLookupAtLastEntry(pixel, v.frame);
    const shd::DistantCorners c = shd::distantCornersAround(pixel);
    return shd::composeAccumulated(integratedEntry(v, k, k.entries.y), t.entryAt(c.corners, c.weights, t.entries));
}

// The fog from the froxel far to viewDepth (> the froxel far) at a pixel, as composite.comp reads it.
shd::Accumulated distantFogAt(const DistantTable& t, const shd::FrameUniforms& frame, vec2 pixel, float viewDepth) {
    const shd::DistantTableLookup k = shd::distantTableLookup(pixel, viewDepth, frame, t.entries);
    return shd::distantTableBlend(t.entryAt(k.corners, k.weights, k.entry - 1), t.entryAt(k.corners, k.weights, k.entry),
                                  k.blend);
}

// The per-pixel part of the point and spot lights' glow (shaders/shared/glow.h; GPU: glow.comp), added
// to the composited colour light by light, in the order the GPU's glow pass adds them. Only the
// lights the light reach lists as glowing, as on the GPU.
vec3 addLightGlow(vec3 color, const CompiledScene& cs, const std::vector<int>& glowLights, const FroxelVolumes& v,
                  vec2 pixel, vec3 dir, float rayPerDepth, float viewDepth) {
    const vec3 origin = vec3(v.frame.cameraPosition);
    for (int index : glowLights) {
        const shd::LightData& l = cs.lights[static_cast<size_t>(index)];
        const shd::LightGlowRay r = shd::lightGlowRay(l, v.frame, origin, dir, viewDepth * rayPerDepth);
        if (r.radius <= 0.0f) continue;
        const ivec3 m = shd::lightGlowFroxel(r, origin, dir, v.frame);
        const size_t i = froxelIndex(v.dims, m.x, m.y, m.z);
        const vec4 scatteringG = v.mediaScatteringG[i];
        const vec3 toEnter = sampleIntegrated(v, pixel, r.enter / rayPerDepth).transmittance;
        color += toEnter * vec3(scatteringG) *
                 shd::lightGlowPerSigmaS(l, r, origin, dir, vec3(v.mediaExtinction[i]), scatteringG.w);
    }
    return color;
}

// Pass 4. One image row: the first surface hit (or the sky) behind the fog.
void compositeRow(const CompiledScene& cs, const GeometrySet& geometry, const ShadowVolume& sv, const SunShadowMap& sun,
                  const LocalShadowMaps& local, const FroxelVolumes& v, const DistantTable& distant,
                  const std::vector<int>& glowLights, Image& img, int y) {
    const float cameraFar = v.frame.projection.w;
    for (int x = 0; x < img.width; ++x) {
        const vec2 pixel = vec2(static_cast<float>(x), static_cast<float>(y)) + vec2(0.5f);
        // viewRay has z = -1, so distance along it / its length is the view depth.
        const vec3 viewRay = shd::viewRayFromPixel(pixel, v.frame);
        const float rayPerDepth = glm::length(viewRay);
        const vec3 dir = glm::normalize(vec3(v.frame.worldFromView * vec4(viewRay, 0.0f)));
        const SurfaceHit hit = geometry.intersect(Ray{vec3(v.frame.cameraPosition), dir}, cameraFar * rayPerDepth);
        vec3 background = cs.ambient;
        float viewDepth = cameraFar;
        if (hit.hit()) {
            // The fog's shadow and the shadow maps' (sun, point, spot) on the surface, as the GPU's geometry pass
            // computes them; exact geometry occlusion stays off so that both renderers agree.
            const LightTransmittanceFn fogShadow = [&](int i, vec3 from, vec3 toLight, float dist) {
                return surfaceFogTransmittance(cs, sv, v.frame, i, from, toLight, dist) *
                       sunShadowVisibility(sun, v.frame, i, from) *
                       localShadowVisibility(local, cs.lights[static_cast<size_t>(i)], from);
            };
            background = shadeSurface(cs, geometry, hit, &fogShadow, /*geometryShadows=*/false);
            viewDepth = hit.t / rayPerDepth;
        }
        // Past the froxel range, height and depth fog continue in closed form (shaders/shared/distant.h);
        // a sky pixel takes the last entries alone (composite_body.glsl skyFogAt).
        const bool distantFog = distant.entries > 0 && viewDepth > v.frame.froxelRange.y;
        shd::Accumulated fog;
        if (distantFog && shd::isSkyDepth(viewDepth, v.frame)) {
            fog = skyFogAt(v, distant, pixel);
        } else {
            fog = sampleIntegrated(v, pixel, viewDepth);
            if (distantFog) fog = shd::composeAccumulated(fog, distantFogAt(distant, v.frame, pixel, viewDepth));
        }
        img.at(x, y) = addLightGlow(shd::compositeFog(background, fog), cs, glowLights, v, pixel, dir, rayPerDepth,
                                    viewDepth);
    }
}

FroxelVolumes allocateVolumes(const shd::FrameUniforms& frame) {
    FroxelVolumes v;
    v.frame = frame;
    v.dims = ivec3(frame.froxelDims);
    const size_t n = static_cast<size_t>(v.dims.x) * static_cast<size_t>(v.dims.y) * static_cast<size_t>(v.dims.z);
    for (std::vector<vec4>* vol : {&v.mediaScatteringG, &v.mediaExtinction, &v.mediaEmission, &v.source,
                                   &v.integratedScattering, &v.integratedTransmittance}) {
        vol->assign(n, vec4(0.0f));
    }
    return v;
}

}  // namespace

FroxelResult renderFroxelFrameCpu(const Scene& scene, const RenderRequest& request, CpuHistory& history) {
    FroxelResult result;
    if (request.width < 1 || request.height < 1) return result;
    CompiledScene cs = compileScene(scene);
    applyVdbCullingSettings(cs, request);
    const FroxelSettings fs = resolveFroxelSettings(scene, request.quality);
    const uint64_t sceneKey = temporalSceneKey(cs, scene, froxelGridDims(request.width, request.height, fs));
    const TemporalFrame t = beginTemporalFrame(history.state, scene, sceneKey, request.history);
    FroxelVolumes& v = result.volumes;
    shd::FrameUniforms frame = makeFrameUniforms(scene, cs, request.width, request.height, fs, t.jitter);
    applyShadowSettings(frame, request);
    applySunShadowSettings(frame, cs);
    applyVdbShadowSettings(frame, cs, request);
    setTemporalBlend(frame, history.state, t);
    v = allocateVolumes(frame);
    result.image = Image(request.width, request.height);

    const int rows = v.dims.y * v.dims.z;  // froxel rows (y, s): the voxelize and light work items
    const int columns = v.dims.x * v.dims.y;
    const int threads = request.threads;
    ProgressReporter progress(request.progress, 2.0 * rows + columns + request.height);
    auto report = [&](int done) { progress.report(done); };

    parallelFor(rows, threads, [&](int r) { voxelizeRow(cs, v, r % v.dims.y, r / v.dims.y); }, report);
    progress.finishedPass(rows);

    const LightClusters clusters = buildLightClusters(cs, frame, request.lightCulling);
    // Layers of lights that touch nothing shaded are skipped: nobody reads them.
    const LightReach reach = buildLightReach(cs, frame, clusters, request.lightCulling);
    // Only the cells the light pass's froxels (those with media whose clusters list the light) and the
    // surfaces read, as on the GPU.
    const std::vector<FroxelRegion> listed =
        listedFroxelRegions(clusters, cs.lights.size(), mediaFroxelRegion(cs, frame));
    std::vector<FroxelRegion> shadowCells;
    for (const FroxelRegion& froxels : listed)
        shadowCells.push_back(shadowCellRegion(froxels, frame, /*surfaces=*/!scene.geometry.empty()));
    const ShadowVolume shadow =
        computeShadowVolume(cs, frame, frame.shadowReduction, threads, &reach.shadowVolume, &shadowCells);
    v.overfullClusters = clusters.overfullClusters;
    const GeometrySet geometry(scene.geometry);
    const SunShadowMap& sun =
        history.sunShadow.get(cs, scene.geometry, frame, sunShadowMapResolution(request.quality), threads);
    const LocalShadowMaps& local = history.localShadows.get(cs, scene.geometry, frame.localShadowTexels, threads);

    // Per-row counts summed afterwards keep the totals independent of scheduling.
    std::vector<size_t> litPerRow(static_cast<size_t>(rows), 0);
    parallelFor(rows, threads,
                [&](int r) {
                    litPerRow[static_cast<size_t>(r)] =
                        lightRow(cs, shadow, clusters, sun, local, v, r % v.dims.y, r / v.dims.y);
                },
                report);
    progress.finishedPass(rows);
    for (size_t lit : litPerRow) v.litFroxels += lit;
    v.skippedFroxels = v.source.size() - v.litFroxels;

    temporalPassCpu(v, history, t, threads);
    endTemporalFrame(history.state, t, v.frame, sceneKey);

    parallelFor(columns, threads, [&](int c) { integrateColumn(v, c % v.dims.x, c / v.dims.x); }, report);
    progress.finishedPass(columns);

    const DistantTable distant = buildDistantTable(cs, v.frame, threads);
    parallelFor(request.height, threads,
                [&](int y) { compositeRow(cs, geometry, shadow, sun, local, v, distant, reach.glowLights, result.image, y); }, report);
    if (request.debugView != shd::DEBUG_VIEW_FINAL)
        result.image = debugViewImage(v, request.debugView, request.debugSlice);
    return result;
}

}  // namespace brume
