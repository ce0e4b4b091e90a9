// The light-shaft scenes of the shadow tests (test_sun_shadow, test_local_shadow) and of
// bench/shaft_study: a roof of two slabs 4 m up over ground-hugging height fog, lit through the gap
// between the slabs by the sun or by a spot, and seen from under the roof.
#pragma once

#include "test_support.h"

namespace brume::test {

// An axis-aligned box of preview geometry.
inline Geometry slab(glm::vec3 center, glm::vec3 size, float albedo) {
    Geometry g;
    g.type = GeometryType::Box;
    g.transform.translation = center;
    g.transform.scale = size;
    g.albedo = glm::vec3(albedo);
    return g;
}

// Exponential height fog based at the ground, 0.15/m scattering and 0.01/m absorption there.
inline Volume groundHaze() {
    Volume v;
    v.type = VolumeType::Height;
    v.base_height = 0.0f;
    v.falloff = 0.4f;
    v.medium.scattering = glm::vec3(0.15f);
    v.medium.absorption = glm::vec3(0.01f);
    return v;
}

// Two 30 x 12 m slabs with a gap [m] along z between them and a slanted sun through the gap: one
// shaft and one lit strip on the ground.
inline Scene sunShaftScene(float gap = 2.5f) {
    Scene s;
    s.camera.position = {7.0f, 1.5f, 0.0f};
    s.camera.target = {0.0f, 1.2f, 0.0f};
    s.camera.far = 40.0f;
    s.froxels.far = 30.0f;
    s.ambient = glm::vec3(0.03f);
    Light sun = makeLight(LightType::Directional);
    sun.direction = glm::normalize(glm::vec3(0.0f, -1.0f, 0.35f));
    sun.intensity = 3.0f;
    sun.shadows = true;
    s.lights = {sun};
    s.volumes = {groundHaze()};
    const float c = 6.0f + 0.5f * gap;  // slab centres: 12 m wide slabs
    s.geometry = {groundPlane(glm::vec3(0.5f)), slab({0.0f, 4.0f, -c}, {30.0f, 0.4f, 12.0f}, 0.3f),
                  slab({0.0f, 4.0f, c}, {30.0f, 0.4f, 12.0f}, 0.3f)};
    return s;
}

// A spot 6 m up shining down through a 1.5 m gap along x: one shaft under the gap, the rest of the
// cone blocked.
inline Scene spotShaftScene() {
    Scene s = sceneWithTestView();
    s.camera.position = {0.0f, 1.5f, 8.0f};
    s.camera.target = {0.0f, 1.3f, 0.0f};
    s.camera.far = 40.0f;
    s.froxels.far = 30.0f;
    s.ambient = glm::vec3(0.01f);
    Light spot = makeLight(LightType::Spot);
    spot.position = {0.0f, 6.0f, 0.0f};
    spot.direction = {0.0f, -1.0f, 0.0f};
    spot.outer_deg = 40.0f;
    spot.inner_deg = 32.0f;
    spot.intensity = 150.0f;
    spot.shadows = true;
    s.lights = {spot};
    s.volumes = {groundHaze()};
    s.geometry = {groundPlane(glm::vec3(0.5f)), slab({-4.75f, 4.0f, 0.0f}, {8.0f, 0.4f, 12.0f}, 0.4f),
                  slab({4.75f, 4.0f, 0.0f}, {8.0f, 0.4f, 12.0f}, 0.4f)};
    return s;
}

}  // namespace brume::test
