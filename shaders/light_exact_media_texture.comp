// Pass 2b for scenes without vdb volumes, with density textures: light_exact.comp with the media computed
// where they are used, not loaded from voxelize's images (light_body.glsl froxelMedia).
#version 450
#extension GL_GOOGLE_include_directive : require
#define BRUME_LIGHT_EXACT
#define BRUME_INLINE_MEDIA
#define BRUME_VOXELIZE_TEXTURE
#include "light_body.glsl"
