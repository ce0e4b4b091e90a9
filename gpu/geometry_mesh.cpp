#include "geometry_mesh.h"

#include <cmath>

namespace brume::gpu {
namespace {

using glm::vec3;
using glm::vec4;

struct Emitter {
    std::vector<GeometryVertex>& out;
    vec4 albedo, emission;
    void vertex(vec3 p, vec3 n) const { out.push_back({vec4(p, 1.0f), vec4(n, 0.0f), albedo, emission}); }
    void quad(vec3 a, vec3 b, vec3 c, vec3 d, vec3 na, vec3 nb, vec3 nc, vec3 nd) const {
        vertex(a, na), vertex(b, nb), vertex(c, nc);
        vertex(a, na), vertex(c, nc), vertex(d, nd);
    }
};

void plane(const Emitter& e, const Geometry& g, const shd::FrameUniforms& f) {
    // Farthest world distance the frustum reaches: the corner ray to the far plane.
    const float reach = f.projection.w * glm::length(vec3(f.projection.x, f.projection.y, 1.0f));
    const float h = 2.0f * reach;
    const vec3 c(f.cameraPosition.x, g.height, f.cameraPosition.z), n(0.0f, 1.0f, 0.0f);
    e.quad(c + vec3(-h, 0, -h), c + vec3(h, 0, -h), c + vec3(h, 0, h), c + vec3(-h, 0, h), n, n, n, n);
}

void box(const Emitter& e, const Geometry& g) {
    const glm::mat4 worldFromLocal = g.transform.worldFromLocal();
    const glm::mat3 normalToWorld = glm::transpose(glm::mat3(g.transform.localFromWorld()));
    auto corner = [&](int x, int y, int z) {
        return vec3(worldFromLocal * vec4(x ? 0.5f : -0.5f, y ? 0.5f : -0.5f, z ? 0.5f : -0.5f, 1.0f));
    };
    for (int axis = 0; axis < 3; ++axis) {
        for (int side = 0; side < 2; ++side) {
            vec3 ln(0.0f);
            ln[axis] = side ? 1.0f : -1.0f;
            const vec3 n = glm::normalize(normalToWorld * ln);
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            vec3 q[4];
            for (int k = 0; k < 4; ++k) {
                int c[3];
                c[axis] = side;
                c[u] = (k == 1 || k == 2) ? 1 : 0;
                c[v] = (k >= 2) ? 1 : 0;
                q[k] = corner(c[0], c[1], c[2]);
            }
            e.quad(q[0], q[1], q[2], q[3], n, n, n, n);
        }
    }
}

void sphere(const Emitter& e, const Geometry& g) {
    auto dir = [](int seg, int ring) {
        const float phi = 2.0f * shd::BRUME_PI * static_cast<float>(seg) / kSphereSegments;
        const float theta = shd::BRUME_PI * static_cast<float>(ring) / kSphereRings;
        return vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
    };
    for (int r = 0; r < kSphereRings; ++r) {
        for (int s = 0; s < kSphereSegments; ++s) {
            const vec3 a = dir(s, r), b = dir(s + 1, r), c = dir(s + 1, r + 1), d = dir(s, r + 1);
            e.quad(g.center + g.radius * a, g.center + g.radius * b, g.center + g.radius * c,
                   g.center + g.radius * d, a, b, c, d);
        }
    }
}

}  // namespace

std::vector<GeometryVertex> tessellateGeometry(const std::vector<Geometry>& geometry, const shd::FrameUniforms& frame) {
    std::vector<GeometryVertex> out;
    for (const Geometry& g : geometry) {
        const Emitter e{out, vec4(g.albedo, 1.0f), vec4(g.emission, 0.0f)};
        switch (g.type) {
            case GeometryType::Plane: plane(e, g, frame); break;
            case GeometryType::Box: box(e, g); break;
            case GeometryType::Sphere: sphere(e, g); break;
        }
    }
    return out;
}

}  // namespace brume::gpu
