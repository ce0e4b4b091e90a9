#include "scene_time.h"

namespace brume::editor {

bool sceneScrolls(const Scene& scene) {
    for (const Volume& v : scene.volumes)
        if (v.density_texture && v.density_texture->scroll_mps != glm::vec3(0.0f) && v.density_texture->strength != 0.0f)
            return true;
    return false;
}

}  // namespace brume::editor
