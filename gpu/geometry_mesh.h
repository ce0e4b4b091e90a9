// Triangles for the preview rasterizer from the scene's analytic surfaces (core Scene geometry).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "shaders/shared/brume.h"

namespace brume::gpu {

// Matches the vertex inputs of shaders/geometry.vert (four vec4, 64 bytes).
struct GeometryVertex {
    glm::vec4 position;  // xyz world [m]
    glm::vec4 normal;    // xyz world, unit; a sphere's proxy: xyz its centre [m], w its radius [m]
    glm::vec4 albedo;
    glm::vec4 emission;
};
static_assert(sizeof(GeometryVertex) == 64);

// The geometry pass's vertices: the triangles of planes and boxes first, then one proxy per sphere.
struct GeometryMesh {
    std::vector<GeometryVertex> vertices;
    uint32_t triangleVertices = 0;  // vertices[0, triangleVertices): planes and boxes, exact as triangles
    uint32_t sphereVertices = 0;    // the rest: sphere proxies, ray cast per pixel (geometry.frag BRUME_SPHERE)
    size_t bytes() const { return vertices.size() * sizeof(GeometryVertex); }
};

// Non-indexed triangle lists. Planes become a square around the camera large enough to reach the
// camera far in every direction of the frustum (the rasterizer clips them at far, as the CPU's
// ray query does). Boxes are their 12 triangles.
//
// A sphere is not tessellated: its proxy covers its silhouette and the fragment shader intersects the
// pixel's ray with the sphere itself, as the CPU's ray query does, writing that depth. A tessellated
// sphere (16,384 triangles of a few pixels each) cost lavapipe ~40 ms at any image size: it shades a
// 4x4 block per covered triangle (docs/performance.md, "impostor"). The proxy is a square facing the
// camera, in the plane that touches the sphere's nearest point, sized to the tangent cone (1.3x the
// disc's pixels); close to the camera (that plane nearer than twice the camera near, along the view
// rays), the sphere's bounding cube instead, which also holds for a camera inside the sphere.
GeometryMesh tessellateGeometry(const std::vector<Geometry>& geometry, const shd::FrameUniforms& frame);

}  // namespace brume::gpu
