// Every resource of the froxel renderer's single descriptor set, expanded from the tables of
// shared/frame_table.h (the C++ side expands the same tables in gpu/frame_table.h). Passes use a
// subset; spirv-opt drops the rest. imageLoad needs the format qualifiers, and only compute stages
// see the images (devices may allow as few as 4 storage images per graphics stage).
#include "brume.h"
#include "bindings.h"
#include "frame_table.h"

#define BRUME_GLSL_BUFFER(id, binding_, kind, layout_, qualifiers, block, body) \
    layout(layout_, set = 0, binding = binding_) qualifiers block { body };
BRUME_FRAME_BUFFERS(BRUME_GLSL_BUFFER)
// The format is the view's (C++); the shader's sampler follows its numeric type: texelFetch returns a
// vec4 for the float formats, an ivec4 for the integer ones.
#define BRUME_GLSL_SAMPLER_rgba32f samplerBuffer
#define BRUME_GLSL_SAMPLER_r32f samplerBuffer
#define BRUME_GLSL_SAMPLER_rg32f samplerBuffer
#define BRUME_GLSL_SAMPLER_r32i isamplerBuffer
#define BRUME_GLSL_SAMPLER_rgba32i isamplerBuffer
#define BRUME_GLSL_TEXEL_VIEW(id, binding_, buffer, format) \
    layout(set = 0, binding = binding_) uniform BRUME_GLSL_SAMPLER_##format id;
BRUME_FRAME_TEXEL_VIEWS(BRUME_GLSL_TEXEL_VIEW)

// Light i and the light cluster buffer's int i. Shaders that define BRUME_LIGHT_TEXELS before this
// file (the light passes) read them through the texel views lightTexels and lightClusterTexels:
// lavapipe loads a storage buffer lane by lane, a texel buffer's texels as vector gathers
// (docs/performance.md, "texel2"). The others read the storage buffers.
#ifdef BRUME_LIGHT_TEXELS
LightData lightAt(int i) {
    int t = LIGHT_DATA_TEXELS * i;
    ivec4 intensityFog = texelFetch(lightTexels, t + 2);
    return LightData(intBitsToFloat(texelFetch(lightTexels, t)), intBitsToFloat(texelFetch(lightTexels, t + 1)),
                     intBitsToFloat(intensityFog.xyz), intBitsToFloat(intensityFog.w),
                     intBitsToFloat(texelFetch(lightTexels, t + 3)), texelFetch(lightTexels, t + 4));
}
int clusterInt(int i) { return texelFetch(lightClusterTexels, i).x; }
#else
LightData lightAt(int i) { return lights[i]; }
int clusterInt(int i) { return lightClusters[i]; }
#endif

// Volume i. Shaders that define BRUME_VOLUME_TEXELS read it through the texel view volumeTexels,
// VOLUME_DATA_TEXELS rgba32i texels per volume, the float members as their stored bits; the texels of
// members a shader does not use are not fetched (dead code once inlined). The others read volumes[].
#ifdef BRUME_VOLUME_TEXELS
vec4 volumeFloats(int t) { return intBitsToFloat(texelFetch(volumeTexels, t)); }
VolumeData volumeAt(int i) {
    int t = VOLUME_DATA_TEXELS * i;
    return VolumeData(mat4(volumeFloats(t), volumeFloats(t + 1), volumeFloats(t + 2), volumeFloats(t + 3)),
                      volumeFloats(t + 4), volumeFloats(t + 5), volumeFloats(t + 6), volumeFloats(t + 7),
                      texelFetch(volumeTexels, t + 8), volumeFloats(t + 9), volumeFloats(t + 10),
                      volumeFloats(t + 11), volumeFloats(t + 12), texelFetch(volumeTexels, t + 13),
                      texelFetch(volumeTexels, t + 14), volumeFloats(t + 15), volumeFloats(t + 16),
                      texelFetch(volumeTexels, t + 17), texelFetch(volumeTexels, t + 18));
}
#else
VolumeData volumeAt(int i) { return volumes[i]; }
#endif

#ifdef BRUME_FROXEL_IMAGES
#define BRUME_GLSL_IMAGE(id, binding_, format, type, flags) \
    layout(set = 0, binding = binding_, format) uniform type id;
BRUME_FRAME_IMAGES(BRUME_GLSL_IMAGE)
#define BRUME_GLSL_HISTORY(id, inName, inBinding, outName, outBinding, format, type) \
    layout(set = 0, binding = inBinding, format) uniform type inName; \
    layout(set = 0, binding = outBinding, format) uniform type outName;
BRUME_FRAME_HISTORY(BRUME_GLSL_HISTORY)

// The temporal history's layout (frame_table.h BRUME_FRAME_HISTORY): one froxel's resolved S and
// sigma_t, each (rgb, alpha 0), in two texels, historySource* (rgba32f: S.rgb, sigma_t.r) and
// historyExtinction* (rg32f: sigma_t.g, sigma_t.b). historyTexelA / B pack them, historySourceOf /
// historyExtinctionOf give them back bit for bit.
vec4 historyTexelA(vec4 source, vec4 extinction) { return vec4(source.rgb, extinction.r); }
vec4 historyTexelB(vec4 extinction) { return vec4(extinction.gb, 0.0f, 0.0f); }
vec4 historySourceOf(vec4 a) { return vec4(a.rgb, 0.0f); }
vec4 historyExtinctionOf(vec4 a, vec4 b) { return vec4(a.a, b.rg, 0.0f); }
// The light pass's output, sourceImage (S.rgb, sigma_t.r) and sourceExtinction (sigma_t.gb), packs the
// same way: the same four functions apply to it.
#endif
