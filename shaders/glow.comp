// The glow pass (glow_body.glsl), reading the media from voxelize's images.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "glow_body.glsl"
