// Ray queries against planes, rotated/scaled boxes and spheres, checked against hand-computed hits.
#include <gtest/gtest.h>

#include <cmath>

#include "core/geometry.h"

namespace brume {
namespace {

constexpr float kS = 0.70710678f;  // sin 45 deg

Geometry plane(float height) {
    Geometry g;
    g.type = GeometryType::Plane;
    g.height = height;
    return g;
}

Geometry sphere(glm::vec3 c, float r) {
    Geometry g;
    g.type = GeometryType::Sphere;
    g.center = c;
    g.radius = r;
    return g;
}

Geometry box(glm::vec3 t, glm::vec3 rotDeg, glm::vec3 scale) {
    Geometry g;
    g.type = GeometryType::Box;
    g.transform.translation = t;
    g.transform.rotation_deg = rotDeg;
    g.transform.scale = scale;
    return g;
}

void expectVec(glm::vec3 got, glm::vec3 want, float tol = 1e-5f) {
    EXPECT_NEAR(got.x, want.x, tol);
    EXPECT_NEAR(got.y, want.y, tol);
    EXPECT_NEAR(got.z, want.z, tol);
}

TEST(Geometry, PlaneHitFromAboveBelowAndObliquely) {
    const GeometrySet above({plane(0.0f)});
    SurfaceHit h = above.intersect({{0, 5, 0}, {0, -1, 0}}, 100.0f);
    ASSERT_TRUE(h.hit());
    EXPECT_NEAR(h.t, 5.0f, 1e-6f);
    expectVec(h.normal, {0, 1, 0});

    const GeometrySet raised({plane(1.0f)});
    h = raised.intersect({{0, -3, 0}, {0, 1, 0}}, 100.0f);
    ASSERT_TRUE(h.hit());
    EXPECT_NEAR(h.t, 4.0f, 1e-6f);
    expectVec(h.normal, {0, -1, 0});  // faces the ray origin below the plane

    const GeometrySet half({plane(0.5f)});
    h = half.intersect({{1, 2, 3}, glm::normalize(glm::vec3(1, -1, 0))}, 100.0f);
    ASSERT_TRUE(h.hit());
    EXPECT_NEAR(h.t, 1.5f * std::sqrt(2.0f), 1e-5f);
    expectVec(h.position, {2.5f, 0.5f, 3.0f});

    EXPECT_FALSE(half.intersect({{0, 2, 0}, {1, 0, 0}}, 100.0f).hit());  // parallel
    EXPECT_FALSE(half.intersect({{0, 2, 0}, {0, 1, 0}}, 100.0f).hit());  // pointing away
}

TEST(Geometry, SphereHitOutsideAndInside) {
    const GeometrySet s({sphere({1, 2, 3}, 2.0f)});
    SurfaceHit h = s.intersect({{1, 2, -5}, {0, 0, 1}}, 100.0f);
    ASSERT_TRUE(h.hit());
    EXPECT_NEAR(h.t, 6.0f, 1e-5f);
    expectVec(h.position, {1, 2, 1});
    expectVec(h.normal, {0, 0, -1});

    h = s.intersect({{1, 2, 3}, {0, 1, 0}}, 100.0f);  // from the centre
    ASSERT_TRUE(h.hit());
    EXPECT_NEAR(h.t, 2.0f, 1e-5f);
    expectVec(h.normal, {0, -1, 0});  // inside: faces back toward the origin

    // Off-centre chord: x = 1 + 1.2 from the axis -> half chord sqrt(4 - 1.44) = 1.6.
    h = s.intersect({{2.2f, 2, -5}, {0, 0, 1}}, 100.0f);
    ASSERT_TRUE(h.hit());
    EXPECT_NEAR(h.t, 8.0f - 1.6f, 1e-5f);
    expectVec(h.normal, glm::vec3(1.2f, 0.0f, -1.6f) / 2.0f);
}

TEST(Geometry, TMinAndTMaxSelectTheHit) {
    const GeometrySet s({sphere({0, 0, 0}, 2.0f)});
    const Ray r{{0, 0, -8}, {0, 0, 1}};
    EXPECT_NEAR(s.intersect(r, 100.0f).t, 6.0f, 1e-5f);
    EXPECT_NEAR(s.intersect(r, 100.0f, 7.0f).t, 10.0f, 1e-5f);  // the far side
    const SurfaceHit miss = s.intersect(r, 5.0f);
    EXPECT_FALSE(miss.hit());
    EXPECT_EQ(miss.t, shd::BRUME_HUGE);
}

// Box rotated 45 deg about Z, scaled (2, 1, 1), centred at (2, 0, 0). In local coordinates a ray
// x = 2, y = t - 5 has q.x = (t - 5) / (2 sqrt 2), q.y = (t - 5) / sqrt 2: it enters through the
// local -y face at t = 5 - sqrt(2)/2, whose world normal is R (0, -1, 0) = (s, -s, 0).
TEST(Geometry, RotatedScaledBoxFromOutsideAndInside) {
    const GeometrySet b({box({2, 0, 0}, {0, 0, 45}, {2, 1, 1})});
    SurfaceHit h = b.intersect({{2, -5, 0}, {0, 1, 0}}, 100.0f);
    ASSERT_TRUE(h.hit());
    EXPECT_NEAR(h.t, 5.0f - kS, 1e-5f);
    expectVec(h.normal, {kS, -kS, 0});

    // From the centre along +x: q.y = -t / sqrt 2 reaches -0.5 at t = sqrt(2)/2; the outward normal
    // (s, -s, 0) is flipped to face the origin inside the box.
    h = b.intersect({{2, 0, 0}, {1, 0, 0}}, 100.0f);
    ASSERT_TRUE(h.hit());
    EXPECT_NEAR(h.t, kS, 1e-5f);
    expectVec(h.normal, {-kS, kS, 0});

    // Along the long axis: the local x extent is +-1 (scale 2), i.e. 1 in world along (s, s, 0).
    h = b.intersect({{2 - 5 * kS, -5 * kS, 0}, {kS, kS, 0}}, 100.0f);
    ASSERT_TRUE(h.hit());
    EXPECT_NEAR(h.t, 4.0f, 1e-5f);
    expectVec(h.normal, {-kS, -kS, 0});

    EXPECT_FALSE(b.intersect({{2, -5, 0.6f}, {0, 1, 0}}, 100.0f).hit());  // passes above the z face
}

TEST(Geometry, NearestOfSeveralAndItsMaterial) {
    Geometry far = sphere({0, 0, -10}, 1.0f), near = box({0, 0, -4}, {0, 0, 0}, {1, 1, 1});
    near.albedo = {0.1f, 0.2f, 0.3f};
    near.emission = {4, 5, 6};
    const GeometrySet set({far, near, plane(-5.0f)});
    const SurfaceHit h = set.intersect({{0, 0, 0}, {0, 0, -1}}, 100.0f);
    ASSERT_TRUE(h.hit());
    EXPECT_EQ(h.index, 1);
    EXPECT_NEAR(h.t, 3.5f, 1e-5f);
    expectVec(h.albedo, near.albedo);
    expectVec(h.emission, near.emission);
}

TEST(Geometry, OccludedRespectsDistance) {
    const GeometrySet set({plane(0.0f), sphere({0, 5, 0}, 1.0f)});
    EXPECT_FALSE(set.occluded({0, 2, 0}, {0, -1, 0}, 1.5f));
    EXPECT_TRUE(set.occluded({0, 2, 0}, {0, -1, 0}, 2.5f));
    EXPECT_FALSE(set.occluded({0, 2, 0}, {0, 1, 0}, 1.9f));
    EXPECT_TRUE(set.occluded({0, 2, 0}, {0, 1, 0}, shd::BRUME_HUGE));  // toward a sun
    EXPECT_FALSE(set.occluded({3, 2, 0}, {0, 1, 0}, shd::BRUME_HUGE));
}

TEST(Geometry, FarFromTheOrigin) {
    const glm::vec3 c(1e5f, 0.0f, -1e5f);
    const GeometrySet set({sphere(c, 1.0f), box(c + glm::vec3(0, 0, -20), {0, 30, 0}, {2, 2, 2})});
    SurfaceHit h = set.intersect({c + glm::vec3(0, 0, 10), {0, 0, -1}}, 1e3f);
    ASSERT_TRUE(h.hit());
    EXPECT_EQ(h.index, 0);
    EXPECT_NEAR(h.t, 9.0f, 1e-2f);
    expectVec(h.normal, {0, 0, 1}, 1e-3f);
    // Behind the sphere, seen from its far side: the box is 2 m wide, rotated 30 deg about Y; its
    // nearest face along -z is at local z = +1 (scale 2 -> 1 m): distance 1 / cos 30.
    h = set.intersect({c + glm::vec3(0, 0, -10), {0, 0, -1}}, 1e3f);
    ASSERT_TRUE(h.hit());
    EXPECT_EQ(h.index, 1);
    EXPECT_NEAR(h.t, 10.0f - 1.0f / std::cos(glm::radians(30.0f)), 2e-2f);
}

// A lit plane point far from the origin must not shadow itself (surfaceRayOffset scales with |p|).
TEST(Geometry, NoSelfShadowFarFromTheOrigin) {
    Scene scene;
    Geometry p = plane(3.0f);
    p.albedo = glm::vec3(1.0f);
    scene.geometry = {p};
    Light sun = makeLight(LightType::Directional);
    sun.direction = glm::normalize(glm::vec3(0.5f, -1.0f, 0.0f));
    sun.intensity = 2.0f;
    scene.lights = {sun};
    const CompiledScene cs = compileScene(scene);
    const GeometrySet set(scene.geometry);
    for (float x : {0.0f, 1e3f, 1e5f, 9e5f}) {
        const SurfaceHit h = set.intersect({{x, 10.0f, x}, glm::normalize(glm::vec3(0.1f, -1.0f, 0.2f))}, 1e6f);
        ASSERT_TRUE(h.hit());
        const glm::vec3 L = shadeSurface(cs, set, h);
        EXPECT_NEAR(L.x, 2.0f / 3.14159265f * -sun.direction.y, 1e-4f) << "x = " << x;
    }
}

// Lit points on a sphere and a rotated box must not shadow themselves, near and far from the origin.
TEST(Geometry, CurvedAndBoxSurfacesDoNotShadowThemselves) {
    for (float x : {0.0f, 37.0f, 1e4f, 1e5f}) {
        Scene scene;
        Geometry s = sphere({x, 0.0f, x}, 1.0f), b = box({x + 5.0f, 0.0f, x}, {20, 30, 10}, {1, 2, 1});
        s.albedo = b.albedo = glm::vec3(1.0f);
        scene.geometry = {s, b};
        Light sun = makeLight(LightType::Directional);
        sun.direction = glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f));
        scene.lights = {sun};
        const CompiledScene cs = compileScene(scene);
        const GeometrySet set(scene.geometry);
        for (float dx : {-0.5f, 0.0f, 0.3f, 4.8f, 5.0f, 5.2f}) {
            const SurfaceHit h = set.intersect({{x + dx, 10.0f, x + 0.1f}, {0, -1, 0}}, 1e3f);
            ASSERT_TRUE(h.hit());
            const float want = sun.intensity / 3.14159265f * std::max(0.0f, glm::dot(h.normal, -sun.direction));
            EXPECT_NEAR(shadeSurface(cs, set, h).x, want, 1e-4f) << "x = " << x << ", dx = " << dx;
        }
    }
}

// A 1 m box standing on a plane 1e5 m from the origin shadows the ground right beside it: the
// shadow-ray offset must stay far below the box's size there.
TEST(Geometry, ContactShadowFarFromTheOrigin) {
    Scene scene;
    const glm::vec3 c(1e5f, 0.0f, 1e5f);
    Geometry ground = plane(0.0f);
    ground.albedo = glm::vec3(1.0f);
    scene.geometry = {ground, box(c + glm::vec3(0, 0.5f, 0), {0, 0, 0}, {1, 1, 1})};
    Light sun = makeLight(LightType::Directional);
    sun.direction = glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f));  // shadow extends 1 m along +x
    scene.lights = {sun};
    const CompiledScene cs = compileScene(scene);
    const GeometrySet set(scene.geometry);
    const SurfaceHit h = set.intersect({c + glm::vec3(0.8f, 10.0f, 0.0f), {0, -1, 0}}, 1e3f);
    ASSERT_TRUE(h.hit());
    ASSERT_EQ(h.index, 0);
    EXPECT_EQ(shadeSurface(cs, set, h).x, 0.0f);  // in the box's shadow: no ambient, no sun
}

}  // namespace
}  // namespace brume
