// The rotate and scale gizmo's math, without a window (the translate gizmo's is in view.h):
// where the cursor's ray meets a ring's plane and at which angle, how an angle about a world axis
// composes with a transform's Euler angles, and the scale factor a drag gives. gizmo.cpp draws the
// handles and turns these into `set` actions; tests/test_editor_actions.cpp checks them.
#pragma once

#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "core/scene.h"

namespace brume::editor {

enum class GizmoMode { Translate, Rotate, Scale };

// Angle [deg] of the point where the ray meets the plane through `center` normal to `axis` (unit
// length), counter-clockwise about `axis` (right hand) from a fixed in-plane direction; nothing
// when the ray runs along the plane (within ~1 degree: no stable angle) or meets it behind.
std::optional<float> ringAngle(glm::vec3 center, glm::vec3 axis, glm::vec3 rayOrigin, glm::vec3 rayDir);
// `deg` wrapped to (-180, 180]: the step between two ring angles a frame apart, so a drag past
// half a turn keeps adding up instead of jumping back.
float wrapDegrees(float deg);
// `deg` rounded to a multiple of `snap` when snap > 0 (Ctrl: 15 degrees).
float snapped(float deg, float snap);

// Euler angles [deg] (scene.h: R = Rz * Ry * Rx) of the rotation `angleDeg` about world axis
// `axis` (0 x, 1 y, 2 z) applied after `rotationDeg`, i.e. R' = R_axis * R.
glm::vec3 rotateEuler(glm::vec3 rotationDeg, int axis, float angleDeg);
// `dir` turned by `angleDeg` about world axis `axis` (a spot light's direction).
glm::vec3 rotateDirection(glm::vec3 dir, int axis, float angleDeg);
// The world direction of local axis `axis` of a transform with these Euler angles (scale handles
// run along the object's own axes, since scale applies before rotation).
glm::vec3 localAxis(glm::vec3 rotationDeg, int axis);

// Scale factor of an axis handle dragged from parameter s0 to s along its axis (view.h's
// axisParam, measured from the pivot): the handle's point follows the cursor, so s / s0; nothing
// when s0 is too near the pivot to divide by.
std::optional<float> axisScaleFactor(float s0, float s);
// Scale factor of the uniform (centre) handle: the cursor's move right plus up [px] over the
// handle length [px]; a handle length doubles, and the factor stays above 0.
float uniformScaleFactor(float rightPx, float upPx, float handlePx);
// `start` with component `axis` (0..2; 3: all three) multiplied by `factor`; Ctrl snaps the
// changed components to multiples of `snap`; results stay at or above `minScale`.
glm::vec3 scaleDrag(glm::vec3 start, int axis, float factor, float snap, float minScale);

// Settings paths the rotate and scale gizmos edit for the selected object, or "" when it has none:
// box and vdb volumes and box geometry rotate and scale their transform; a spot light rotates its
// direction ("lights[2].direction").
std::string rotationPath(const Scene& scene, const std::string& kind, size_t index);
std::string scalePath(const Scene& scene, const std::string& kind, size_t index);

}  // namespace brume::editor
