// Exact ray queries against the scene's analytic surfaces (planes, boxes, spheres) and their
// Lambert shading. Used by the CPU reference and the CPU froxel renderer for the surfaces behind
// the fog; the GPU rasterizes the same surfaces.
#pragma once

#include <functional>
#include <vector>

#include "compile.h"
#include "scene.h"

namespace brume {

struct Ray {
    glm::vec3 origin;
    glm::vec3 dir;  // unit length
};

struct SurfaceHit {
    float t = shd::BRUME_HUGE;  // distance along the ray [m]
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 1.0f, 0.0f};  // unit, facing the ray origin
    glm::vec3 albedo{0.0f};
    glm::vec3 emission{0.0f};
    int index = -1;  // into Scene::geometry; -1 = missed
    bool hit() const { return index >= 0; }
};

class GeometrySet {
public:
    explicit GeometrySet(const std::vector<Geometry>& geometry);

    // Nearest hit with t in (tMin, tMax).
    SurfaceHit intersect(const Ray& ray, float tMax, float tMin = 0.0f) const;
    // intersect's t and index alone (index -1: none, t then tMax), among the primitives `candidates`
    // (indices, increasing): bit for bit intersect's, when the ray cannot hit the others (the same
    // test per primitive, in the same order), without the hit's position and normal.
    struct Nearest {
        float t;
        int index;
    };
    Nearest nearest(const Ray& ray, float tMax, float tMin, const std::vector<int>& candidates) const;
    // A world-space box [lo, hi] holding every point of primitive `index`; false for a plane
    // (unbounded).
    bool worldBounds(int index, glm::vec3& lo, glm::vec3& hi) const;
    int size() const { return static_cast<int>(prims_.size()); }
    // Whether anything lies between `from` and `from + dir * maxDist` (dir unit).
    bool occluded(glm::vec3 from, glm::vec3 dir, float maxDist) const;
    // Type of primitive `index` (SurfaceHit::index).
    GeometryType type(int index) const { return prims_[static_cast<size_t>(index)].type; }

private:
    float primitiveT(size_t i, const Ray& ray, float tMin, int& boxAxis) const;
    void intersectPrim(size_t i, const Ray& ray, float tMin, SurfaceHit& best) const;

    struct Prim {
        GeometryType type;
        glm::vec3 lo, hi;          // box, sphere: world bounds (worldBounds)
        glm::mat4 localFromWorld;  // box
        glm::mat3 normalToWorld;   // box: inverse transpose of the linear part
        glm::vec3 center;          // sphere
        float radius;              // sphere
        float height;              // plane
        glm::vec3 albedo;
        glm::vec3 emission;
    };
    std::vector<Prim> prims_;
};

// Offset for shadow rays leaving a surface, relative to the point's magnitude so that it holds far
// from the origin.
float surfaceRayOffset(glm::vec3 p);

// Fog transmittance toward a light from a surface point, for renderers that account for it
// (arguments: light index, point, unit direction toward the light, distance to the light).
using LightTransmittanceFn = std::function<glm::vec3(int, glm::vec3, glm::vec3, float)>;

// Outgoing radiance of a Lambertian surface point: albedo/pi x irradiance of each light (occluded by
// geometry for lights with shadows, times `fogTransmittance` when given) + albedo x ambient + emission.
// geometryShadows = false ignores occlusion entirely (the froxel renderers until shadow maps land).
glm::vec3 shadeSurface(const CompiledScene& cs, const GeometrySet& geometry, const SurfaceHit& hit,
                       const LightTransmittanceFn* fogTransmittance = nullptr, bool geometryShadows = true);

}  // namespace brume
