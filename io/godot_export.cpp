#include "godot_export.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>

#include <glm/gtc/matrix_transform.hpp>

#include "core/compile.h"

namespace brume {
namespace {

// Godot clamps the Environment's volumetric fog anisotropy to this range.
constexpr float kGodotMaxAnisotropy = 0.9f;
// Godot's light ranges stop here (OmniLight3D.omni_range, SpotLight3D.spot_range).
constexpr float kGodotMaxRange = 4096.0f;
// RenderingServer.FogVolumeShape.
constexpr int kShapeEllipsoid = 0;  // Godot's FogVolume shapes: RenderingServer::FogVolumeShape
constexpr int kShapeCylinder = 2;
constexpr int kShapeBox = 3;
constexpr int kShapeWorld = 4;

std::string num(float v) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}

std::string vec3(glm::vec3 v) { return "Vector3(" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + ")"; }
std::string color(glm::vec3 c) { return "Color(" + num(c.r) + ", " + num(c.g) + ", " + num(c.b) + ", 1)"; }

// Godot writes a Transform3D's basis row by row, then the origin.
std::string transform3d(const glm::mat3& basis, glm::vec3 origin) {
    std::string s = "Transform3D(";
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col) s += num(basis[col][row]) + ", ";
    return s + num(origin.x) + ", " + num(origin.y) + ", " + num(origin.z) + ")";
}

// A basis whose -Z is `forward` (Godot's lights and cameras look down their -Z).
glm::mat3 lookBasis(glm::vec3 forward, glm::vec3 up) {
    const glm::vec3 z = -glm::normalize(forward);
    if (glm::length(glm::cross(up, z)) < 1.0e-4f) up = std::abs(z.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 x = glm::normalize(glm::cross(up, z));
    return glm::mat3(x, glm::cross(z, x), z);
}

glm::mat3 rotationOf(const Transform& t) {
    Transform r = t;
    r.translation = glm::vec3(0.0f);
    r.scale = glm::vec3(1.0f);
    return glm::mat3(r.worldFromLocal());
}

std::string quote(const std::string& s) {
    std::string out = "\"";
    for (char c : s) out += c == '"' || c == '\\' ? std::string("\\") + c : std::string(1, c);
    return out + "\"";
}

// Godot node names may not hold . : @ / " %; an empty name gets the kind and index.
std::string nodeName(const std::string& name, const std::string& fallback) {
    std::string out;
    for (char c : name) out += std::string(".:@/\"%").find(c) == std::string::npos ? c : '_';
    return out.empty() ? fallback : out;
}

// Comment lines must stay one line whatever a name holds.
std::string oneLine(std::string s) {
    for (char& c : s)
        if (c == '\n' || c == '\r') c = ' ';
    return s;
}

struct MappedMedium {
    float density;     // mean sigma_t [1/m]
    glm::vec3 albedo;  // sigma_s / sigma_t per channel
};

MappedMedium mapMedium(const Medium& m) {
    const glm::vec3 sigmaT = m.scattering + m.absorption;
    MappedMedium out;
    out.density = (sigmaT.x + sigmaT.y + sigmaT.z) / 3.0f;
    for (int i = 0; i < 3; ++i) out.albedo[i] = sigmaT[i] > 0.0f ? std::min(1.0f, m.scattering[i] / sigmaT[i]) : 0.0f;
    return out;
}

struct Writer {
    std::vector<std::string> losses;
    std::string resources;
    std::string nodes;
    int nextId = 1;

    std::string volumeLabel(const Volume& v, size_t i) const {
        return "volumes[" + std::to_string(i) + "]" + (v.name.empty() ? "" : " \"" + v.name + "\"") + " (" +
               toString(v.type) + ")";
    }

    std::string fogMaterial(const Volume& v, size_t i, float heightFalloff, float densityScale = 1.0f) {
        const MappedMedium m = mapMedium(v.medium);
        const glm::vec3 sigmaT = v.medium.scattering + v.medium.absorption;
        if (std::max({sigmaT.x, sigmaT.y, sigmaT.z}) > 1.01f * std::min({sigmaT.x, sigmaT.y, sigmaT.z}))
            losses.push_back(volumeLabel(v, i) + ": sigma_t differs per channel (" + num(sigmaT.x) + ", " +
                             num(sigmaT.y) + ", " + num(sigmaT.z) +
                             " 1/m) but Godot's density is one number: density = their mean, so the coloured "
                             "transmittance is lost.");
        const std::string id = "FogMaterial_" + std::to_string(nextId++);
        resources += "[sub_resource type=\"FogMaterial\" id=\"" + id + "\"]\n";
        resources += "density = " + num(m.density * densityScale) + "\n";
        resources += "albedo = " + color(m.albedo) + "\n";
        resources += "emission = " + color(v.medium.emission) + "\n";
        resources += "height_falloff = " + num(heightFalloff) + "\n";
        resources += "edge_fade = " + num(isLocalShape(v.type) ? v.edge_fade : 0.0f) + "\n\n";
        return id;
    }

    void fogVolume(const Volume& v, size_t i, int shape, glm::vec3 size, const glm::mat3& basis, glm::vec3 origin,
                   float heightFalloff, float densityScale = 1.0f) {
        const std::string material = fogMaterial(v, i, heightFalloff, densityScale);
        nodes += "[node name=" + quote(nodeName(v.name, "Volume" + std::to_string(i))) +
                 " type=\"FogVolume\" parent=\".\"]\n";
        nodes += "transform = " + transform3d(basis, origin) + "\n";
        nodes += "size = " + vec3(size) + "\n";
        nodes += "shape = " + std::to_string(shape) + "\n";
        nodes += "material = SubResource(\"" + material + "\")\n\n";
    }

    void volume(const Volume& v, size_t i, const Volume* firstDepth) {
        if (v.density_texture)
            losses.push_back(volumeLabel(v, i) + ": its density_texture (" + v.density_texture->file +
                             ") is not exported (the volume renders without it; docs/export.md: Godot would need it baked into a "
                             "Texture3D resource).");
        switch (v.type) {
            case VolumeType::Box:
            case VolumeType::Ellipsoid:
            case VolumeType::Cylinder: {
                const int shape = v.type == VolumeType::Box ? kShapeBox : v.type == VolumeType::Ellipsoid ? kShapeEllipsoid : kShapeCylinder;
                // height_falloff: Brume's exp(-k (y - bottom)) is Godot's min(1, 2^(-k/ln2 (y - centre)))
                // times exp(-k (centre - bottom)): the same above the centre, held at the centre's value below.
                const float k = v.height_falloff;
                const float below = v.transform.translation.y - compileVolume(v).worldMin.y;
                fogVolume(v, i, shape, v.transform.scale, rotationOf(v.transform), v.transform.translation,
                          k / std::numbers::ln2_v<float>, std::exp(-k * below));
                if (k > 0.0f)
                    losses.push_back(volumeLabel(v, i) + ": height_falloff " + num(k) + " 1/m: Godot's FogMaterial "
                                     "holds the density below the volume's centre at the centre's value (approximate).");
                if (v.edge_fade > 0.0f)
                    losses.push_back(volumeLabel(v, i) + ": edge_fade " + num(v.edge_fade) +
                                     " is written as Godot's edge_fade, whose fade curve differs (approximate).");
                break;
            }
            case VolumeType::Height: {
                // Godot: density * min(1, 2^(-height_falloff (y - origin.y))); Brume: min(1, e^(-k (y - base))).
                float k = v.falloff;
                if (v.profile == HeightProfile::Linear) {
                    k = 2.0f / v.transition_height;  // the exponential with the same column density
                    losses.push_back(volumeLabel(v, i) + ": the linear profile (transition_height " +
                                     num(v.transition_height) + " m) is written as the exponential of the same "
                                     "column density, falloff 2/transition_height.");
                }
                fogVolume(v, i, kShapeWorld, glm::vec3(1.0f), glm::mat3(1.0f), glm::vec3(0.0f, v.base_height, 0.0f),
                          k / std::numbers::ln2_v<float>);
                break;
            }
            case VolumeType::Depth:
                if (&v != firstDepth) {
                    losses.push_back(volumeLabel(v, i) + ": Godot has one global fog; only the first depth volume "
                                     "is exported, this one is not.");
                    break;
                }
                losses.push_back(volumeLabel(v, i) + ": Godot's global fog is uniform: the rise over visibility_distance " +
                                 num(v.visibility_distance) + " m is lost (full density from the camera on).");
                if (v.start_distance > 0.0f)
                    losses.push_back(volumeLabel(v, i) + ": start_distance " + num(v.start_distance) +
                                     " m has no Godot equivalent and is lost.");
                break;
            case VolumeType::Vdb:
                losses.push_back(volumeLabel(v, i) + ": Godot has no VDB grids; " + v.file + " is not exported.");
                break;
            case VolumeType::Mesh:
                losses.push_back(volumeLabel(v, i) + ": Godot's FogVolume shapes are analytic; the mesh fog hull " + v.file +
                                 " is not exported.");
                break;
        }
    }

    void light(const Light& l, size_t i) {
        const std::string name = nodeName(l.name, "Light" + std::to_string(i));
        const glm::vec3 c = l.color;
        const float maxC = std::max({c.r, c.g, c.b});
        const glm::vec3 lightColor = maxC > 0.0f ? c / maxC : glm::vec3(1.0f);
        const float energy = l.intensity * maxC;
        const char* type = l.type == LightType::Directional ? "DirectionalLight3D"
                         : l.type == LightType::Point       ? "OmniLight3D"
                                                             : "SpotLight3D";
        nodes += "[node name=" + quote(name) + " type=\"" + type + "\" parent=\".\"]\n";
        const glm::vec3 dir = l.type == LightType::Point ? glm::vec3(0, -1, 0) : l.direction;
        nodes += "transform = " + transform3d(lookBasis(dir, glm::vec3(0, 1, 0)),
                                              l.type == LightType::Directional ? glm::vec3(0.0f) : l.position) + "\n";
        nodes += "light_color = " + color(lightColor) + "\n";
        nodes += "light_energy = " + num(energy) + "\n";
        nodes += "light_volumetric_fog_energy = " + num(l.fog_scale) + "\n";
        nodes += std::string("shadow_enabled = ") + (l.shadows ? "true" : "false") + "\n";
        const std::string label = "lights[" + std::to_string(i) + "]" + (l.name.empty() ? "" : " \"" + l.name + "\"");
        if (l.type != LightType::Directional) {
            const std::string prefix = l.type == LightType::Point ? "omni_" : "spot_";
            float range = l.range > 0.0f ? l.range : kGodotMaxRange;
            if (range > kGodotMaxRange) range = kGodotMaxRange;
            if (l.range == 0.0f || l.range > kGodotMaxRange)
                losses.push_back(label + ": Godot lights need a range of at most 4096 m; written as 4096 m (Brume's is " +
                                 (l.range == 0.0f ? std::string("unlimited") : num(l.range) + " m") + ").");
            nodes += prefix + "range = " + num(range) + "\n";
            nodes += prefix + "attenuation = 2\n";  // inverse square, Brume's falloff
        }
        if (l.type == LightType::Spot) {
            nodes += "spot_angle = " + num(l.outer_deg) + "\n";
            losses.push_back(label + ": Godot's spot cone fades by spot_angle_attenuation, not by Brume's smoothstep from inner_deg " +
                             num(l.inner_deg) + " to outer_deg " + num(l.outer_deg) + " (approximate).");
        }
        nodes += "\n";
    }
};

}  // namespace

GodotExport exportGodot(const FogSource& source) {
    const Scene& s = source.scene;
    Writer w;
    const Volume* firstDepth = nullptr;
    for (const Volume& v : s.volumes)
        if (v.type == VolumeType::Depth && !firstDepth) firstDepth = &v;

    // The phase g is global in Godot: the scattering-weighted mean of the volumes'.
    float gSum = 0.0f, weight = 0.0f;
    for (const Volume& v : s.volumes) {
        const float sigmaS = (v.medium.scattering.x + v.medium.scattering.y + v.medium.scattering.z) / 3.0f;
        gSum += sigmaS * v.medium.phase_g;
        weight += sigmaS;
    }
    const float g = weight > 0.0f ? gSum / weight : 0.0f;
    const float anisotropy = std::clamp(g, -kGodotMaxAnisotropy, kGodotMaxAnisotropy);
    for (size_t i = 0; i < s.volumes.size(); ++i)
        if (std::abs(s.volumes[i].medium.phase_g - anisotropy) > 1.0e-4f)
            w.losses.push_back(w.volumeLabel(s.volumes[i], i) + ": phase_g " + num(s.volumes[i].medium.phase_g) +
                               " is per volume in Brume but global in Godot: volumetric_fog_anisotropy = " + num(anisotropy) +
                               " (the scattering-weighted mean" + (anisotropy != g ? ", clamped to Godot's [-0.9, 0.9]" : "") + ").");
    for (size_t i = 0; i < s.volumes.size(); ++i) w.volume(s.volumes[i], i, firstDepth);
    for (size_t i = 0; i < s.lights.size(); ++i) w.light(s.lights[i], i);

    // Environment: the ambient (sky radiance) and the global fog.
    const float ambientMax = std::max({s.ambient.r, s.ambient.g, s.ambient.b});
    const glm::vec3 ambientColor = ambientMax > 0.0f ? s.ambient / ambientMax : glm::vec3(0.0f);
    std::string env = "[sub_resource type=\"Environment\" id=\"Environment_1\"]\n";
    env += "background_mode = 1\n";
    env += "background_color = " + color(ambientColor) + "\n";
    env += "background_energy_multiplier = " + num(ambientMax) + "\n";
    env += "ambient_light_source = 2\n";
    env += "ambient_light_color = " + color(ambientColor) + "\n";
    env += "ambient_light_energy = " + num(ambientMax) + "\n";
    env += "volumetric_fog_enabled = true\n";
    if (firstDepth) {
        const MappedMedium m = mapMedium(firstDepth->medium);
        env += "volumetric_fog_density = " + num(m.density) + "\n";
        env += "volumetric_fog_albedo = " + color(m.albedo) + "\n";
        env += "volumetric_fog_emission = " + color(firstDepth->medium.emission) + "\n";
    } else {
        env += "volumetric_fog_density = 0\n";
    }
    env += "volumetric_fog_anisotropy = " + num(anisotropy) + "\n";
    env += "volumetric_fog_ambient_inject = 1\n";
    if (!source.isPreset) env += "volumetric_fog_length = " + num(s.camera.far) + "\n";
    env += "\n";

    std::string camera;
    if (!source.isPreset) {
        const Camera& c = s.camera;
        camera = "[node name=\"Camera\" type=\"Camera3D\" parent=\".\"]\n";
        camera += "transform = " + transform3d(lookBasis(c.target - c.position, c.up), c.position) + "\n";
        camera += "fov = " + num(c.fov_y_deg) + "\n";
        camera += "near = " + num(c.near) + "\n";
        camera += "far = " + num(c.far) + "\n\n";
        for (size_t i = 0; i < s.geometry.size(); ++i)
            w.losses.push_back("geometry[" + std::to_string(i) + "]" +
                               (s.geometry[i].name.empty() ? "" : " \"" + s.geometry[i].name + "\"") +
                               ": preview geometry is not exported to Godot (the fog, lights and camera are).");
    }

    GodotExport out;
    out.losses = w.losses;
    std::string& t = out.tscn;
    t = "[gd_scene format=3]\n\n";
    t += "; Exported by brume from " + quote(oneLine(source.name)) + " (docs/export.md).\n";
    for (const std::string& loss : w.losses) t += "; loss: " + oneLine(loss) + "\n";
    t += "\n" + w.resources + env;
    t += "[node name=" + quote(nodeName(source.name, "Fog")) + " type=\"Node3D\"]\n\n";
    t += "[node name=\"WorldEnvironment\" type=\"WorldEnvironment\" parent=\".\"]\n";
    t += "environment = SubResource(\"Environment_1\")\n\n";
    t += w.nodes + camera;
    return out;
}

}  // namespace brume
