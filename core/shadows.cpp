#include "shadows.h"

#include <cmath>

namespace brume {

bool localLightFogShadows(Quality q) { return q != Quality::Low; }

glm::vec3 lightFogTransmittance(const CompiledScene& cs, const shd::LightData& l, glm::vec3 p, glm::vec3 toLight,
                                float distance, int localLightsToo) {
    if (!shd::fogShadowsLight(l, localLightsToo)) return glm::vec3(1.0f);
    glm::vec3 tau(0.0f);
    for (const shd::VolumeData& v : cs.volumes) tau += shd::shadowOpticalDepth(v, p, toLight, distance);
    return glm::exp(-tau);
}

}  // namespace brume
