// Descriptor bindings of the GPU froxel renderer: one set (set 0) shared by every pass, so the
// numbers are written once here for gpu/*.cpp and shaders/resources.glsl. Not used by the CPU.
#ifndef BRUME_SHARED_BINDINGS_H
#define BRUME_SHARED_BINDINGS_H

#include "common.h"

BRUME_NAMESPACE_BEGIN

BRUME_CONST int BINDING_FRAME = 0;             // uniform FrameUniforms
BRUME_CONST int BINDING_VOLUMES = 1;           // storage VolumeData[]
BRUME_CONST int BINDING_LIGHTS = 2;            // storage LightData[]
BRUME_CONST int BINDING_COUNTERS = 3;          // storage FroxelCounters
BRUME_CONST int BINDING_MEDIA_SCATTERING = 4;  // image3D rgba32f: rgb sigma_s, a phase g
BRUME_CONST int BINDING_MEDIA_EXTINCTION = 5;  // image3D rgba32f: rgb sigma_t
BRUME_CONST int BINDING_MEDIA_EMISSION = 6;    // image3D rgba32f: rgb emission
BRUME_CONST int BINDING_SOURCE = 7;            // image3D rgba32f: rgb source S
BRUME_CONST int BINDING_INTEGRATED_SCATTERING = 8;     // image3D rgba32f
BRUME_CONST int BINDING_INTEGRATED_TRANSMITTANCE = 9;  // image3D rgba32f
BRUME_CONST int BINDING_SCENE_COLOR = 10;      // image2D rgba32f: shaded surfaces / sky
BRUME_CONST int BINDING_SCENE_DEPTH = 11;      // image2D r32f: view depth [m] (camera far = sky)
BRUME_CONST int BINDING_OUTPUT = 12;           // image2D rgba32f: the composited image
// Temporal pass (gpu/pass_temporal.cpp): last frame's constants and the history ping-pong pair,
// rebound every frame so that *_IN is what the previous frame wrote to *_OUT.
BRUME_CONST int BINDING_PREVIOUS_FRAME = 13;   // uniform FrameUniforms of the previous frame
BRUME_CONST int BINDING_HISTORY_SOURCE_IN = 14;       // image3D rgba32f: resolved S, previous frame
BRUME_CONST int BINDING_HISTORY_EXTINCTION_IN = 15;   // image3D rgba32f: resolved sigma_t, previous frame
BRUME_CONST int BINDING_HISTORY_SOURCE_OUT = 16;      // image3D rgba32f: resolved S, this frame
BRUME_CONST int BINDING_HISTORY_EXTINCTION_OUT = 17;  // image3D rgba32f: resolved sigma_t, this frame
BRUME_CONST int BINDING_SHADOW_TRANSMITTANCE = 18;  // storage vec4[]: fog transmittance volume
                                                     // (shadow_volume.h shadowVolumeIndex); a buffer, not an
                                                     // image: lavapipe's imageLoad is ~3x dearer, and the
                                                     // geometry pass may read it
BRUME_CONST int BINDING_VDB_GRIDS = 19;  // storage uint[]: every vdb volume's NanoVDB grid, back to back
                                          // (VolumeData.kind.y: byte offset), read with PNanoVDB
BRUME_CONST int BINDING_LIGHT_CLUSTERS = 20;  // storage int[]: light lists per cluster (clusters.h), uploaded
                                               // from core/clusters.cpp each frame
BRUME_CONST int BINDING_SUN_SHADOW_MAP = 21;  // storage: SunShadowFit, then float depth[N * N]
                                               // (sun_shadow.h); built on the host (core/sun_shadow.h)
BRUME_CONST int BINDING_LOCAL_SHADOW_MAPS = 22;  // storage float[]: every point/spot shadow map face
                                                  // (local_shadow.h); built on the host (core/local_shadow.h)
BRUME_CONST int BINDING_COUNT = 23;

// Written by the light pass with atomics; 16 bytes in std430.
struct FroxelCounters {
    uint litFroxels;      // froxels with sigma_t > 0
    uint skippedFroxels;  // froxels with sigma_t = 0 (lighting skipped)
    uint pad0;
    uint pad1;
};

BRUME_NAMESPACE_END

#endif
