#include "animate.h"

#include <algorithm>
#include <array>

namespace brume {
namespace {

namespace st = settings;

// The key of a setting relative to its object: what follows "volumes[...]." or "*.".
std::string_view relativeKey(const Setting& s) {
    const size_t bracket = s.path.find("].");
    if (bracket != std::string_view::npos) return s.path.substr(bracket + 2);
    return s.path.starts_with("*.") ? s.path.substr(2) : s.path;
}

template <class T>
struct Target {
    const Setting* setting;
    unsigned types;             // bit (1 << type) for each type that has the setting
    float* (*field)(T&);        // the first float of the value (a Vec3's x)
};

constexpr unsigned bit(auto type) { return 1u << static_cast<unsigned>(type); }
constexpr unsigned kAllVolumes = ~0u;  // every type's bit, however many types there are
constexpr unsigned kAllLights = 0x7u;
constexpr unsigned kShapes = bit(VolumeType::Box) | bit(VolumeType::Ellipsoid) | bit(VolumeType::Cylinder);
constexpr unsigned kTransformed = kShapes | bit(VolumeType::Vdb) | bit(VolumeType::Mesh);
constexpr unsigned kLocal = bit(LightType::Point) | bit(LightType::Spot);

// Every numeric setting of a volume, save the density texture's scroll (keying a speed would move the
// texture by speed x time, a jump at each key), its exponent (the mean it is measured against is
// computed once, at load) and file names.
const std::array<Target<Volume>, 17> kVolumeTargets = {{
    {&st::volume_edge_fade, kShapes, [](Volume& v) { return &v.edge_fade; }},
    {&st::volume_height_falloff, kShapes | bit(VolumeType::Vdb) | bit(VolumeType::Mesh), [](Volume& v) { return &v.height_falloff; }},
    {&st::volume_base_height, bit(VolumeType::Height), [](Volume& v) { return &v.base_height; }},
    {&st::volume_falloff, bit(VolumeType::Height), [](Volume& v) { return &v.falloff; }},
    {&st::volume_transition_height, bit(VolumeType::Height), [](Volume& v) { return &v.transition_height; }},
    {&st::volume_visibility_distance, bit(VolumeType::Depth), [](Volume& v) { return &v.visibility_distance; }},
    {&st::volume_start_distance, bit(VolumeType::Depth), [](Volume& v) { return &v.start_distance; }},
    {&st::volume_density_scale, bit(VolumeType::Vdb), [](Volume& v) { return &v.density_scale; }},
    {&st::texture_tile_size, kAllVolumes, [](Volume& v) { return v.density_texture ? &v.density_texture->tile_size_m : nullptr; }},
    {&st::texture_strength, kAllVolumes, [](Volume& v) { return v.density_texture ? &v.density_texture->strength : nullptr; }},
    {&st::transform_translation, kTransformed, [](Volume& v) { return &v.transform.translation.x; }},
    {&st::transform_rotation, kTransformed, [](Volume& v) { return &v.transform.rotation_deg.x; }},
    {&st::transform_scale, kTransformed, [](Volume& v) { return &v.transform.scale.x; }},
    {&st::medium_scattering, kAllVolumes, [](Volume& v) { return &v.medium.scattering.x; }},
    {&st::medium_absorption, kAllVolumes, [](Volume& v) { return &v.medium.absorption.x; }},
    {&st::medium_emission, kAllVolumes, [](Volume& v) { return &v.medium.emission.x; }},
    {&st::medium_phase_g, kAllVolumes, [](Volume& v) { return &v.medium.phase_g; }},
}};

const std::array<Target<Light>, 9> kLightTargets = {{
    {&st::light_direction, bit(LightType::Directional) | bit(LightType::Spot), [](Light& l) { return &l.direction.x; }},
    {&st::light_position, kLocal, [](Light& l) { return &l.position.x; }},
    {&st::light_color, kAllLights, [](Light& l) { return &l.color.x; }},
    {&st::light_intensity_directional, bit(LightType::Directional), [](Light& l) { return &l.intensity; }},
    {&st::light_intensity_local, kLocal, [](Light& l) { return &l.intensity; }},
    {&st::light_range, kLocal, [](Light& l) { return &l.range; }},
    {&st::light_fog_scale, kAllLights, [](Light& l) { return &l.fog_scale; }},
    {&st::light_inner_deg, bit(LightType::Spot), [](Light& l) { return &l.inner_deg; }},
    {&st::light_outer_deg, bit(LightType::Spot), [](Light& l) { return &l.outer_deg; }},
}};

template <class T, size_t N>
const Target<T>* find(const std::array<Target<T>, N>& table, unsigned typeBit, std::string_view target) {
    for (const Target<T>& t : table)
        if ((t.types & typeBit) != 0 && relativeKey(*t.setting) == target) return &t;
    return nullptr;
}

template <class T, size_t N>
std::vector<std::string> names(const std::array<Target<T>, N>& table, unsigned typeBit) {
    std::vector<std::string> out;
    for (const Target<T>& t : table)
        if ((t.types & typeBit) != 0) out.emplace_back(relativeKey(*t.setting));
    return out;
}

template <class T, size_t N>
void apply(const std::array<Target<T>, N>& table, unsigned typeBit, T& object, float time) {
    for (const KeyTrack& track : object.keys) {
        const Target<T>* t = find(table, typeBit, track.target);
        if (!t) continue;  // the reader refuses such tracks; a scene built in code may have them
        float* field = t->field(object);
        if (!field) continue;
        const glm::vec3 v = evaluateTrack(track, time);
        const int n = t->setting->kind == SettingKind::Vec3 ? 3 : 1;
        for (int i = 0; i < n; ++i)
            field[i] = static_cast<float>(std::clamp(static_cast<double>(v[i]), t->setting->min, t->setting->max));
    }
}

}  // namespace

const Setting* volumeKeyTarget(VolumeType type, std::string_view target) {
    const Target<Volume>* t = find(kVolumeTargets, bit(type), target);
    return t ? t->setting : nullptr;
}

const Setting* lightKeyTarget(LightType type, std::string_view target) {
    const Target<Light>* t = find(kLightTargets, bit(type), target);
    return t ? t->setting : nullptr;
}

std::vector<std::string> volumeKeyTargets(VolumeType type) { return names(kVolumeTargets, bit(type)); }
std::vector<std::string> lightKeyTargets(LightType type) { return names(kLightTargets, bit(type)); }

void applyKeys(Volume& v, float t) { apply(kVolumeTargets, bit(v.type), v, t); }

void applyKeys(Light& l, float t) {
    if (l.keys.empty()) return;
    const glm::vec3 oldDirection = l.direction;
    apply(kLightTargets, bit(l.type), l, t);
    const float len = glm::length(l.direction);
    l.direction = len > 1.0e-6f ? l.direction / len : oldDirection;
    l.inner_deg = std::min(l.inner_deg, l.outer_deg);
}

bool hasKeys(const Scene& scene) {
    for (const Volume& v : scene.volumes)
        if (!v.keys.empty()) return true;
    for (const Light& l : scene.lights)
        if (!l.keys.empty()) return true;
    return false;
}

Scene bakeKeys(const Scene& scene, float t) {
    Scene s = scene;
    s.time_s = t;
    for (Volume& v : s.volumes) {
        applyKeys(v, t);
        v.keys.clear();
    }
    for (Light& l : s.lights) {
        applyKeys(l, t);
        l.keys.clear();
    }
    return s;
}

}  // namespace brume
