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

// The froxels the GPU's temporal and integrate passes compute: the media region grown by the one
// froxel of the temporal neighbourhood (shared/temporal.h step 5), within the grid. Outside it every
// froxel's neighbourhood holds no media, so what a pass over the whole grid would write there is
// known: a resolved S and sigma_t of 0 (the clamp in motion; at rest the froxel's own history, 0 by
// the same argument one frame earlier; without history this frame's 0), hence integrated scattering
// 0 and transmittance 1 up to the region and their values at its far end behind it. Empty when the
// media region is.
FroxelRegion temporalFroxelRegion(const FroxelRegion& media, glm::ivec3 dims);

// The cells of the fog transmittance volume (shared/shadow_volume.h, reduction frame.shadowReduction)
// that some reader needs this frame, i.e. the cells the shadow volume pass computes:
// - the light passes (light.comp, light_exact.comp; core: lightRow) read the 8 cells of
//   shd::shadowLookup (cell f / r and the clamped upper one) only at froxels f with sigma_t > 0, all in
//   `media`: the cells from media.lo / r up to and including (media.hi - 1) / r + 1, within the volume.
//   The renderers pass, per light, the box of the media froxels whose clusters list the light
//   (core/light_reach.h listedFroxelRegions), the only ones that read its layer;
// - surfaces (geometry.frag; core: surfaceFogTransmittance) read only the vdb layers, at any point of
//   the grid: the whole volume when vdb shadows are on (frame.vdbShadowSamples > 0) and `surfaces`.
// Indices are cells, not froxels. Empty when nothing reads the volume.
FroxelRegion shadowCellRegion(const FroxelRegion& media, const shd::FrameUniforms& frame, bool surfaces);

// Whether every froxel of `inner` lies in `outer` (an empty inner lies in any region).
bool regionContains(const FroxelRegion& outer, const FroxelRegion& inner);

// The smallest region holding both a and b (an empty one adds nothing; empty when both are).
FroxelRegion regionUnion(const FroxelRegion& a, const FroxelRegion& b);

// Per volume of cs: whether it can add anything to the froxel passes of this frame (voxelize's media,
// the fog transmittance toward a light at a froxel's sample point or a shadow volume cell). False
// only when proved: the volume's bounds miss both the froxel frustum (every sample point, any
// jitter, lies in it) and every shadow ray from it toward a light whose fog shadow is evaluated
// (directional lights, and point/spot lights with frame.localFogShadows). Such a volume's density and
// density length there are exactly 0, so leaving it out changes no value. Unbounded volumes: true.
std::vector<bool> froxelVolumesInReach(const CompiledScene& cs, const shd::FrameUniforms& frame);

// Per volume of cs: whether it can change a surface's fog transmittance toward a light this frame
// (geometry.frag; core: surfaceFogTransmittance), i.e. froxelVolumesInReach's test with the view
// frustum from the camera near to the camera far, where the rasterizer keeps every shaded surface
// point, in place of the froxel frustum. A volume behind the camera that no shadow ray from the
// view crosses is out of reach: its optical depth along every such ray is exactly 0.
std::vector<bool> surfaceVolumesInReach(const CompiledScene& cs, const shd::FrameUniforms& frame);

}  // namespace brume
