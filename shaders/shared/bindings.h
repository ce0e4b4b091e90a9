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
BRUME_CONST int BINDING_SHADOW_TRANSMITTANCE = 13;  // storage vec4[]: fog transmittance volume
                                                     // (shadow_volume.h shadowVolumeIndex); a buffer, not an
                                                     // image: lavapipe's imageLoad is ~3x dearer, and the
                                                     // geometry pass may read it
BRUME_CONST int BINDING_COUNT = 14;

// Written by the light pass with atomics; 16 bytes in std430.
struct FroxelCounters {
    uint litFroxels;      // froxels with sigma_t > 0
    uint skippedFroxels;  // froxels with sigma_t = 0 (lighting skipped)
    uint pad0;
    uint pad1;
};

BRUME_NAMESPACE_END

#endif
