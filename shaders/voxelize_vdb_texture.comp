// Pass 1 for scenes with vdb volumes and density textures (vdb_sample.glsl, density_texture.glsl).
#version 450
#extension GL_GOOGLE_include_directive : require
#define BRUME_FROXEL_IMAGES
#define BRUME_VOLUME_TEXELS
#define BRUME_VOXELIZE_VDB
#define BRUME_VOXELIZE_TEXTURE
#include "resources.glsl"
#include "vdb_sample.glsl"
#include "density_texture.glsl"
#include "voxelize_body.glsl"
