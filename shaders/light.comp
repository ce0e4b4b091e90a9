// Pass 2: source S = sigma_s (lights' in-scattering x fog transmittance toward the light, read from
// the shadow volume pass's output (fog_shadow.glsl froxelFogTransmittance), + ambient)
// + emission (core: lightRow). Froxels with sigma_t = 0 skip lighting and hold S = emission: nothing scatters
// where nothing extinguishes, but a purely emissive medium still glows.
#version 450
#extension GL_GOOGLE_include_directive : require
#define BRUME_FROXEL_IMAGES
#include "resources.glsl"
#include "fog_shadow.glsl"
#include "sun_shadow.glsl"
#include "local_shadow.glsl"

layout(local_size_x = FROXEL_GROUP_X, local_size_y = FROXEL_GROUP_Y, local_size_z = FROXEL_GROUP_Z) in;

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(id, frame.froxelDims.xyz))) return;
    vec3 sigmaT = imageLoad(mediaExtinction, id).rgb;
    if (sigmaT == vec3(0.0f)) {
        imageStore(sourceImage, id, vec4(imageLoad(mediaEmission, id).rgb, 0.0f));
        atomicAdd(counters.skippedFroxels, 1u);
        return;
    }
    atomicAdd(counters.litFroxels, 1u);
    vec4 scatteringG = imageLoad(mediaScatteringG, id);
    vec3 p = worldFromFroxelCoord(vec3(id) + frame.jitter.xyz, frame);
    vec3 viewDir = normalize(p - frame.cameraPosition.xyz);
    vec3 perSigmaS = frame.ambient.rgb;
    ShadowLookup shadow = shadowLookup(id, frame.froxelDims.xyz, frame.shadowReduction);
    float nearest = FROXEL_LIGHT_CLAMP * froxelRadius(id.z, frame);
    // Only the lights of this froxel's cluster (clusters.h), in the CPU's order.
    int record = clusterRecord(id, frame.froxelDims.xyz);
    bool all = lightClusters[record] == CLUSTER_ALL_LIGHTS;
    int count = all ? frame.counts.w : lightClusters[record];
    for (int k = 0; k < count; ++k) {
        int i = all ? k : lightClusters[record + 1 + k];
        LightSample ls = evalLightFroxel(lights[i], p, nearest, frame);
        vec3 inScatter = inScatterPerSigmaS(lights[i], ls, viewDir, scatteringG.a);
        // Outside the range window or the cone, or fog_scale 0: the shadow cannot matter.
        if (inScatter == vec3(0.0f)) continue;
        perSigmaS += inScatter * froxelFogTransmittance(i, shadow, p, ls.toLight, ls.distance) *
                     sunShadowFroxelVisibility(i, p) * localShadowVisibility(i, p);
    }
    vec3 source = scatteringG.rgb * perSigmaS + imageLoad(mediaEmission, id).rgb;
    imageStore(sourceImage, id, vec4(source, 0.0f));
}
