// The editor's viewport scaled from a source of another size: display_body.glsl with its bilinear filter.
#version 450
#extension GL_GOOGLE_include_directive : require
#define BRUME_DISPLAY_SCALED
#include "display_body.glsl"
