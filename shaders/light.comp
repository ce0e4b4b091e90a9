// Pass 2a: the light pass over every froxel, trusted shadow-volume blends only (light_body.glsl).
#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require  // [[unroll]] (light_body.glsl lightBlock)
#include "light_body.glsl"
