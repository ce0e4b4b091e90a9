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

// The proxy of a sphere (geometry_mesh.h): its vertices carry the centre and radius in `normal`.
void sphereProxy(std::vector<GeometryVertex>& out, const Geometry& g, const shd::FrameUniforms& f) {
    const vec4 sphere(g.center, g.radius);
    const vec4 albedo(g.albedo, 1.0f), emission(g.emission, 0.0f);
    auto triangle = [&](vec3 a, vec3 b, vec3 c) {
        for (const vec3& p : {a, b, c}) out.push_back({vec4(p, 1.0f), sphere, albedo, emission});
    };
    auto quad = [&](vec3 a, vec3 b, vec3 c, vec3 d) { triangle(a, b, c), triangle(a, c, d); };
    const vec3 camera(f.cameraPosition);
    const vec3 axis = g.center - camera;
    const float d = glm::length(axis), r = g.radius;
    // The view rays' smallest cosine to the view direction: that of the frustum's corner rays.
    const float cosCorner = 1.0f / glm::length(vec3(f.projection.x, f.projection.y, 1.0f));
    const float planeDistance = d - r;
    if (d > 1.5f * r && planeDistance * cosCorner > 2.0f * f.projection.z) {
        const vec3 a = axis / d;
        const vec3 u = glm::normalize(glm::cross(a, std::abs(a.y) < 0.9f ? vec3(0, 1, 0) : vec3(1, 0, 0)));
        const vec3 v = glm::cross(a, u);
        // The tangent cone's radius in that plane, plus 1% for rounding; the sphere lies behind the plane.
        const float h = 1.01f * planeDistance * r / std::sqrt((d - r) * (d + r));
        const vec3 c = camera + a * planeDistance;
        quad(c - h * u - h * v, c + h * u - h * v, c + h * u + h * v, c - h * u + h * v);
        return;
    }
    const float h = 1.01f * r;
    auto corner = [&](int k) { return g.center + h * vec3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1); };
    static constexpr int kFaces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
    for (const auto& q : kFaces) quad(corner(q[0]), corner(q[1]), corner(q[2]), corner(q[3]));
}

}  // namespace

GeometryMesh tessellateGeometry(const std::vector<Geometry>& geometry, const shd::FrameUniforms& frame) {
    GeometryMesh mesh;
    std::vector<GeometryVertex>& out = mesh.vertices;
    for (const Geometry& g : geometry) {
        const Emitter e{out, vec4(g.albedo, 1.0f), vec4(g.emission, 0.0f)};
        switch (g.type) {
            case GeometryType::Plane: plane(e, g, frame); break;
            case GeometryType::Box: box(e, g); break;
            case GeometryType::Sphere: break;
        }
    }
    mesh.triangleVertices = static_cast<uint32_t>(out.size());
    for (const Geometry& g : geometry)
        if (g.type == GeometryType::Sphere) sphereProxy(out, g, frame);
    mesh.sphereVertices = static_cast<uint32_t>(out.size()) - mesh.triangleVertices;
    return mesh;
}

}  // namespace brume::gpu
