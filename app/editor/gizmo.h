// The transform gizmo, drawn on ImGui's background draw list at the selected object's pivot, in one
// of three modes (W / E / R, as in DCC tools):
//   translate: three arrows along world X, Y, Z; a drag moves along that axis (Ctrl: 0.25 m steps);
//   rotate:    three rings about world X, Y, Z through the pivot; the angle follows the cursor's
//              position on the ring's plane (Ctrl: 15 degree steps);
//   scale:     three handles along the object's own axes and a centre handle for uniform scale
//              (Ctrl: multiples of 0.1).
// Every drag is `begin`, `set PATH X Y Z`..., `end`: one undo step, and --record replays it. The
// math is in view.h (translate) and gizmo_math.h (rotate, scale), tested without a window.
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "gizmo_math.h"

namespace brume::editor {

class Editor;

struct GizmoState {
    int axis = -1;  // the handle being dragged (0 x, 1 y, 2 z, 3 the uniform scale centre), -1 none
    glm::vec3 start{0.0f};  // the edited value when the drag began
    float s0 = 0.0f;        // translate, scale: axis parameter at the press
    float prevAngle = 0.0f, totalAngle = 0.0f;  // rotate [deg]
    glm::vec2 pressPx{0.0f};                    // uniform scale: cursor at the press
    std::string path;
};

// Draws the handles of the editor's mode (Editor::gizmoMode) and runs their drags; true while the gizmo owns the mouse
// (a handle is being dragged, or hovered with no button down), so camera drags keep off it.
bool transformGizmo(Editor& e, GizmoState& g, double now);

}  // namespace brume::editor
