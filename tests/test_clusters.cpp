// Clustered light culling (core/clusters.h): the lists are exact enough to change nothing (every
// light that lights a froxel is in its cluster's list), tight (lights that cannot reach a cluster
// are absent), and the CPU froxel renderer's image is the unculled one.
#include <gtest/gtest.h>

#include "test_support.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/clusters.h"
#include "core/render.h"

using namespace brume;
using glm::ivec3;
using glm::vec3;

namespace {

constexpr int kWidth = 160;
constexpr int kHeight = 90;

Light point(vec3 p, float range) { return test::pointLight(p, range, 20.0f); }

Light spot(vec3 p, vec3 dir, float outerDeg, float range) {
    Light l = makeLight(LightType::Spot);
    l.position = p;
    l.direction = glm::normalize(dir);
    l.outer_deg = outerDeg;
    l.inner_deg = outerDeg * 0.5f;
    l.range = range;
    l.intensity = 40.0f;
    return l;
}

// Camera at z = 6 looking toward -z; fog everywhere below 3 m and a box; lights of every kind,
// some that reach the fog and some that cannot.
Scene clusterScene() {
    Scene s = test::heightFogView(30.0f, 0.5f, {0.2f, 0.2f, 0.25f});
    Light sun = makeLight(LightType::Directional);
    sun.direction = glm::normalize(vec3(0.3f, -1.0f, -0.4f));
    sun.shadows = false;
    s.lights = {sun,
                point({-2.0f, 0.5f, 0.0f}, 1.5f),
                point({2.5f, 1.0f, -4.0f}, 3.0f),
                point({0.0f, 0.2f, 3.0f}, 1.0f),
                point({0.0f, 1.0f, 14.0f}, 2.0f),    // behind the camera, out of reach of the froxels
                point({60.0f, 1.0f, -5.0f}, 4.0f),   // far to the side
                spot({1.0f, 3.0f, -1.0f}, {0.0f, -1.0f, 0.0f}, 20.0f, 6.0f),
                spot({-1.0f, 1.0f, -8.0f}, {-1.0f, 0.0f, 0.2f}, 15.0f, 0.0f),  // no range: the cone alone
                point({0.5f, 0.5f, -1.0f}, 3.0f),
                point({1.0f, 1.0f, -2.0f}, 3.0f)};
    s.lights[8].fog_scale = 0.0f;   // lights surfaces only
    s.lights[9].intensity = 0.0f;   // dark
    return s;
}

shd::FrameUniforms frameOf(const Scene& s, const CompiledScene& cs) {
    return makeFrameUniforms(s, cs, kWidth, kHeight, resolveFroxelSettings(s, Quality::High));
}

bool listed(const LightClusters& c, ivec3 froxel, ivec3 dims, int light) {
    const int* r = &c.records[static_cast<size_t>(shd::clusterRecord(froxel, dims))];
    if (r[0] == shd::CLUSTER_ALL_LIGHTS) return true;
    return std::find(r + 1, r + 1 + r[0], light) != r + 1 + r[0];
}

// The CPU froxel renderer's S and image with the clusters and with every light in every cluster:
// culled lights contribute exactly 0 and the loop order is kept, so the same bits.
void expectCulledEqualsUnculled(const Scene& s) {
    RenderRequest r;
    r.width = kWidth;
    r.height = kHeight;
    r.threads = 2;
    const FroxelResult culled = renderFroxelCpu(s, r);
    r.lightCulling = false;
    const FroxelResult all = renderFroxelCpu(s, r);
    EXPECT_EQ(culled.volumes.source, all.volumes.source);
    EXPECT_EQ(culled.image.pixels, all.image.pixels);
}

// Lights that light each froxel at any of these sample positions (the jitter's extremes and centre).
constexpr float kJitters[] = {0.0f, 0.5f, 0.999f};

}  // namespace

TEST(LightClusters, ListEveryLightThatLightsAFroxel) {
    const Scene s = clusterScene();
    const CompiledScene cs = compileScene(s);
    const shd::FrameUniforms frame = frameOf(s, cs);
    const ivec3 dims(frame.froxelDims);
    const LightClusters c = buildLightClusters(cs, frame);
    EXPECT_EQ(c.overfullClusters, 0u);
    std::vector<size_t> litSamples(cs.lights.size(), 0);
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x)
                for (float j : kJitters) {
                    const vec3 p = shd::worldFromFroxelCoord(vec3(x, y, z) + vec3(j), frame);
                    const float nearest = shd::FROXEL_LIGHT_CLAMP * shd::froxelRadius(z, frame);
                    for (size_t li = 0; li < cs.lights.size(); ++li) {
                        const shd::LightSample ls = shd::evalLightNear(cs.lights[li], p, nearest);
                        const vec3 in = shd::inScatterPerSigmaS(cs.lights[li], ls, vec3(0.0f, 0.0f, -1.0f), 0.0f);
                        if (in == vec3(0.0f)) continue;
                        ++litSamples[li];
                        ASSERT_TRUE(listed(c, ivec3(x, y, z), dims, static_cast<int>(li)))
                            << "light " << li << " lights froxel " << x << "," << y << "," << z << " but is not listed";
                    }
                }
    // The scene exercises what it claims: every light meant to reach the fog does.
    for (size_t li : {0u, 1u, 2u, 3u, 6u, 7u}) EXPECT_GT(litSamples[li], 0u) << "light " << li;
}

TEST(LightClusters, LightsThatCannotReachAreAbsent) {
    const Scene s = clusterScene();
    const CompiledScene cs = compileScene(s);
    const shd::FrameUniforms frame = frameOf(s, cs);
    const ivec3 dims(frame.froxelDims);
    const LightClusters c = buildLightClusters(cs, frame);
    const int clusters = c.dims.x * c.dims.y * c.dims.z;
    std::vector<int> clustersListing(cs.lights.size(), 0);
    for (int i = 0; i < clusters; ++i) {
        const int* r = &c.records[static_cast<size_t>(i * shd::CLUSTER_STRIDE)];
        ASSERT_GE(r[0], 0);
        for (int k = 0; k < r[0]; ++k) ++clustersListing[static_cast<size_t>(r[1 + k])];
    }
    EXPECT_EQ(clustersListing[0], clusters) << "a directional light reaches every cluster";
    std::printf("[clusters] %d clusters; listed in:", clusters);
    for (int n : clustersListing) std::printf(" %d", n);
    std::printf("\n");
    for (size_t li : {4u, 5u, 8u, 9u}) EXPECT_EQ(clustersListing[li], 0) << "light " << li << " cannot reach the fog";
    // The spot's cone removes clusters its range sphere alone would reach.
    Scene asPoint = s;
    asPoint.lights[6].type = LightType::Point;
    const CompiledScene csPoint = compileScene(asPoint);
    const LightClusters sphereOnly = buildLightClusters(csPoint, frameOf(asPoint, csPoint));
    int sphereListing = 0;
    for (int i = 0; i < clusters; ++i) {
        const int* r = &sphereOnly.records[static_cast<size_t>(i * shd::CLUSTER_STRIDE)];
        sphereListing += static_cast<int>(std::count(r + 1, r + 1 + r[0], 6));
    }
    EXPECT_GT(clustersListing[6], 0);
    EXPECT_LT(clustersListing[6], sphereListing) << "the spot's cone culls nothing";
    // Short-range lights: listed only where a point of the cluster lies within range (up to the
    // spacing of a 9^3 grid of points over the cluster, measured here independently of the bounds).
    constexpr int kN = 9;
    for (size_t li : {1u, 2u, 3u}) {
        EXPECT_GT(clustersListing[li], 0) << "light " << li;
        EXPECT_LT(clustersListing[li], clusters / 3) << "light " << li;
        const vec3 light = s.lights[li].position;
        for (int cz = 0; cz < c.dims.z; ++cz)
            for (int cy = 0; cy < c.dims.y; ++cy)
                for (int cx = 0; cx < c.dims.x; ++cx) {
                    const ivec3 first = ivec3(cx, cy, cz) * shd::CLUSTER_FROXELS;
                    if (!listed(c, first, dims, static_cast<int>(li))) continue;
                    const vec3 lo(first), hi(glm::min(first + ivec3(shd::CLUSTER_FROXELS), dims));
                    float nearest = 1e30f, spacing = 0.0f;
                    for (int k = 0; k < kN * kN * kN; ++k) {
                        const vec3 t = vec3(k % kN, (k / kN) % kN, k / (kN * kN)) / float(kN - 1);
                        const vec3 p = shd::worldFromFroxelCoord(glm::mix(lo, hi, t), frame);
                        nearest = std::min(nearest, glm::length(p - light));
                        if (k % kN + 1 < kN) {
                            const float step = 1.0f / float(kN - 1);
                            const vec3 q = shd::worldFromFroxelCoord(glm::mix(lo, hi, t + vec3(step, 0, 0)), frame);
                            const vec3 u = shd::worldFromFroxelCoord(glm::mix(lo, hi, t + vec3(0, 0, step)), frame);
                            const vec3 w = shd::worldFromFroxelCoord(glm::mix(lo, hi, t + vec3(0, step, 0)), frame);
                            spacing = std::max({spacing, glm::length(q - p), glm::length(u - p), glm::length(w - p)});
                        }
                    }
                    EXPECT_LT(nearest, s.lights[li].range + 2.0f * spacing)
                        << "light " << li << " listed in cluster " << cx << "," << cy << "," << cz;
                }
    }
}

TEST(LightClusters, CulledImageEqualsUnculled) { expectCulledEqualsUnculled(clusterScene()); }

// A light whose range reaches froxels but no volume's bounds lights no froxel that has media: it is
// listed in no cluster (target 4's dark lights: one test per volume, not one per cluster), and the
// image keeps its bits.
TEST(LightClusters, LightsThatReachNoVolumeAreListedNowhere) {
    Scene s = clusterScene();
    s.volumes = {test::boxFog({0.0f, 1.0f, -3.0f}, {1.0f, 1.0f, 1.0f}, 0.2f, 0.5f, 0.02f)};
    s.lights = {point({-2.0f, 0.5f, 0.0f}, 1.5f),    // 2.9 m from the box: dark
                point({0.0f, 1.0f, -1.5f}, 2.0f)};  // reaches it
    const CompiledScene cs = compileScene(s);
    const LightClusters c = buildLightClusters(cs, frameOf(s, cs));
    auto listings = [](const LightClusters& lc, int light) {
        int n = 0;
        for (size_t i = 0; i < lc.records.size(); i += shd::CLUSTER_STRIDE) {
            const int* r = &lc.records[i];
            n += static_cast<int>(std::count(r + 1, r + 1 + r[0], light));
        }
        return n;
    };
    EXPECT_EQ(listings(c, 0), 0) << "a light that reaches no volume is listed";
    EXPECT_GT(listings(c, 1), 0);
    // With unbounded fog the same light reaches froxels that have media: listed, so the test above
    // measures the volumes' bounds, not a light outside the grid.
    Scene fogged = s;
    fogged.volumes = clusterScene().volumes;
    const CompiledScene csFogged = compileScene(fogged);
    EXPECT_GT(listings(buildLightClusters(csFogged, frameOf(fogged, csFogged)), 0), 0);
    expectCulledEqualsUnculled(s);
}

TEST(LightClusters, OverfullClustersLoopOverEveryLight) {
    Scene s = clusterScene();
    // More unbounded lights than a cluster lists: every cluster falls back to the full loop.
    for (int i = 0; i <= shd::CLUSTER_MAX_LIGHTS; ++i) {
        Light l = point({0.1f * static_cast<float>(i) - 3.0f, 1.0f, -2.0f}, 0.0f);
        l.intensity = 0.2f;
        s.lights.push_back(l);
    }
    const CompiledScene cs = compileScene(s);
    const LightClusters c = buildLightClusters(cs, frameOf(s, cs));
    EXPECT_EQ(c.overfullClusters, static_cast<size_t>(c.dims.x * c.dims.y * c.dims.z));
    RenderRequest r;
    r.width = 64;
    r.height = 36;
    r.threads = 2;
    const FroxelResult culled = renderFroxelCpu(s, r);
    EXPECT_GT(culled.volumes.overfullClusters, 0u);
    r.lightCulling = false;
    const FroxelResult all = renderFroxelCpu(s, r);
    EXPECT_EQ(culled.image.pixels, all.image.pixels);
}
