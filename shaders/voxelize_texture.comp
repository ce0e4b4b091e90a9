// Pass 1 for scenes with density textures but no vdb volumes (density_texture.glsl).
#version 450
#extension GL_GOOGLE_include_directive : require
#define BRUME_FROXEL_IMAGES
#define BRUME_VOLUME_TEXELS
#define BRUME_VOXELIZE_TEXTURE
#include "resources.glsl"
#include "density_texture.glsl"
#include "voxelize_body.glsl"
