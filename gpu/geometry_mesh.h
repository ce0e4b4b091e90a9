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
    glm::vec4 normal;    // xyz world, unit
    glm::vec4 albedo;
    glm::vec4 emission;
};
static_assert(sizeof(GeometryVertex) == 64);

// Sphere tessellation: the chord of a 128-gon sags by r (1 - cos(pi/128)) = 3e-4 r at silhouettes,
// well under a pixel for any sphere smaller than ~3000 pixels across.
inline constexpr int kSphereSegments = 128;
inline constexpr int kSphereRings = 64;

// Non-indexed triangle list. Planes become a square around the camera large enough to reach the
// camera far in every direction of the frustum (the rasterizer clips them at far, as the CPU's
// ray query does).
std::vector<GeometryVertex> tessellateGeometry(const std::vector<Geometry>& geometry, const shd::FrameUniforms& frame);

}  // namespace brume::gpu
