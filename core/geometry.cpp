#include "geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace brume {

GeometrySet::GeometrySet(const std::vector<Geometry>& geometry) {
    prims_.reserve(geometry.size());
    for (const Geometry& g : geometry) {
        Prim p{};
        p.type = g.type;
        p.albedo = g.albedo;
        p.emission = g.emission;
        p.height = g.height;
        p.center = g.center;
        p.radius = g.radius;
        p.localFromWorld = g.transform.localFromWorld();
        p.normalToWorld = glm::transpose(glm::mat3(p.localFromWorld));
        if (g.type == GeometryType::Sphere) {
            p.lo = g.center - glm::vec3(g.radius);
            p.hi = g.center + glm::vec3(g.radius);
        } else if (g.type == GeometryType::Box) {
            unitCubeWorldBounds(g.transform.worldFromLocal(), p.lo, p.hi);  // the cube intersect() tests
        }
        prims_.push_back(p);
    }
}

// Where the ray meets primitive i past tMin (t <= tMin or NaN: it does not); for a box, the axis of
// the face it meets (boxAxis).
constexpr float kMiss = std::numeric_limits<float>::quiet_NaN();  // fails every t > tMin test

float GeometrySet::primitiveT(size_t i, const Ray& ray, float tMin, int& boxAxis) const {
    const Prim& p = prims_[i];
    if (p.type == GeometryType::Plane) {
        if (ray.dir.y == 0.0f) return kMiss;
        return (p.height - ray.origin.y) / ray.dir.y;
    }
    if (p.type == GeometryType::Sphere) {
        // Solve with the origin moved to the centre; the half-b form avoids cancellation.
        const glm::vec3 oc = ray.origin - p.center;
        const float b = glm::dot(oc, ray.dir);
        const glm::vec3 perp = oc - b * ray.dir;
        const float disc = p.radius * p.radius - glm::dot(perp, perp);
        if (disc < 0.0f) return kMiss;
        const float s = std::sqrt(disc);
        const float t0 = -b - s, t1 = -b + s;
        return t0 > tMin ? t0 : t1;
    }
    // Affine maps keep the ray parameter: intersect the unit cube in local space.
    const glm::vec3 o = glm::vec3(p.localFromWorld * glm::vec4(ray.origin, 1.0f));
    const glm::vec3 d = glm::vec3(p.localFromWorld * glm::vec4(ray.dir, 0.0f));
    float tNear = -shd::BRUME_HUGE, tFar = shd::BRUME_HUGE;
    int axisNear = 0, axisFar = 0;
    bool miss = false;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0f) {
            if (std::abs(o[a]) > 0.5f) miss = true;
            continue;
        }
        float ta = (-0.5f - o[a]) / d[a], tb = (0.5f - o[a]) / d[a];
        if (ta > tb) std::swap(ta, tb);
        if (ta > tNear) { tNear = ta; axisNear = a; }
        if (tb < tFar) { tFar = tb; axisFar = a; }
    }
    if (miss || tNear > tFar) return kMiss;
    boxAxis = tNear > tMin ? axisNear : axisFar;
    return tNear > tMin ? tNear : tFar;
}

// Primitive i's hit, if nearer than best (t in (tMin, best.t)), replaces best.
void GeometrySet::intersectPrim(size_t i, const Ray& ray, float tMin, SurfaceHit& best) const {
    int axis = 0;
    const float t = primitiveT(i, ray, tMin, axis);
    if (!(t > tMin && t < best.t)) return;
    const Prim& p = prims_[i];
    glm::vec3 n(0.0f, 1.0f, 0.0f);  // plane
    if (p.type == GeometryType::Sphere) {
        n = glm::normalize(ray.origin + t * ray.dir - p.center);
    } else if (p.type == GeometryType::Box) {
        const glm::vec3 o = glm::vec3(p.localFromWorld * glm::vec4(ray.origin, 1.0f));
        const glm::vec3 d = glm::vec3(p.localFromWorld * glm::vec4(ray.dir, 0.0f));
        glm::vec3 ln(0.0f);
        ln[axis] = (o[axis] + t * d[axis]) > 0.0f ? 1.0f : -1.0f;
        n = glm::normalize(p.normalToWorld * ln);
    }
    best.t = t;
    best.index = static_cast<int>(i);
    best.position = ray.origin + t * ray.dir;
    best.normal = glm::dot(n, ray.dir) > 0.0f ? -n : n;
    best.albedo = p.albedo;
    best.emission = p.emission;
}

SurfaceHit GeometrySet::intersect(const Ray& ray, float tMax, float tMin) const {
    SurfaceHit best;
    best.t = tMax;
    for (size_t i = 0; i < prims_.size(); ++i) intersectPrim(i, ray, tMin, best);
    if (!best.hit()) best.t = shd::BRUME_HUGE;
    return best;
}

GeometrySet::Nearest GeometrySet::nearest(const Ray& ray, float tMax, float tMin, const std::vector<int>& candidates) const {
    Nearest best{tMax, -1};
    for (const int i : candidates) {
        int axis = 0;
        const float t = primitiveT(static_cast<size_t>(i), ray, tMin, axis);
        if (t > tMin && t < best.t) best = {t, i};
    }
    return best;
}

bool GeometrySet::worldBounds(int index, glm::vec3& lo, glm::vec3& hi) const {
    const Prim& p = prims_[static_cast<size_t>(index)];
    if (p.type == GeometryType::Plane) return false;
    lo = p.lo;
    hi = p.hi;
    return true;
}

bool GeometrySet::occluded(glm::vec3 from, glm::vec3 dir, float maxDist) const {
    return intersect(Ray{from, dir}, maxDist).hit();
}

float surfaceRayOffset(glm::vec3 p) {
    const float m = std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z)));
    // About 16 float ulps of the largest coordinate plus 0.1 mm: enough to leave the surface, yet
    // 0.2 m at 1e5 m from the origin (1e-4 * m lost contact shadows there: 10 m).
    return 1e-4f + 2e-6f * m;
}

glm::vec3 shadeSurface(const CompiledScene& cs, const GeometrySet& geometry, const SurfaceHit& hit,
                       const LightTransmittanceFn* fogTransmittance, bool geometryShadows) {
    glm::vec3 radiance = hit.emission + hit.albedo * cs.ambient;
    const glm::vec3 origin = hit.position + hit.normal * surfaceRayOffset(hit.position);
    for (size_t i = 0; i < cs.lights.size(); ++i) {
        const shd::LightData& l = cs.lights[i];
        const shd::LightSample s = shd::evalLight(l, hit.position);
        glm::vec3 direct = shd::lambert(hit.albedo, hit.normal, s);
        if (direct == glm::vec3(0.0f)) continue;
        if (geometryShadows && shd::lightCastsShadows(l) && geometry.occluded(origin, s.toLight, s.distance)) continue;
        if (fogTransmittance) direct *= (*fogTransmittance)(static_cast<int>(i), origin, s.toLight, s.distance);
        radiance += direct;
    }
    return radiance;
}

}  // namespace brume
