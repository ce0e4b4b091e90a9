// Structs and enums that cross the CPU/GPU boundary. Every member is a vec4, mat4 or ivec4 so that
// std140 and std430 layouts are identical and match glm's C++ layout (tests/test_shared_layout.cpp
// checks every offset and size).
#ifndef BRUME_SHARED_TYPES_H
#define BRUME_SHARED_TYPES_H

#include "common.h"

BRUME_NAMESPACE_BEGIN

// VolumeData.kind.x
BRUME_CONST int VOLUME_BOX = 0;
BRUME_CONST int VOLUME_HEIGHT_EXPONENTIAL = 1;
BRUME_CONST int VOLUME_HEIGHT_LINEAR = 2;
BRUME_CONST int VOLUME_DEPTH = 3;
BRUME_CONST int VOLUME_VDB = 4;

// VolumeData.kind.y of a VOLUME_BOX: the shape in its local unit cube. One volume kind for the three
// shapes, so the renderers' loops over volumes gain no branch (docs/performance.md): media.h picks
// the shape's distance with selects.
BRUME_CONST int SHAPE_BOX = 0;
BRUME_CONST int SHAPE_ELLIPSOID = 1;  // the sphere of diameter 1
BRUME_CONST int SHAPE_CYLINDER = 2;   // diameter 1, height 1 along local Y

// LightData.kind.x
BRUME_CONST int LIGHT_DIRECTIONAL = 0;
BRUME_CONST int LIGHT_POINT = 1;
BRUME_CONST int LIGHT_SPOT = 2;

// Froxel compute passes (voxelize, shadow volume, temporal) run 8x2x4 invocations; dispatch counts
// use brumeDivRoundUp. Lavapipe runs a workgroup as 8-wide batches along x only, so 4x4x4 left half
// of every batch masked (docs/performance.md, "froxel, round 7" and "groups").
BRUME_CONST int FROXEL_GROUP_X = 8;
BRUME_CONST int FROXEL_GROUP_Y = 2;
BRUME_CONST int FROXEL_GROUP_Z = 4;
// The integration pass walks slices serially; one invocation per (x, y) column.
BRUME_CONST int INTEGRATE_GROUP_X = 8;
BRUME_CONST int INTEGRATE_GROUP_Y = 8;
// Screen-space passes (composite).
BRUME_CONST int SCREEN_GROUP_X = 8;
BRUME_CONST int SCREEN_GROUP_Y = 8;

// One fog volume, ready to evaluate. 304 bytes.
struct VolumeData {
    mat4 localFromWorld;  // box: world -> unit cube [-0.5,0.5]^3; vdb: world -> grid index space
    vec4 sigmaS_g;        // rgb: scattering coefficient at density 1 [1/m]; a: phase g
    vec4 sigmaA;          // rgb: absorption coefficient at density 1 [1/m]; a: unused
    vec4 emission;        // rgb: emitted radiance per meter at density 1; a: unused
    vec4 params;          // box: x edge_fade, z height_falloff [1/m], w bottom: lowest world y [m]. height: x base_height, y falloff [1/m] or transition
                          // height [m]. depth: x visibility_distance, y start_distance. vdb: x density_scale, y shortest voxel edge [m],
                          // z height_falloff [1/m], w bottom (as a box's)
    ivec4 kind;           // x: VOLUME_*; vdb: y byte offset of its grid in the GPU grid buffer, z 1 = has a grid,
                          // w byte offset of its occupancy cells after y (vdb.h), 0 = no culling;
                          // box: y SHAPE_*
    vec4 worldMin;        // xyz: world-space bounds of non-zero density (+-BRUME_HUGE when unbounded)
    vec4 worldMax;
    // Density texture (density_texture.h), all zero when the volume has none.
    vec4 textureParams;   // x: 1 / tile_size [1/m]; y: strength; z: 1 / the mean of value^exponent; w: exponent
    vec4 textureScroll;   // xyz: scroll velocity [m/s]; w unused
    ivec4 textureMin;     // xyz: the grid's active index box minimum; w: byte offset in the GPU grid buffer
    ivec4 textureSize;    // xyz: active index box size in voxels (the period); w: 1 = has a texture
    // The texture's detail layer, the same four fields (all zero when none; only with a texture).
    vec4 detailParams;
    vec4 detailScroll;
    ivec4 detailMin;
    ivec4 detailSize;
};

// One light, ready to evaluate. 80 bytes.
struct LightData {
    vec4 positionRange;   // xyz: world position [m] (point, spot); w: range [m], 0 = no window
    vec4 direction;       // xyz: unit direction the light travels (directional, spot)
    vec3 intensity;       // color * intensity (W/m^2 for directional, W/sr for point and spot)
    float fogScale;       // fog_scale: the light's in-scattering in fog is multiplied by it
    vec4 spot;            // x: cos(outer angle); y: cos(inner angle); z: 0 as compiled; the GPU renderer
                          // writes the glow radius of the frame there (gpu_renderer.cpp writeLightGlowRadii)
    ivec4 kind;           // x: LIGHT_*; y: casts shadows (0/1); z: point/spot: local shadow map slot + 1,
                          // 0 = none (local_shadow.h)
};
// LightData as 16-byte texels (std430 stride = sizeof = 80 bytes): the light passes read lights[]
// through the rgba32i texel view lightTexels, texel t holding bytes 16t..16t+15 (resources.glsl lightAt).
BRUME_CONST int LIGHT_DATA_TEXELS = 5;
// VolumeData as 16-byte texels (std430 stride = sizeof = 304 bytes): the passes that define
// BRUME_VOLUME_TEXELS read volumes[] through the rgba32i texel view volumeTexels (resources.glsl volumeAt).
BRUME_CONST int VOLUME_DATA_TEXELS = 19;

// The slots of LightData.kind and VolumeData.kind after x (the kind), by name, for C++ and GLSL
// (compileScene writes them).
BRUME_FUNC bool lightCastsShadows(LightData l) { return l.kind.y != 0; }
BRUME_FUNC int lightShadowSlot(LightData l) { return l.kind.z - 1; }  // point/spot map slot, -1 = none
BRUME_FUNC int vdbGridOffset(VolumeData v) { return v.kind.y; }      // byte offset in the grid buffer
BRUME_FUNC bool vdbHasGrid(VolumeData v) { return v.kind.z != 0; }
BRUME_FUNC int vdbOccupancyOffset(VolumeData v) { return v.kind.w; }  // after the grid, 0 = no culling
BRUME_FUNC int boxShape(VolumeData v) { return v.kind.y; }           // SHAPE_*

// Per-frame constants shared by every pass. 416 bytes.
struct FrameUniforms {
    mat4 viewFromWorld;
    mat4 worldFromView;
    mat4 clipFromView;
    mat4 clipFromWorld;
    vec4 cameraPosition;  // xyz: world position; w unused
    vec4 ambient;         // rgb: radiance arriving from every direction; w: scene time [s] (density textures)
    vec4 projection;      // x: tan(fov_y/2) * aspect; y: tan(fov_y/2); z: camera near; w: camera far
    vec4 froxelRange;     // x: froxel near [m]; y: froxel far [m]; z: slice distribution exponent
    ivec4 froxelDims;     // xyz: froxel grid size; w: tile size [px]
    ivec4 counts;         // x: image width, y: image height [px]; z: volume count; w: light count
    vec4 jitter;          // xyz: sample position inside each froxel in [0,1)^3 (0.5 = centre); w unused
    // Shadows (four ints fill one 16-byte slot in std140, std430 and C++ alike):
    int localFogShadows;  // fog transmittance toward point and spot lights too (0/1; the sun's is
                          // always on; shadows.h)
    int shadowReduction;  // transmittance volume reduction r >= 1 (shadow_volume.h)
    int sunShadowLight;   // index + 1 of the light the sun shadow map serves, 0 = none (sun_shadow.h)
    int localShadowTexels;  // texels per side of each point/spot shadow map face, 0 = none (local_shadow.h)
    int vdbShadowSamples;   // vdb shadow march samples per shortest voxel edge, 0 = vdb volumes cast
                            // no fog shadows (vdb_shadow.h)
    // GPU only (0 on the CPU): the first froxel of the region the voxelize and light passes dispatch
    // over (core/media_region.h); the rest of the grid holds no media.
    int mediaOriginX;
    int mediaOriginY;
    int mediaOriginZ;
    vec4 temporal;        // temporal pass (temporal.h): x: this frame's history weight (0 = no
                          // history); y: 1 = the view rests (progressive mean, no clamp), 0 = it
                          // moved or the scene time changed; GPU only (0 on the CPU): z: 1 = the
                          // froxels no lookup reads are skipped (temporalSkipsHidden); w: the
                          // history side this frame writes, 0 or 1 (its half of columnEnds)
};

BRUME_NAMESPACE_END

#endif
