// Pass 1 for scenes without vdb volumes (voxelize_body.glsl); vdb volumes report density 0 here.
#version 450
#extension GL_GOOGLE_include_directive : require
#define BRUME_FROXEL_IMAGES
#define BRUME_VOLUME_TEXELS
#include "resources.glsl"
#include "voxelize_body.glsl"
