// The viewport's debug view (docs/editor.md, "Debug views"): which froxel slice the viewport
// shows instead of the final image, and whether the froxel grid is drawn over it. View state, like
// the quality preset: not saved in the scene, not undoable.
#pragma once

#include <string>

#include "core/quality.h"
#include "core/result.h"
#include "document.h"

namespace brume::editor {

struct DebugViewState {
    int view = 0;        // shd::DEBUG_VIEW_* (core/debug_view.h); 0 = the final image
    int slice = 0;       // froxel slice shown; the renderer clamps it to the grid
    bool grid = false;   // froxel tile lines over the viewport
    bool errorMap = false;  // `debug error`: the heat map of the error against the reference over the final image
    std::string legend;  // the last debug render's slice, depths and ramp (debugViewLegend)
};

// debug final|density|scattering|transmittance [SLICE]   (SLICE kept when omitted)
// debug error   (the final image under the heat map of its error against the reference, quality_panel.h)
// debug slice SLICE, debug depth METRES (the slice holding that view depth in the grid `froxels`),
// debug grid on|off
Result<void> runDebugAction(DebugViewState& state, const Action& action, const FroxelSettings& froxels);

}  // namespace brume::editor
