// Pass 2a: the light pass over every froxel, trusted shadow-volume blends only (light_body.glsl).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "light_body.glsl"
