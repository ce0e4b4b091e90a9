#include "scene.h"

#include <glm/gtc/matrix_transform.hpp>

namespace brume {

glm::mat4 Transform::worldFromLocal() const {
    const glm::vec3 r = glm::radians(rotation_deg);
    glm::mat4 m = glm::translate(glm::mat4(1.0f), translation);
    m = glm::rotate(m, r.z, glm::vec3(0, 0, 1));
    m = glm::rotate(m, r.y, glm::vec3(0, 1, 0));
    m = glm::rotate(m, r.x, glm::vec3(1, 0, 0));
    return glm::scale(m, scale);
}

glm::mat4 Transform::localFromWorld() const { return glm::inverse(worldFromLocal()); }

glm::mat4 Camera::viewFromWorld() const { return glm::lookAt(position, target, up); }

Light makeLight(LightType type) {
    Light l;
    l.type = type;
    const bool local = type != LightType::Directional;
    l.intensity = local ? settings::light_intensity_local.f() : settings::light_intensity_directional.f();
    l.shadows = local ? settings::light_shadows_local.b() : settings::light_shadows_directional.b();
    if (type == LightType::Spot) l.direction = glm::vec3(0, -1, 0);
    if (type == LightType::Directional) l.direction = glm::normalize(l.direction);
    return l;
}

TextureLayer makeDetailLayer() {
    TextureLayer d;
    d.tile_size_m = settings::detail_tile_size.f();
    d.scroll_mps = vec3Default(settings::detail_scroll);
    d.strength = settings::detail_strength.f();
    d.exponent = settings::detail_exponent.f();
    return d;
}

const char* toString(Quality q) {
    switch (q) {
        case Quality::Low: return "low";
        case Quality::Medium: return "medium";
        case Quality::High: return "high";
        case Quality::Ultra: return "ultra";
    }
    return "?";
}
const char* toString(LightType t) {
    switch (t) {
        case LightType::Directional: return "directional";
        case LightType::Point: return "point";
        case LightType::Spot: return "spot";
    }
    return "?";
}
const char* toString(VolumeType t) {
    switch (t) {
        case VolumeType::Box: return "box";
        case VolumeType::Ellipsoid: return "ellipsoid";
        case VolumeType::Cylinder: return "cylinder";
        case VolumeType::Height: return "height";
        case VolumeType::Depth: return "depth";
        case VolumeType::Vdb: return "vdb";
        case VolumeType::Mesh: return "mesh";
    }
    return "?";
}
const char* toString(HeightProfile p) { return p == HeightProfile::Exponential ? "exponential" : "linear"; }
const char* toString(InfluencerType t) { return t == InfluencerType::Sphere ? "sphere" : "capsule"; }
const char* toString(GeometryType t) {
    switch (t) {
        case GeometryType::Plane: return "plane";
        case GeometryType::Box: return "box";
        case GeometryType::Sphere: return "sphere";
    }
    return "?";
}

}  // namespace brume
