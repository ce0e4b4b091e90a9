// The lights on the surfaces, every pixel, trusted corner blends only (surface_body.glsl).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "surface_body.glsl"
