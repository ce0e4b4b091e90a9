// Pass 1 for scenes with vdb volumes: sampled from their NanoVDB grids (vdb_sample.glsl).
#version 450
#extension GL_GOOGLE_include_directive : require
#define BRUME_FROXEL_IMAGES
#define BRUME_VOLUME_TEXELS
#define BRUME_VOXELIZE_VDB
#include "resources.glsl"
#include "vdb_sample.glsl"
#include "voxelize_body.glsl"
