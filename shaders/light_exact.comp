// Pass 2b: the light pass again over the froxels pass 2a listed, with the exact fallback
// (light_body.glsl); dispatched indirectly.
#version 450
#extension GL_GOOGLE_include_directive : require
#define BRUME_LIGHT_EXACT
#include "light_body.glsl"
