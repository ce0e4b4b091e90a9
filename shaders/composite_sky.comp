// The composite over the tiles whose pixels are all sky (tile_lists.comp): each pixel's fog from the
// integrated volume's last entry and the distant fog table's, without its depth (composite_body.glsl).
#version 450
#extension GL_GOOGLE_include_directive : require
#define BRUME_FROXEL_IMAGES
#define BRUME_COMPOSITE_SKY
#include "resources.glsl"
#include "distant_table.h"
#include "composite_body.glsl"
