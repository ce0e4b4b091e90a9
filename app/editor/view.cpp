#include "view.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

#include "core/density_grid.h"
#include "core/compile.h"

namespace brume::editor {
namespace {

template <class T>
void dropHidden(std::vector<T>& list) {
    std::erase_if(list, [](const T& x) { return x.hidden; });
}

struct Axes {
    glm::vec3 forward, right, up;
};

Axes axesOf(const Camera& c) {
    const glm::vec3 forward = glm::normalize(c.target - c.position);
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::normalize(c.up)));
    return {forward, right, glm::cross(right, forward)};
}

// A box in its own space [lo, hi] placed by worldFromBox: where the box's extent comes from.
struct PlacedBox {
    glm::mat4 worldFromBox;
    glm::vec3 lo, hi;
};

std::optional<PlacedBox> placedBox(const Volume& v) {
    const glm::mat4 world = v.transform.worldFromLocal();
    if (isLocalShape(v.type)) return PlacedBox{world, glm::vec3(-0.5f), glm::vec3(0.5f)};
    if ((v.type == VolumeType::Vdb || v.type == VolumeType::Mesh) && v.density && !v.density->empty())
        return PlacedBox{world * v.density->gridFromIndex(), v.density->indexMin(), v.density->indexMax()};
    return std::nullopt;  // height and depth fog fill the world; an unloaded vdb is empty
}

// Ray parameter where the ray enters (or starts inside) the box, slab test in the box's space
// (an affine map keeps the ray parameter); nothing when it misses or the box is behind.
std::optional<float> enterBox(const PlacedBox& b, glm::vec3 origin, glm::vec3 dir) {
    const glm::mat4 boxFromWorld = glm::inverse(b.worldFromBox);
    const glm::vec3 o = glm::vec3(boxFromWorld * glm::vec4(origin, 1.0f));
    const glm::vec3 d = glm::vec3(boxFromWorld * glm::vec4(dir, 0.0f));
    float t0 = 0.0f, t1 = std::numeric_limits<float>::max();
    for (int a = 0; a < 3; ++a) {
        if (std::abs(d[a]) < 1e-12f) {
            if (o[a] < b.lo[a] || o[a] > b.hi[a]) return std::nullopt;
            continue;
        }
        float ta = (b.lo[a] - o[a]) / d[a], tb = (b.hi[a] - o[a]) / d[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
        if (t0 > t1) return std::nullopt;
    }
    return t0;
}

// Where the ray enters a volume: an ellipsoid or a cylinder by its own surface (the interval the
// renderers' fog shadows use), anything else by its box.
std::optional<float> enterVolume(const Volume& vol, const PlacedBox& b, glm::vec3 origin, glm::vec3 dir) {
    if (vol.type != VolumeType::Ellipsoid && vol.type != VolumeType::Cylinder) return enterBox(b, origin, dir);
    const glm::mat4 localFromWorld = glm::inverse(b.worldFromBox);
    const glm::vec3 o = glm::vec3(localFromWorld * glm::vec4(origin, 1.0f));
    const glm::vec3 d = glm::vec3(localFromWorld * glm::vec4(dir, 0.0f));
    const int shape = vol.type == VolumeType::Ellipsoid ? shd::SHAPE_ELLIPSOID : shd::SHAPE_CYLINDER;
    const glm::vec2 in = shd::shapeInterval(shape, o, d, 0.5f);
    if (!(in.y >= std::max(in.x, 0.0f))) return std::nullopt;
    return std::max(in.x, 0.0f);
}

}  // namespace

std::vector<std::array<glm::vec3, 2>> volumeWireframe(const Volume& v) {
    std::vector<std::array<glm::vec3, 2>> lines;
    if (!isLocalShape(v.type)) return lines;
    const glm::mat4 world = v.transform.worldFromLocal();
    auto add = [&](glm::vec3 a, glm::vec3 b) {
        lines.push_back({glm::vec3(world * glm::vec4(a, 1.0f)), glm::vec3(world * glm::vec4(b, 1.0f))});
    };
    constexpr int kSegments = 48;
    // A circle of radius 0.5 in the plane of local axes (a, b), at c along the third axis.
    auto circle = [&](int a, int b, glm::vec3 centre) {
        for (int i = 0; i < kSegments; ++i) {
            glm::vec3 p = centre, q = centre;
            const float t0 = 6.2831853f * float(i) / kSegments, t1 = 6.2831853f * float(i + 1) / kSegments;
            p[a] += 0.5f * std::cos(t0), p[b] += 0.5f * std::sin(t0);
            q[a] += 0.5f * std::cos(t1), q[b] += 0.5f * std::sin(t1);
            add(p, q);
        }
    };
    if (v.type == VolumeType::Ellipsoid) {
        circle(0, 1, glm::vec3(0.0f)), circle(1, 2, glm::vec3(0.0f)), circle(0, 2, glm::vec3(0.0f));
    } else if (v.type == VolumeType::Cylinder) {
        circle(0, 2, glm::vec3(0.0f, -0.5f, 0.0f)), circle(0, 2, glm::vec3(0.0f, 0.5f, 0.0f));
        for (const glm::vec2 xz : {glm::vec2(0.5f, 0.0f), glm::vec2(-0.5f, 0.0f), glm::vec2(0.0f, 0.5f), glm::vec2(0.0f, -0.5f)})
            add(glm::vec3(xz.x, -0.5f, xz.y), glm::vec3(xz.x, 0.5f, xz.y));
    } else {
        for (int axis = 0; axis < 3; ++axis)
            for (int k = 0; k < 4; ++k) {
                glm::vec3 a(0.0f);
                a[(axis + 1) % 3] = (k & 1) ? 0.5f : -0.5f;
                a[(axis + 2) % 3] = (k & 2) ? 0.5f : -0.5f;
                glm::vec3 b = a;
                a[axis] = -0.5f, b[axis] = 0.5f;
                add(a, b);
            }
    }
    return lines;
}

Scene visibleScene(const Scene& scene) {
    Scene s = scene;
    dropHidden(s.volumes);
    dropHidden(s.lights);
    dropHidden(s.geometry);
    dropHidden(s.influencers);
    return s;
}

namespace {

// Whether a and b specialize pipelines alike: the same kind, and for the box kinds the same shape and
// whether a height falloff (gpu: SPEC_VOLUME_LIST, SPEC_SHAPE_LIST).
bool sameKind(const Volume& a, const Volume& b) {
    if (a.type != b.type) return false;
    if (a.type == VolumeType::Height) return a.profile == b.profile;
    if (isLocalShape(a.type)) return (a.height_falloff > 0.0f) == (b.height_falloff > 0.0f);
    return true;
}

}  // namespace

std::optional<Scene> withStandIns(const Scene& shown, const std::vector<Volume>& before) {
    if (shown.volumes.size() >= before.size()) return std::nullopt;  // nothing missing
    Scene s = shown;
    s.volumes.clear();
    size_t next = 0;  // shown's next volume
    for (const Volume& was : before) {
        if (next < shown.volumes.size() && sameKind(shown.volumes[next], was)) {
            s.volumes.push_back(shown.volumes[next++]);
            continue;
        }
        Volume dark = was;
        dark.medium.scattering = dark.medium.absorption = dark.medium.emission = glm::vec3(0.0f);
        dark.keys.clear();  // a keyed medium would light it again
        dark.hidden = false;
        s.volumes.push_back(std::move(dark));
    }
    if (next < shown.volumes.size()) return std::nullopt;
    return s;
}

Scene withoutViewState(Scene scene) {
    for (Volume& v : scene.volumes) v.hidden = false;
    for (Light& l : scene.lights) l.hidden = false;
    for (Geometry& g : scene.geometry) g.hidden = false;
    for (Influencer& f : scene.influencers) f.hidden = false;
    return scene;
}

Camera flyCamera(const Camera& c, glm::vec3 move) {
    const Axes a = axesOf(c);
    const glm::vec3 d = a.right * move.x + a.up * move.y + a.forward * move.z;
    Camera out = c;
    out.position += d;
    out.target += d;
    return out;
}

Camera lookCamera(const Camera& c, float yawDeg, float pitchDeg) {
    const glm::vec3 up = glm::normalize(c.up);
    glm::vec3 offset = c.target - c.position;
    offset = glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(yawDeg), up) * glm::vec4(offset, 0.0f));
    const float elevation = std::asin(std::clamp(glm::dot(glm::normalize(offset), up), -1.0f, 1.0f));
    const float limit = glm::radians(89.0f);
    const float pitch = std::clamp(elevation + glm::radians(pitchDeg), -limit, limit) - elevation;
    const glm::vec3 r = glm::normalize(glm::cross(offset, up));
    Camera out = c;
    out.target = c.position + glm::vec3(glm::rotate(glm::mat4(1.0f), pitch, r) * glm::vec4(offset, 0.0f));
    return out;
}

Result<Bounds> objectBounds(const Scene& scene, const std::string& kind, size_t index) {
    auto outOfRange = [&](size_t n) {
        return Error{"There is no " + kind + " " + std::to_string(index) + " (the list has " + std::to_string(n) + ")."};
    };
    auto ofBox = [](const PlacedBox& b) {
        const glm::vec3 lo = glm::vec3(b.worldFromBox * glm::vec4(b.lo, 1.0f));
        const glm::vec3 hi = glm::vec3(b.worldFromBox * glm::vec4(b.hi, 1.0f));
        return Bounds{(lo + hi) * 0.5f, std::max(0.5f * glm::length(hi - lo), 1e-3f)};
    };
    if (kind == "volume") {
        if (index >= scene.volumes.size()) return outOfRange(scene.volumes.size());
        if (std::optional<PlacedBox> b = placedBox(scene.volumes[index])) return ofBox(*b);
        return Error{"This volume fills the world (or its grid is empty): there is nothing to frame."};
    }
    if (kind == "light") {
        if (index >= scene.lights.size()) return outOfRange(scene.lights.size());
        const Light& l = scene.lights[index];
        if (l.type == LightType::Directional) return Error{"A directional light has no position to frame."};
        return Bounds{l.position, 1.0f};
    }
    if (kind == "geometry") {
        if (index >= scene.geometry.size()) return outOfRange(scene.geometry.size());
        const Geometry& g = scene.geometry[index];
        if (g.type == GeometryType::Sphere) return Bounds{g.center, g.radius};
        if (g.type == GeometryType::Box) return ofBox({g.transform.worldFromLocal(), glm::vec3(-0.5f), glm::vec3(0.5f)});
        return Error{"A plane is infinite: there is nothing to frame."};
    }
    return Error{"\"" + kind + "\" is not a kind of object: use volume, light or geometry."};
}

Camera frameCamera(const Camera& c, Bounds b) {
    const glm::vec3 forward = glm::normalize(c.target - c.position);
    const float halfFov = glm::radians(std::clamp(c.fov_y_deg, 1.0f, 179.0f)) * 0.5f;
    const float dist = std::max(1.2f * b.radius / std::sin(halfFov), 2.0f * c.near);
    Camera out = c;
    out.target = b.center;
    out.position = b.center - forward * dist;
    return out;
}

std::optional<Picked> pick(const Scene& scene, float aspect, float u, float v) {
    const Camera& c = scene.camera;
    const Axes a = axesOf(c);
    const float tanY = std::tan(glm::radians(c.fov_y_deg) * 0.5f);
    const glm::vec3 dir = rayDirection(c, aspect, u, v);
    std::optional<Picked> best;
    float bestT = std::numeric_limits<float>::max();
    for (size_t i = 0; i < scene.volumes.size(); ++i) {
        if (scene.volumes[i].hidden) continue;
        const std::optional<PlacedBox> b = placedBox(scene.volumes[i]);
        const std::optional<float> t = b ? enterVolume(scene.volumes[i], *b, c.position, dir) : std::nullopt;
        if (t && *t < bestT) bestT = *t, best = Picked{"volume", i};
    }
    // A light is a point: hit when the ray passes within 2% of the view height at its depth. A hit
    // light wins over volumes, since lights usually sit inside the fog they light.
    std::optional<Picked> light;
    float lightT = std::numeric_limits<float>::max();
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& l = scene.lights[i];
        if (l.hidden || l.type == LightType::Directional) continue;
        const float t = glm::dot(l.position - c.position, dir);
        if (t <= 0.0f || t >= lightT) continue;
        const float miss = glm::length(c.position + dir * t - l.position);
        const float tolerance = 0.02f * 2.0f * tanY * glm::dot(l.position - c.position, a.forward);
        if (miss <= tolerance) lightT = t, light = Picked{"light", i};
    }
    if (light) return light;
    return best;
}

glm::vec3 rayDirection(const Camera& c, float aspect, float u, float v) {
    const Axes a = axesOf(c);
    const float tanY = std::tan(glm::radians(c.fov_y_deg) * 0.5f);
    const float ndcX = 2.0f * u - 1.0f, ndcY = 1.0f - 2.0f * v;
    return glm::normalize(a.forward + a.right * (ndcX * tanY * aspect) + a.up * (ndcY * tanY));
}

std::optional<glm::vec2> windowFromWorld(const Camera& c, float aspect, glm::vec3 p) {
    const Axes a = axesOf(c);
    const glm::vec3 d = p - c.position;
    const float z = glm::dot(d, a.forward);
    if (z <= 1e-4f) return std::nullopt;
    const float tanY = std::tan(glm::radians(c.fov_y_deg) * 0.5f);
    const float ndcX = glm::dot(d, a.right) / (z * tanY * aspect), ndcY = glm::dot(d, a.up) / (z * tanY);
    return glm::vec2(0.5f * (ndcX + 1.0f), 0.5f * (1.0f - ndcY));
}

std::optional<float> axisParam(glm::vec3 origin, glm::vec3 axis, glm::vec3 rayOrigin, glm::vec3 rayDir) {
    // Closest points of two lines: solve for s on the axis and t on the ray (both unit length).
    const glm::vec3 w = origin - rayOrigin;
    const float b = glm::dot(axis, rayDir), d = glm::dot(axis, w), e = glm::dot(rayDir, w);
    const float den = 1.0f - b * b;
    if (den < 1e-4f) return std::nullopt;  // within ~0.6 degrees of parallel
    return (b * e - d) / den;
}

glm::vec3 axisDrag(glm::vec3 start, glm::vec3 axis, float s0, float s, float snap) {
    float move = s - s0;
    if (snap > 0.0f) move = std::round(move / snap) * snap;
    return start + axis * move;
}

std::string positionPath(const Scene& scene, const std::string& kind, size_t index) {
    const std::string i = "[" + std::to_string(index) + "]";
    if (kind == "volume" && index < scene.volumes.size()) {
        const VolumeType t = scene.volumes[index].type;
        return isLocalShape(t) || t == VolumeType::Vdb || t == VolumeType::Mesh ? "volumes" + i + ".transform.translation" : "";
    }
    if (kind == "light" && index < scene.lights.size())
        return scene.lights[index].type == LightType::Directional ? "" : "lights" + i + ".position";
    if (kind == "geometry" && index < scene.geometry.size()) {
        const GeometryType t = scene.geometry[index].type;
        return t == GeometryType::Box ? "geometry" + i + ".transform.translation"
             : t == GeometryType::Sphere ? "geometry" + i + ".center" : "";
    }
    return "";
}

}  // namespace brume::editor
