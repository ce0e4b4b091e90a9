// The composite over the pixels within the froxel far (composite_body.glsl).
#version 450
#extension GL_GOOGLE_include_directive : require
#define BRUME_FROXEL_IMAGES
#include "resources.glsl"
#include "distant_table.h"
#include "composite_body.glsl"
