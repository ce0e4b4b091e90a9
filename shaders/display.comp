// The editor's viewport at the source's own size (exact texels): display_body.glsl without the
// bilinear filter, which lavapipe would run for every pixel behind an untaken branch (display_scaled.comp).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "display_body.glsl"
