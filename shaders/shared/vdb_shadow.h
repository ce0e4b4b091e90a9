// VDB volumes in the froxel renderers' fog shadows (docs/shadows.md, "VDB volumes"). A grid has no
// closed-form line integral, so its optical depth toward a light is marched: the shadow ray is clipped
// to the grid's world bounds (the active voxels' box grown by one voxel, VolumeData.worldMin/Max), then
// cut into equal steps of at most 1 / FrameUniforms.vdbShadowSamples of the grid's shortest voxel edge
// (VolumeData.params.y), each sampled trilinearly at its midpoint. The CPU (NanoVDB) and the GPU
// (PNanoVDB) run the same loop over the same sample points:
//
//   VdbShadowMarch m = vdbShadowMarch(v, p, dir, maxDist, frame.vdbShadowSamples);
//   float sum = 0; for (int s = 0; s < m.count; ++s) sum += density(m.start + m.step * float(s));
//   tau += vdbShadowOpticalDepth(v, sum, m.stepLength);
//
// The march runs only where the transmittance volume (shadow_volume.h) is built: each shadowing light
// gets a second layer there, layer vdbShadowLayer(light, lights), holding the vdb volumes' optical
// depth alone; the light pass and the surfaces multiply the analytic transmittance (exact at edges) by
// exp(-that layer's trilinear blend), so no other pass walks a grid.
#ifndef BRUME_SHARED_VDB_SHADOW_H
#define BRUME_SHARED_VDB_SHADOW_H

#include "shadows.h"

BRUME_NAMESPACE_BEGIN

// At most this many samples per grid and shadow ray: a bound on the cost of one cell (a 1000-voxel
// diagonal at one sample per voxel), not a quality setting; longer chords take longer steps.
BRUME_CONST int VDB_SHADOW_MAX_STEPS = 1024;

struct VdbShadowMarch {
    vec3 start;        // world position of the first sample (the middle of the first step)
    vec3 step;         // world displacement from one sample to the next
    float stepLength;  // [m]
    int count;         // samples; 0 when the ray misses the grid or vdb shadows are off
};

// The march of vdb volume v from p along unit dir over [0, maxDist] (BRUME_HUGE: a directional light)
// at samplesPerVoxel samples per shortest voxel edge (0: none).
BRUME_FUNC VdbShadowMarch vdbShadowMarch(VolumeData v, vec3 p, vec3 dir, float maxDist, int samplesPerVoxel) {
    VdbShadowMarch m;
    m.start = p;
    m.step = vec3(0.0f);
    m.stepLength = 0.0f;
    m.count = 0;
    if (v.kind.x != VOLUME_VDB || !vdbHasGrid(v) || samplesPerVoxel <= 0) return m;
    // The bounds' box as the cube [-1, 1]^3: scaling each axis keeps the ray parameter.
    vec3 centre = 0.5f * (vec3(v.worldMax) + vec3(v.worldMin));
    vec3 halfSize = max(0.5f * (vec3(v.worldMax) - vec3(v.worldMin)), vec3(1.0e-6f));
    vec2 t = cubeInterval((p - centre) / halfSize, dir / halfSize, 1.0f);
    t = vec2(max(t.x, 0.0f), min(t.y, maxDist));
    if (!(t.y > t.x)) return m;
    float len = t.y - t.x;
    float n = clamp(ceil(len * float(samplesPerVoxel) / v.params.y), 1.0f, float(VDB_SHADOW_MAX_STEPS));
    m.stepLength = len / n;
    m.count = int(n);
    m.start = p + dir * (t.x + 0.5f * m.stepLength);
    m.step = dir * m.stepLength;
    return m;
}

// Optical depth of a march whose samples' densities (density_scale applied) sum to densitySum.
BRUME_FUNC vec3 vdbShadowOpticalDepth(VolumeData v, float densitySum, float stepLength) {
    return (vec3(v.sigmaS_g) + vec3(v.sigmaA)) * (densitySum * stepLength);
}

// The vdb layer holds optical depth, blended linearly and exponentiated here: at a shadow edge the
// blend then stays as dark as the darker cells allow (exp of a mean <= mean of exps), where a blend
// of transmittances would spread light over r froxels into the shadow.
BRUME_FUNC vec3 vdbShadowTransmittance(vec3 blendedOpticalDepth) { return exp(-blendedOpticalDepth); }

// The transmittance volume's layer that holds light `light`'s vdb transmittance, after the lights'
// analytic layers (shadowVolumeIndex's `light` argument).
BRUME_FUNC int vdbShadowLayer(int light, int lightCount) { return lightCount + light; }

BRUME_NAMESPACE_END

#endif
