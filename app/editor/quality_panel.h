// The editor's Quality panel (docs/quality.md, "The editor's Quality panel") and the error heat
// map debug view: `brume tradeoff` on the current view in the background (quality_job.h), its chart
// and table, one click to apply a candidate to the document, and where the error is.
//
// Actions (Editor::run; scripts use them like the UI):
//   tradeoff show|hide                the panel
//   tradeoff plan QUALITIES FRAMES    what to measure, as `brume tradeoff --quality --frames`
//   tradeoff renderer gpu|cpu         which renderer is timed
//   tradeoff size 1|2|4               the measured size: the view's divided by this
//   tradeoff run [WIDTH HEIGHT]       starts measuring the view (at that size, if given)
//   tradeoff cancel                   stops it (a cancelled reference leaves no cache entry)
//   tradeoff wait                     a script waits here until the measurement has finished
//   tradeoff apply INDEX              the table's row INDEX (from 0): its preset and frames into the
//                                     document's render block (one undo step) and the viewport's preset
#pragma once

#include "editor.h"

namespace brume::editor {

Result<void> runQualityAction(Editor& editor, const Action& action);

// Starts the heat map of the current view when it has none or a stale one (`debug error`).
void requestHeatMap(Editor& editor);

// The panel, when shown; call once per frame inside the ImGui frame.
void drawQualityPanel(Editor& editor, double now);
// The heat map over the viewport while the debug view is `error` (behind the panels).
void heatMapOverlay(Editor& editor);
// The heat map's legend and state, for the Debug section.
void heatMapLegend(Editor& editor, double now);

}  // namespace brume::editor
