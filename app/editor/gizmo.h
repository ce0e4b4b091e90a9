// The translate gizmo: three axis handles drawn on ImGui's background draw list at the selected
// object's position; dragging one moves the object along that world axis (Ctrl: snapped to
// 0.25 m), through `set PATH X Y Z` actions bracketed by begin/end, so a drag is one undo step.
// The math (projection, closest point on the axis, snapping) is in view.h, tested without a window.
#pragma once

#include <string>

#include <glm/glm.hpp>

namespace brume::editor {

class Editor;

struct GizmoState {
    int axis = -1;  // the axis being dragged (0 x, 1 y, 2 z), -1 when none
    glm::vec3 start{0.0f};
    float s0 = 0.0f;
    std::string path;
};

// Draws the handles and runs their drags; true while the gizmo owns the mouse (a handle is being
// dragged, or hovered with no button down), so the viewport's camera drags keep off it.
bool translateGizmo(Editor& e, GizmoState& g, double now);

}  // namespace brume::editor
