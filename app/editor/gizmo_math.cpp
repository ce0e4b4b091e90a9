#include "gizmo_math.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace brume::editor {
namespace {

glm::mat3 rotationOf(glm::vec3 deg) { return glm::mat3(Transform{glm::vec3(0.0f), deg, glm::vec3(1.0f)}.worldFromLocal()); }

glm::mat3 axisRotation(int axis, float deg) {
    glm::vec3 a(0.0f);
    a[axis] = 1.0f;
    return glm::mat3(glm::rotate(glm::mat4(1.0f), glm::radians(deg), a));
}

// `deg` moved by whole turns to lie within half a turn of `near`.
float nearestTurn(float deg, float near) { return deg + 360.0f * std::round((near - deg) / 360.0f); }

// Euler angles of R = Rz * Ry * Rx, of the two solutions the one nearest `near` (so a small turn
// changes the inspector's numbers a little, not by 180 degrees). glm is column-major: m[col][row].
glm::vec3 eulerFrom(const glm::mat3& m, glm::vec3 near) {
    const float sy = std::clamp(-m[0][2], -1.0f, 1.0f);
    glm::vec3 a, b;
    if (std::abs(sy) > 0.99999f) {  // gimbal lock: only x - z (or x + z) is defined; keep x
        const float y = std::copysign(90.0f, sy);
        const float z = glm::degrees(std::atan2(-m[1][0], m[1][1]));
        a = b = glm::vec3(0.0f, y, z);
    } else {
        const float y = glm::degrees(std::asin(sy));
        a = glm::vec3(glm::degrees(std::atan2(m[1][2], m[2][2])), y, glm::degrees(std::atan2(m[0][1], m[0][0])));
        b = glm::vec3(a.x + 180.0f, 180.0f - y, a.z + 180.0f);
    }
    auto fit = [&](glm::vec3 v) {
        for (int i = 0; i < 3; ++i) v[i] = nearestTurn(v[i], near[i]);
        return v;
    };
    a = fit(a), b = fit(b);
    const glm::vec3 da = glm::abs(a - near), db = glm::abs(b - near);
    return da.x + da.y + da.z <= db.x + db.y + db.z ? a : b;
}

}  // namespace

std::optional<float> ringAngle(glm::vec3 center, glm::vec3 axis, glm::vec3 rayOrigin, glm::vec3 rayDir) {
    const float den = glm::dot(rayDir, axis);
    if (std::abs(den) < 0.0175f) return std::nullopt;  // sin(1 degree)
    const float t = glm::dot(center - rayOrigin, axis) / den;
    if (t <= 0.0f) return std::nullopt;
    const glm::vec3 p = rayOrigin + rayDir * t - center;
    // In-plane basis (u, v = axis x u): counter-clockwise about the axis.
    const glm::vec3 helper = std::abs(axis.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    const glm::vec3 u = glm::normalize(helper - axis * glm::dot(helper, axis));
    const glm::vec3 v = glm::cross(axis, u);
    return glm::degrees(std::atan2(glm::dot(p, v), glm::dot(p, u)));
}

float wrapDegrees(float deg) {
    const float w = deg - 360.0f * std::floor((deg + 180.0f) / 360.0f);
    return w == -180.0f ? 180.0f : w;
}

float snapped(float deg, float snap) { return snap > 0.0f ? std::round(deg / snap) * snap : deg; }

glm::vec3 rotateEuler(glm::vec3 rotationDeg, int axis, float angleDeg) {
    if (angleDeg == 0.0f) return rotationDeg;
    return eulerFrom(axisRotation(axis, angleDeg) * rotationOf(rotationDeg), rotationDeg);
}

glm::vec3 rotateDirection(glm::vec3 dir, int axis, float angleDeg) { return axisRotation(axis, angleDeg) * dir; }

glm::vec3 localAxis(glm::vec3 rotationDeg, int axis) { return rotationOf(rotationDeg)[axis]; }

std::optional<float> axisScaleFactor(float s0, float s) {
    if (std::abs(s0) < 1e-6f) return std::nullopt;
    return s / s0;
}

float uniformScaleFactor(float rightPx, float upPx, float handlePx) {
    return std::max(1.0f + (rightPx + upPx) / std::max(handlePx, 1.0f), 1e-3f);
}

glm::vec3 scaleDrag(glm::vec3 start, int axis, float factor, float snap, float minScale) {
    glm::vec3 out = start;
    for (int i = 0; i < 3; ++i) {
        if (axis != 3 && axis != i) continue;
        float v = start[i] * factor;
        if (snap > 0.0f) v = std::round(v / snap) * snap;
        out[i] = std::max(v, minScale);
    }
    return out;
}

std::string rotationPath(const Scene& scene, const std::string& kind, size_t index) {
    const std::string i = "[" + std::to_string(index) + "]";
    if (kind == "volume" && index < scene.volumes.size()) {
        const VolumeType t = scene.volumes[index].type;
        return isLocalShape(t) || t == VolumeType::Vdb || t == VolumeType::Mesh ? "volumes" + i + ".transform.rotation_deg" : "";
    }
    if (kind == "light" && index < scene.lights.size())
        return scene.lights[index].type == LightType::Spot ? "lights" + i + ".direction" : "";
    if (kind == "geometry" && index < scene.geometry.size())
        return scene.geometry[index].type == GeometryType::Box ? "geometry" + i + ".transform.rotation_deg" : "";
    return "";
}

std::string scalePath(const Scene& scene, const std::string& kind, size_t index) {
    const std::string path = rotationPath(scene, kind, index);
    if (path.empty() || kind == "light") return "";
    return path.substr(0, path.rfind('.')) + ".scale";
}

}  // namespace brume::editor
