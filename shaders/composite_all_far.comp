// The composite over the tiles whose pixels all lie past the froxel far (tile_lists.comp): the distant
// fog table's lookup included, and the integrated volume's last entry read once (composite_body.glsl).
#version 450
#extension GL_GOOGLE_include_directive : require
#define BRUME_FROXEL_IMAGES
#define BRUME_COMPOSITE_FAR
#define BRUME_COMPOSITE_ALL_FAR
#include "resources.glsl"
#include "distant_table.h"
#include "composite_body.glsl"
