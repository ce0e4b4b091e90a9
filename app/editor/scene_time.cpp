#include "scene_time.h"

#include "core/animate.h"

namespace brume::editor {

bool sceneScrolls(const Scene& scene) {
    if (hasKeys(scene)) return true;
    // An influencer moves along its path, and its wake decays, with the time.
    for (const Influencer& f : scene.influencers)
        if (!f.hidden && f.strength > 0.0f) return true;
    for (const Volume& v : scene.volumes)
        if (v.density_texture && v.density_texture->scroll_mps != glm::vec3(0.0f) && v.density_texture->strength != 0.0f)
            return true;
        else if (v.density_texture && v.density_texture->detail && v.density_texture->detail->scroll_mps != glm::vec3(0.0f) &&
                 v.density_texture->detail->strength != 0.0f)
            return true;
    return false;
}

}  // namespace brume::editor
