#include "render.h"

namespace brume {

RenderRequest requestFromScene(const Scene& scene) {
    RenderRequest r;
    r.width = scene.render.width;
    r.height = scene.render.height;
    r.quality = scene.render.quality;
    return r;
}

}  // namespace brume
