// The Stats panel's Debug section (view, slice slider with its depths, ramp, grid toggle) and the
// froxel grid drawn over the viewport. Every change is an action (`debug ...`, debug_view.h).
#pragma once

#include "editor.h"

namespace brume::editor {

void debugSection(Editor& editor, double now);
// Tile lines of the froxel grid over the viewport and the slice's depths, when `debug grid on`.
void froxelGridOverlay(Editor& editor);

}  // namespace brume::editor
