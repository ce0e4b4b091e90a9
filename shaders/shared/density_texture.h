// Density textures: a grid's active index box tiled through world space (period tile_size along X, Y
// and Z), scrolled by the wind, trilinear with wrapping at the seam, modulating a volume's density.
// Evaluated identically by the CPU (DensityGrid::sampleCorners) and the GPU (density_texture.glsl):
// each fetches the 8 voxels of textureCell(...) its own way and mixes them with vdbTrilinear.
#ifndef BRUME_SHARED_DENSITY_TEXTURE_H
#define BRUME_SHARED_DENSITY_TEXTURE_H

#include "types.h"
#include "vdb.h"

BRUME_NAMESPACE_BEGIN

struct TextureCell {
    ivec3 lo;    // index of the lower corner voxel, inside the active box
    ivec3 hi;    // the upper corner voxel: lo + 1, or the box's first voxel at the seam
    vec3 frac;   // position inside the cell, in [0, 1)
};

// i in [0, n]: n wraps to 0 (u = fract(q) * n reaches n when fract rounds up to 1).
BRUME_FUNC int textureWrap(int i, int n) { return i >= n ? i - n : i; }

// World position p at scene time t -> the cell of a texture layer (the texture or its detail: the four
// fields of VolumeData.texture* or .detail*). Tile coordinate q = (p - scroll t) / tile; one tile
// holds the box's n voxels per axis, so the field has period n voxels (voxel n is voxel 0).
BRUME_FUNC TextureCell textureLayerCell(vec4 params, vec4 scroll, ivec4 boxMin, ivec4 boxSize, vec3 worldPos, float time) {
    vec3 q = (worldPos - vec3(scroll) * time) * params.x;
    ivec3 n = ivec3(boxSize);
    vec3 u = (q - floor(q)) * vec3(n);
    vec3 f = floor(u);
    ivec3 b = ivec3(f);
    TextureCell c;
    c.frac = u - f;
    ivec3 lo = ivec3(textureWrap(b.x, n.x), textureWrap(b.y, n.y), textureWrap(b.z, n.z));
    ivec3 hi = ivec3(textureWrap(lo.x + 1, n.x), textureWrap(lo.y + 1, n.y), textureWrap(lo.z + 1, n.z));
    ivec3 origin = ivec3(boxMin);
    c.lo = origin + lo;
    c.hi = origin + hi;
    return c;
}

BRUME_FUNC TextureCell textureCell(VolumeData v, vec3 worldPos, float time) {
    return textureLayerCell(v.textureParams, v.textureScroll, v.textureMin, v.textureSize, worldPos, time);
}

// The detail layer's cell: its own tile, scroll and grid.
BRUME_FUNC TextureCell detailCell(VolumeData v, vec3 worldPos, float time) {
    return textureLayerCell(v.detailParams, v.detailScroll, v.detailMin, v.detailSize, worldPos, time);
}

// A texture voxel's value under the contrast exponent: value^exponent, applied to each of the 8
// voxels before the trilinear mix, so that the mixed field's mean over a tile is exactly the voxels'
// mean of value^exponent (the mean rule below holds for any exponent). Exponent 1 returns the value
// untouched (negative values too), so scenes without an exponent render as before.
BRUME_FUNC float textureShape(float value, float exponent) {
    return exponent == 1.0f ? value : pow(max(value, 1.0e-30f), exponent);
}

// The factor on the volume's density for a (shaped) texture value: 1 + strength (value / mean - 1), held at
// >= 0. Strength 0 gives exactly 1 (the plain volume); strength <= 1 keeps the mean density (the
// factor's mean over a tile is exactly 1, since trilinear interpolation of a periodic field keeps its
// voxels' mean), which is what fog shadows use (docs/vdb.md).
// params: a layer's textureParams or detailParams (y strength, z 1 / mean).
BRUME_FUNC float textureLayerFactor(vec4 params, float value) {
    return max(1.0f + params.y * (value * params.z - 1.0f), 0.0f);
}

BRUME_FUNC float textureDensityFactor(VolumeData v, float value) { return textureLayerFactor(v.textureParams, value); }

// The detail layer multiplies the texture's factor by its own, under the same rule with its own
// strength and mean: strength 0 gives exactly 1, and each layer's factor has mean 1 over its tile.
BRUME_FUNC float detailDensityFactor(VolumeData v, float value) { return textureLayerFactor(v.detailParams, value); }

BRUME_FUNC bool hasDensityTexture(VolumeData v) { return v.textureSize.w != 0; }
// Only a volume with a density texture has a detail layer (compileScene).
BRUME_FUNC bool hasDetailTexture(VolumeData v) { return v.detailSize.w != 0; }

BRUME_NAMESPACE_END

#endif
