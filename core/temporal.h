// Temporal integration bookkeeping shared by the CPU froxel renderer and the GPU renderer: which
// jitter a frame uses, whether it may read the history, and when the history must be dropped.
// The blend itself is shaders/shared/temporal.h (rule and reasons written there); the CPU pass is
// core/temporal.cpp, the GPU pass gpu/pass_temporal.cpp + shaders/temporal.comp.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "compile.h"
#include "scene.h"
#include "local_shadow.h"
#include "sun_shadow.h"

namespace brume {

// How a render call treats the history left by the previous call of the same renderer.
enum class HistoryMode {
    Restart,   // drop it: the call's first frame starts fresh (jitter index 0 = froxel centres)
    Continue,  // blend with it, unless the scene key or the grid changed (then it is dropped anyway)
};

// Everything that, when edited, must drop the history so that no edit ever leaves a ghost: the
// compiled volumes, lights, ambient and influence samples, the shapes and places of the geometry (it shadows the
// froxels), the grid size and the temporal settings. The camera is not
// in it: camera motion is what reprojection handles. FNV-1a over the compiled records' bytes.
uint64_t temporalSceneKey(const CompiledScene& cs, const Scene& scene, glm::ivec3 dims);

// The history's bookkeeping; the history volumes themselves are an explicit ping-pong pair held
// by the renderer (CPU: CpuHistory::pair, GPU: FrameResources::history). Frame n reads the pair
// entry frame n-1 wrote (lastWritten) and writes the other one.
struct TemporalState {
    int lastWritten = 0;
    bool valid = false;           // the pair entry lastWritten holds a usable history
    shd::FrameUniforms frame{};   // the frame that wrote it (its view, projection and grid)
    uint64_t sceneKey = 0;
    int frameIndex = 0;           // jitter index of the next frame
    int restFrames = 0;           // frames the history has averaged since the view last moved
};

struct TemporalFrame {
    glm::vec3 jitter{0.5f};      // sample position inside each froxel
    bool useHistory = false;     // blend with the pair entry lastWritten
    float historyWeight = 0.0f;  // scene.temporal.history_weight (0 when temporal is off)
    int readIndex = 0;           // pair entry to read
    int writeIndex = 1;          // pair entry to write
    int frameIndex = 0;
};

// Before a frame: drops the history when asked (Restart), when temporal is off, or when the key
// changed, and picks the frame's jitter.
TemporalFrame beginTemporalFrame(TemporalState& state, const Scene& scene, uint64_t sceneKey, HistoryMode mode);
// Once the frame's uniforms are made: frame.temporal, the history weight and whether the view rests
// (the same view, projection, grid and scene time as the frame that wrote the history): then the
// weight makes the history a progressive mean (shd::temporalRestWeight), else it is t.historyWeight.
void setTemporalBlend(shd::FrameUniforms& frame, const TemporalState& state, const TemporalFrame& t);
// After a frame: what it wrote becomes the history of the next.
void endTemporalFrame(TemporalState& state, const TemporalFrame& t, const shd::FrameUniforms& frame,
                      uint64_t sceneKey);

// The camera path of `brume render --orbit`: the position turned by `degrees` about the axis
// through the target along camera.up (right-handed: positive turns counter-clockwise seen from above).
Camera orbitCamera(const Camera& camera, float degrees);

struct HistoryVolume {
    std::vector<glm::vec4> source;      // resolved rgb S
    std::vector<glm::vec4> extinction;  // resolved rgb sigma_t
};

// What the CPU froxel renderer keeps from frame to frame: the temporal history, and the sun shadow
// map, which only geometry, camera, froxel range or sun changes invalidate (not the jitter), so a
// sequence of --frames pays its ray cast once, as the GPU renderer does.
struct CpuHistory {
    TemporalState state;
    std::array<HistoryVolume, 2> pair;
    SunShadowCache sunShadow;
    LocalShadowCache localShadows;  // point and spot light maps, likewise kept
};

}  // namespace brume
