// The Timeline panel (issue 16): play / pause and scrub the view's scene time (scene_time.h: view
// state, not an undo step; a new time is a new image for the accumulation), "Set key" on the
// selected volume's or light's setting at the current time (`key PATH SECONDS`, one undo step),
// and that object's keys drawn as diamonds on a row per keyed setting: a click goes to the key's
// time, a right click deletes it (`unkey`, undoable).
#pragma once

#include <string>

#include "editor.h"

namespace brume::editor {

struct TimelineState {
    bool show = true;
    bool loop = true;        // playing past the end starts again at 0
    float lengthS = 5.0f;    // the shown range [0, lengthS]; grows to the last key
    int target = 0;          // index into the selected object's keyable settings
};

// The time at fraction x of a bar spanning [0, length] (clamped to it).
double timelineTimeAt(float x, float width, double length);

void drawTimelinePanel(Editor& editor, TimelineState& state, double now);

}  // namespace brume::editor
