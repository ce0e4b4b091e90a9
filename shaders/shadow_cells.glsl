// The shadow volume pass's runs (shadow_volume.comp, shadow_volume_vdb.comp): one invocation computes
// SHADOW_RUN cells along z of one listed light's layer, over the cells of the pushed region. The cells
// past `end` (shadowCellEnd, or the region's end) are not computed: no reader reads them this frame.
#include "balanced_groups.glsl"

// The first cell of this invocation's run; the run is [first.z, min(first.z + SHADOW_RUN, end)).
ivec3 shadowRunFirst() {
    // Workgroups interleaved between lavapipe's threads (balanced_groups.glsl): where the runs stop at
    // the columns' ends, the deep ones cost little.
    uvec3 id = balancedGlobalID();
    return ivec3(id.xy, int(id.z) * SHADOW_RUN) + region.lo.xyz;
}
