// The lights on the surfaces again at the pixels surface_light.comp listed, with the exact fog
// transmittance where the corners' blend is not trusted (surface_body.glsl); dispatched indirectly.
#version 450
#extension GL_GOOGLE_include_directive : require
#define BRUME_SURFACE_EXACT
#include "surface_body.glsl"
