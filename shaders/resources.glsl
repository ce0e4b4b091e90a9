// Every resource of the froxel renderer's single descriptor set (numbers: shared/bindings.h).
// Passes use a subset; spirv-opt drops the rest. imageLoad needs the format qualifiers.
#include "brume.h"
#include "bindings.h"

layout(std140, set = 0, binding = BINDING_FRAME) uniform FrameBlock { FrameUniforms frame; };
layout(std430, set = 0, binding = BINDING_VOLUMES) readonly buffer VolumeBlock { VolumeData volumes[]; };
layout(std430, set = 0, binding = BINDING_LIGHTS) readonly buffer LightBlock { LightData lights[]; };
layout(std430, set = 0, binding = BINDING_COUNTERS) buffer CounterBlock { FroxelCounters counters; };
layout(std140, set = 0, binding = BINDING_PREVIOUS_FRAME) uniform PreviousFrameBlock { FrameUniforms previousFrame; };
layout(std430, set = 0, binding = BINDING_SHADOW_TRANSMITTANCE) buffer ShadowBlock { vec4 shadowTransmittance[]; };
layout(std430, set = 0, binding = BINDING_LIGHT_CLUSTERS) readonly buffer ClusterBlock { int lightClusters[]; };
layout(std430, set = 0, binding = BINDING_SUN_SHADOW_MAP) readonly buffer SunShadowBlock {
    SunShadowFit sunShadowFit;
    float sunShadowDepth[];
};
layout(std430, set = 0, binding = BINDING_LOCAL_SHADOW_MAPS) readonly buffer LocalShadowBlock { float localShadowDepth[]; };

#ifdef BRUME_FROXEL_IMAGES
layout(set = 0, binding = BINDING_MEDIA_SCATTERING, rgba32f) uniform image3D mediaScatteringG;
layout(set = 0, binding = BINDING_MEDIA_EXTINCTION, rgba32f) uniform image3D mediaExtinction;
layout(set = 0, binding = BINDING_MEDIA_EMISSION, rgba32f) uniform image3D mediaEmission;
layout(set = 0, binding = BINDING_SOURCE, rgba32f) uniform image3D sourceImage;
layout(set = 0, binding = BINDING_INTEGRATED_SCATTERING, rgba32f) uniform image3D integratedScattering;
layout(set = 0, binding = BINDING_INTEGRATED_TRANSMITTANCE, rgba32f) uniform image3D integratedTransmittance;
layout(set = 0, binding = BINDING_SCENE_COLOR, rgba32f) uniform image2D sceneColor;
layout(set = 0, binding = BINDING_SCENE_DEPTH, r32f) uniform image2D sceneDepth;
layout(set = 0, binding = BINDING_OUTPUT, rgba32f) uniform image2D outputImage;
layout(set = 0, binding = BINDING_HISTORY_SOURCE_IN, rgba32f) uniform image3D historySourceIn;
layout(set = 0, binding = BINDING_HISTORY_EXTINCTION_IN, rgba32f) uniform image3D historyExtinctionIn;
layout(set = 0, binding = BINDING_HISTORY_SOURCE_OUT, rgba32f) uniform image3D historySourceOut;
layout(set = 0, binding = BINDING_HISTORY_EXTINCTION_OUT, rgba32f) uniform image3D historyExtinctionOut;
#endif
