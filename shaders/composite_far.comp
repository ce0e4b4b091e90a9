// The composite over the tiles with a pixel past the froxel far: the distant fog table's lookup
// included (composite_body.glsl).
#version 450
#extension GL_GOOGLE_include_directive : require
#define BRUME_FROXEL_IMAGES
#define BRUME_COMPOSITE_FAR
#include "resources.glsl"
#include "distant_table.h"
#include "composite_body.glsl"
