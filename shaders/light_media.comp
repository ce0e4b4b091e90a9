// Pass 2a for scenes without vdb volumes: light.comp with the media computed
// where they are used, not loaded from voxelize's images (light_body.glsl froxelMedia).
#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require  // [[unroll]] (light_body.glsl lightBlock)
#define BRUME_INLINE_MEDIA
#include "light_body.glsl"
