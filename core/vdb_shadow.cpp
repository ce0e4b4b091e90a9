#include "vdb_shadow.h"

namespace brume {

// One sample per voxel already resolves the trilinear field's shadow to ~1% of the reference's
// quarter-voxel march on the smoke (docs/shadows.md); ultra halves the step.
int vdbShadowSamplesPerVoxel(Quality q) { return q == Quality::Ultra ? 2 : 1; }

void applyVdbShadowSettings(shd::FrameUniforms& frame, const CompiledScene& cs, const RenderRequest& request) {
    bool anyGrid = false;
    for (const DensityGridPtr& g : cs.grids) anyGrid = anyGrid || g != nullptr;
    frame.vdbShadowSamples = anyGrid && request.vdbShadows ? vdbShadowSamplesPerVoxel(request.quality) : 0;
}

void applyVdbCullingSettings(CompiledScene& cs, const RenderRequest& request) {
    if (request.vdbCulling) return;
    for (shd::VolumeData& v : cs.volumes)
        if (v.kind.x == shd::VOLUME_VDB) v.kind.w = 0;
}

glm::vec3 vdbFogOpticalDepth(const CompiledScene& cs, const shd::FrameUniforms& frame, const shd::LightData& l,
                             glm::vec3 p, glm::vec3 toLight, float distance) {
    if (frame.vdbShadowSamples <= 0 || !shd::fogShadowsLight(l, frame.localFogShadows)) return glm::vec3(0.0f);
    glm::vec3 tau(0.0f);
    for (size_t i = 0; i < cs.volumes.size(); ++i) {
        const shd::VolumeData& v = cs.volumes[i];
        const shd::VdbShadowMarch m = shd::vdbShadowMarch(v, p, toLight, distance, frame.vdbShadowSamples);
        float sum = 0.0f;
        for (int s = 0; s < m.count; ++s) sum += plainVolumeDensity(cs, i, m.start + m.step * static_cast<float>(s));
        tau += shd::vdbShadowOpticalDepth(v, sum, m.stepLength);
    }
    return tau;
}

}  // namespace brume
