// The froxels of a frame that can hold media (docs/performance.md, "Dispatch only where media
// are"): every volume's density is 0 outside its world bounds (shd::insideBounds gates it), so the
// GPU's voxelize and light passes dispatch over the box of froxels around the bounds of the volumes
// and leave the rest of the grid at 0 (cleared), which is what they would have computed there.
// Unbounded volumes (height, depth fog) cover the whole grid.
#pragma once

#include <cstdint>

#include "compile.h"

namespace brume {

// Froxel indices [lo, hi) per axis; empty when lo == hi on some axis.
struct FroxelRegion {
    glm::ivec3 lo{0};
    glm::ivec3 hi{0};
    bool empty() const { return hi.x <= lo.x || hi.y <= lo.y || hi.z <= lo.z; }
    int64_t froxels() const {
        return empty() ? 0 : int64_t(hi.x - lo.x) * int64_t(hi.y - lo.y) * int64_t(hi.z - lo.z);
    }
};

// Every froxel whose sample point (id + frame.jitter, any jitter in [0, 1)^3) can lie inside some
// volume's bounds, with a froxel of margin on each side; the whole grid as soon as one volume is
// unbounded.
FroxelRegion mediaFroxelRegion(const CompiledScene& cs, const shd::FrameUniforms& frame);

// Per volume of cs: whether it can add anything to the froxel passes of this frame (voxelize's media,
// the fog transmittance toward a light at a froxel's sample point or a shadow volume cell). False
// only when proved: the volume's bounds miss both the froxel frustum (every sample point, any
// jitter, lies in it) and every shadow ray from it toward a light whose fog shadow is evaluated
// (directional lights, and point/spot lights with frame.localFogShadows). Such a volume's density and
// density length there are exactly 0, so leaving it out changes no value. Unbounded volumes: true.
std::vector<bool> froxelVolumesInReach(const CompiledScene& cs, const shd::FrameUniforms& frame);

}  // namespace brume
