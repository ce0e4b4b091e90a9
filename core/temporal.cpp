// Temporal bookkeeping (core/temporal.h), the CPU temporal pass and the multi-frame CPU renderer.
// The pass mirrors shaders/temporal.comp: both evaluate shaders/shared/temporal.h, whose header
// comment holds the reprojection rule.
#include "temporal.h"

#include <algorithm>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include "froxel_frame.h"
#include "parallel.h"

namespace brume {
namespace {

using glm::ivec3;
using glm::vec4;

uint64_t fnv1a(uint64_t h, const void* data, size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

size_t indexOf(ivec3 dims, ivec3 c) {
    return (static_cast<size_t>(c.z) * static_cast<size_t>(dims.y) + static_cast<size_t>(c.y)) *
               static_cast<size_t>(dims.x) +
           static_cast<size_t>(c.x);
}

shd::HistorySample readTrilinear(const std::vector<vec4>& vol, ivec3 dims, const shd::HistoryTaps& k) {
    shd::HistorySample h = shd::emptyHistorySample();
    for (int corner = 0; corner < 8; ++corner) {
        const ivec3 c(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
        const ivec3 at(c.x ? k.hi.x : k.lo.x, c.y ? k.hi.y : k.lo.y, c.z ? k.hi.z : k.lo.z);
        h = shd::addHistoryTap(h, vol[indexOf(dims, at)], c, k.fractions);
    }
    return h;
}

// The froxel and its six face neighbours that lie inside the grid.
shd::Bounds neighbourhood(const std::vector<vec4>& vol, ivec3 dims, ivec3 c) {
    static constexpr ivec3 kOffsets[7] = {{0, 0, 0}, {-1, 0, 0}, {1, 0, 0}, {0, -1, 0},
                                          {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
    shd::Bounds b = shd::emptyBounds();
    for (const ivec3& o : kOffsets) {
        const ivec3 n = c + o;
        if (glm::any(glm::lessThan(n, ivec3(0))) || glm::any(glm::greaterThanEqual(n, dims))) continue;
        b = shd::growBounds(b, vol[indexOf(dims, n)]);
    }
    return b;
}

void resolveRow(FroxelVolumes& v, const HistoryVolume& in, HistoryVolume& out, const TemporalState& state, int y,
                int s) {
    const ivec3 prevDims(state.frame.froxelDims);
    const float weight = v.frame.temporal.x;
    for (int x = 0; x < v.dims.x; ++x) {
        const ivec3 c(x, y, s);
        const size_t i = indexOf(v.dims, c);
        if (shd::temporalAtRest(v.frame.temporal)) {
            // The view rests (the same grid as the history's) or there is no history to read.
            const bool read = weight > 0.0f;
            out.source[i] = shd::resolveTemporalAtRest(v.source[i], read ? in.source[i] : vec4(0.0f), weight);
            out.extinction[i] =
                shd::resolveTemporalAtRest(v.mediaExtinction[i], read ? in.extinction[i] : vec4(0.0f), weight);
            continue;
        }
        const shd::HistoryTaps k = shd::historyTaps(c, v.frame, state.frame, v.frame.temporal.x);
        const bool clampHistory = v.frame.temporal.y == 0.0f;
        const bool read = k.weight > 0.0f;
        const shd::HistorySample histS = read ? readTrilinear(in.source, prevDims, k) : shd::emptyHistorySample();
        const shd::HistorySample histE = read ? readTrilinear(in.extinction, prevDims, k) : shd::emptyHistorySample();
        out.source[i] =
            shd::resolveTemporal(v.source[i], histS, neighbourhood(v.source, v.dims, c), k.weight, clampHistory);
        out.extinction[i] = shd::resolveTemporal(v.mediaExtinction[i], histE, neighbourhood(v.mediaExtinction, v.dims, c),
                                                 k.weight, clampHistory);
    }
}

}  // namespace

uint64_t temporalSceneKey(const CompiledScene& cs, const Scene& scene, glm::ivec3 dims) {
    uint64_t h = 14695981039346656037ull;
    h = fnv1a(h, cs.volumes.data(), cs.volumes.size() * sizeof(shd::VolumeData));
    h = fnv1a(h, cs.lights.data(), cs.lights.size() * sizeof(shd::LightData));
    h = fnv1a(h, &cs.ambient, sizeof(cs.ambient));
    // A moved influencer or a decayed wake is a changed medium, like a moved volume.
    h = fnv1a(h, cs.influence.samples.data(), cs.influence.samples.size() * sizeof(shd::InfluenceSample));
    h = fnv1a(h, &dims, sizeof(dims));
    // Geometry shadows the froxels (sun and point/spot shadow maps): a moved box moves its shadow.
    // Its colours do not reach the froxels, so recolouring keeps the history.
    for (const Geometry& g : scene.geometry) {
        if (g.hidden) continue;
        const float shape[17] = {static_cast<float>(g.type), g.height, g.transform.translation.x,
                                 g.transform.translation.y, g.transform.translation.z, g.transform.rotation_deg.x,
                                 g.transform.rotation_deg.y, g.transform.rotation_deg.z, g.transform.scale.x,
                                 g.transform.scale.y, g.transform.scale.z, g.center.x, g.center.y, g.center.z,
                                 g.radius, 0.0f, 0.0f};
        h = fnv1a(h, shape, sizeof(shape));
    }
    const float settings[2] = {scene.temporal.enabled ? 1.0f : 0.0f, scene.temporal.history_weight};
    return fnv1a(h, settings, sizeof(settings));
}

TemporalFrame beginTemporalFrame(TemporalState& state, const Scene& scene, uint64_t sceneKey, HistoryMode mode) {
    const bool enabled = scene.temporal.enabled;
    if (mode == HistoryMode::Restart || !enabled || state.sceneKey != sceneKey) {
        state.valid = false;
        state.frameIndex = 0;
    }
    TemporalFrame t;
    t.frameIndex = state.frameIndex;
    t.jitter = enabled ? shd::temporalJitter(t.frameIndex) : glm::vec3(0.5f);
    t.useHistory = enabled && state.valid;
    t.historyWeight = enabled ? scene.temporal.history_weight : 0.0f;
    t.readIndex = state.lastWritten;
    t.writeIndex = 1 - state.lastWritten;
    return t;
}

namespace {

bool sameBytes(const void* a, const void* b, size_t n) { return std::memcmp(a, b, n) == 0; }

// Whether `frame` sees the scene exactly as `prev` did (the jitter aside): the same froxels at the
// same places and the same scene time, so that the history is the same quantity's mean.
bool viewRests(const shd::FrameUniforms& frame, const shd::FrameUniforms& prev) {
    return sameBytes(&frame.viewFromWorld, &prev.viewFromWorld, sizeof(frame.viewFromWorld)) &&
           sameBytes(&frame.clipFromView, &prev.clipFromView, sizeof(frame.clipFromView)) &&
           sameBytes(&frame.projection, &prev.projection, sizeof(frame.projection)) &&
           sameBytes(&frame.froxelRange, &prev.froxelRange, sizeof(frame.froxelRange)) &&
           sameBytes(&frame.froxelDims, &prev.froxelDims, sizeof(frame.froxelDims)) &&
           frame.ambient.w == prev.ambient.w;
}

}  // namespace

void setTemporalBlend(shd::FrameUniforms& frame, const TemporalState& state, const TemporalFrame& t) {
    frame.temporal = glm::vec4(0.0f);
    if (!t.useHistory || t.historyWeight <= 0.0f) return;
    const bool rests = viewRests(frame, state.frame);
    frame.temporal.x = rests ? shd::temporalRestWeight(state.restFrames, t.historyWeight) : t.historyWeight;
    frame.temporal.y = rests ? 1.0f : 0.0f;
}

void endTemporalFrame(TemporalState& state, const TemporalFrame& t, const shd::FrameUniforms& frame,
                      uint64_t sceneKey) {
    // A moved view's history counts as one sample of the new view: the progressive mean restarts.
    state.restFrames = frame.temporal.y != 0.0f ? state.restFrames + 1 : 1;
    state.lastWritten = t.writeIndex;
    state.valid = true;
    state.frame = frame;
    state.sceneKey = sceneKey;
    state.frameIndex = t.frameIndex + 1;
}

Camera orbitCamera(const Camera& camera, float degrees) {
    Camera c = camera;
    const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), glm::radians(degrees), glm::normalize(camera.up));
    c.position = camera.target + glm::vec3(turn * glm::vec4(camera.position - camera.target, 0.0f));
    return c;
}

void temporalPassCpu(FroxelVolumes& v, CpuHistory& history, const TemporalFrame& t, int threads) {
    const HistoryVolume& in = history.pair[static_cast<size_t>(t.readIndex)];
    HistoryVolume& out = history.pair[static_cast<size_t>(t.writeIndex)];
    out.source.resize(v.source.size());
    out.extinction.resize(v.source.size());
    parallelFor(v.dims.y * v.dims.z, threads,
                [&](int r) { resolveRow(v, in, out, history.state, r % v.dims.y, r / v.dims.y); });
    // The integrate pass reads the resolved values.
    v.source = out.source;
    v.mediaExtinction = out.extinction;
}

FroxelResult FroxelCpuRenderer::render(const Scene& scene, const RenderRequest& request) {
    RenderRequest frame = request;
    const int frames = std::max(request.frames, 1);
    FroxelResult result;
    for (int n = 0; n < frames; ++n) {
        // Frame n covers [n, n + 1) / frames of the sequence, so progress never goes back.
        if (request.progress) {
            frame.progress = [&request, n, frames](float f) {
                request.progress((static_cast<float>(n) + f) / static_cast<float>(frames));
            };
        }
        result = renderFroxelFrameCpu(scene, frame, history_);
        frame.history = HistoryMode::Continue;
    }
    return result;
}

FroxelResult renderFroxelCpu(const Scene& scene, const RenderRequest& request) {
    FroxelCpuRenderer renderer;
    RenderRequest r = request;
    r.history = HistoryMode::Restart;
    return renderer.render(scene, r);
}

}  // namespace brume
