// The glow for scenes without vdb volumes, with density textures: glow_body.glsl with the media at the glow's froxel
// computed (media_at.glsl), not loaded from voxelize's images.
#version 450
#extension GL_GOOGLE_include_directive : require
#define BRUME_INLINE_MEDIA
#define BRUME_VOXELIZE_TEXTURE
#include "glow_body.glsl"
