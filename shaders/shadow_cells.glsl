// The shadow volume pass's runs (shadow_volume.comp, shadow_volume_vdb.comp): one invocation computes
// SHADOW_RUN cells along z of one listed light's layer, over the cells of the pushed region. The cells
// past `end` (shadowCellEnd, or the region's end) are not computed: no reader reads them this frame.
// Include after fog_shadow.glsl and the push constants (region).
#include "balanced_groups.glsl"

// Where a cell's shadow ray starts, and the light's sample there.
struct ShadowCellRay {
    vec3 p;
    LightSample ls;
};

// Writes cell `cell` of light l's analytic layer (region.lo.w: the light's index): the fog
// transmittance toward l from the cell's sample point (its froxel's, jittered). Returns the ray, which
// the vdb variant marches its grids along.
ShadowCellRay writeAnalyticShadowCell(LightData l, FogVolumes volumes, ivec3 cells, ivec3 cell) {
    ShadowCellRay r;
    ivec3 froxel = shadowCellFroxel(cell, frame.froxelDims.xyz, frame.shadowReduction);
    r.p = worldFromFroxelCoord(vec3(froxel) + frame.jitter.xyz, frame);
    r.ls = evalLight(l, r.p);
    shadowTransmittance[shadowVolumeIndex(cells, region.lo.w, cell)] =
        vec4(lightFogTransmittance(volumes, l, r.p, r.ls.toLight, r.ls.distance), 0.0f);
    return r;
}

// The first cell of this invocation's run; the run is [first.z, min(first.z + SHADOW_RUN, end)).
ivec3 shadowRunFirst() {
    // Workgroups interleaved between lavapipe's threads (balanced_groups.glsl): where the runs stop at
    // the columns' ends, the deep ones cost little.
    uvec3 id = balancedGlobalID();
    return ivec3(id.xy, int(id.z) * SHADOW_RUN) + region.lo.xyz;
}
