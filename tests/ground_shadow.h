// The check both froxel renderers' tests make of the dense block's shadow on the ground
// (FogShadowDenseBlock's scene: a 3 x 1 x 3 m block of dense fog centred over the origin, a sun
// straight down, no ambient): the ground beneath its core is black, the ground beside it sunlit.
#pragma once

#include <gtest/gtest.h>

#include <cmath>

#include "core/geometry.h"
#include "core/image.h"
#include "core/scene.h"
#include "shaders/shared/froxel.h"

namespace brume::test {

// Every ground pixel of img within 1.4 m of the block's axis in x and z (10 cm inside its sides)
// gets no sun (< 1e-6), every one past 1.6 m some (> 0.1), and there are enough of each to mean it.
inline void expectNoSunBeneathTheBlock(const Image& img, const Scene& s, const shd::FrameUniforms& f) {
    const GeometrySet geometry(s.geometry);
    int dark = 0, sunlit = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const glm::vec3 viewRay = shd::viewRayFromPixel(glm::vec2(x, y) + glm::vec2(0.5f), f);
            const glm::vec3 dir = glm::normalize(glm::vec3(f.worldFromView * glm::vec4(viewRay, 0.0f)));
            const SurfaceHit hit = geometry.intersect(Ray{s.camera.position, dir}, 30.0f);  // inside camera.far
            if (!hit.hit()) continue;
            const glm::vec3 q = hit.position;
            if (std::abs(q.x) < 1.4f && std::abs(q.z) < 1.4f) {
                ++dark;
                EXPECT_LT(img.at(x, y).x, 1e-6f) << "sun leaked onto the ground at pixel " << x << "," << y;
            } else if (std::abs(q.x) > 1.6f || std::abs(q.z) > 1.6f) {
                ++sunlit;
                EXPECT_GT(img.at(x, y).x, 0.1f) << "no sun on the ground at pixel " << x << "," << y;
            }
        }
    EXPECT_GT(dark, 30);
    EXPECT_GT(sunlit, 50);
}

}  // namespace brume::test
