// The viewport's geometry, without a window: what it renders (the scene less hidden objects), the
// fly camera, frame-selected, and picking an object under the cursor. Editor::run's verbs (fly,
// look, frame, pick) call these, so scripts and tests go through the same code as the mouse.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/result.h"
#include "core/scene.h"

namespace brume::editor {

// The scene without its hidden volumes, lights and geometry (what the viewport renders).
Scene visibleScene(const Scene& scene);

// `shown` with dark stand-ins for the volumes of `before` (an earlier shown scene's list) that it no
// longer has, a volume hidden or deleted since: each stand-in is that volume as it was, scattering,
// absorbing and emitting nothing, without keys, at its place in the list. It adds exactly 0, so the
// image is `shown`'s; and it keeps the list of before (kinds, shapes, bounds), so the renderer's
// pipelines for that list serve it, where `shown`'s new list would compile (0.4-1 s on lavapipe; the
// editor asks GpuRenderer::hasPipelines). shown's volumes are matched to before's in order, by kind
// (type, height profile, whether a height falloff); nullopt when they are not an ordered subset of
// before's (a volume added or of another kind: no stand-ins can keep the list). Lights have no
// stand-ins: a light of intensity 0 is culled like a removed one (core/light_reach.cpp).
std::optional<Scene> withStandIns(const Scene& shown, const std::vector<Volume>& before);

// The scene with every hidden flag cleared (what a file holds: hidden is not saved).
Scene withoutViewState(Scene scene);

// Moves the camera (position and target together) by `move` metres along its right, up and
// forward axes: the fly camera's WASD / QE.
Camera flyCamera(const Camera& c, glm::vec3 move);
// Turns the view about the camera position (fly mouse look); pitch stops 1 degree from the poles.
Camera lookCamera(const Camera& c, float yawDeg, float pitchDeg);

struct Bounds {
    glm::vec3 center{0.0f};
    float radius = 1.0f;  // of a sphere enclosing the object
};
// Bounds of the object of `kind` ("volume", "light", "geometry") at `index`, or an Error for one
// without a place (height and depth fog, directional lights, planes) or an index out of range.
Result<Bounds> objectBounds(const Scene& scene, const std::string& kind, size_t index);
// Keeps the view direction and aims at the bounds' centre from the distance where the enclosing
// sphere fills the vertical field of view (with a 20% margin).
Camera frameCamera(const Camera& c, Bounds b);

struct Picked {
    std::string kind;  // "volume" or "light"
    size_t index = 0;
};
// The visible object under the window position (u, v) in [0, 1] from the top-left, for a window of
// `aspect` = width / height: the nearest box, ellipsoid, cylinder (by its surface) or vdb volume
// (by its box) the ray enters, or light
// (point, spot) within 2% of the view height of the ray; nothing when the ray misses them all.
std::optional<Picked> pick(const Scene& scene, float aspect, float u, float v);

// World-space line segments outlining a box, ellipsoid or cylinder volume (the box's 12 edges; three
// great circles; two rims and four sides) for the viewport's selection outline; empty for the rest.
std::vector<std::array<glm::vec3, 2>> volumeWireframe(const Volume& v);

// Translate gizmo. The world direction of the camera ray through window fractions (u, v).
glm::vec3 rayDirection(const Camera& c, float aspect, float u, float v);
// Window fractions of a world point, or nothing when it is behind the camera.
std::optional<glm::vec2> windowFromWorld(const Camera& c, float aspect, glm::vec3 p);
// Parameter along the line origin + s * axis (axis of unit length) of its point closest to the
// ray; nothing when the ray runs along the axis (no stable drag there).
std::optional<float> axisParam(glm::vec3 origin, glm::vec3 axis, glm::vec3 rayOrigin, glm::vec3 rayDir);
// Where an axis drag puts the object: start + axis * (s - s0), the move rounded to a multiple of
// `snap` metres when snap > 0.
glm::vec3 axisDrag(glm::vec3 start, glm::vec3 axis, float s0, float s, float snap);
// The settings path of the selected object's position ("volumes[2].transform.translation",
// "lights[0].position", "geometry[1].center"), or "" when it has none to drag.
std::string positionPath(const Scene& scene, const std::string& kind, size_t index);

}  // namespace brume::editor
