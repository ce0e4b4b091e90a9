// The editor's Dear ImGui panels: menu bar, outliner, inspector (widgets built from the settings
// metadata in core/settings.h: unit, range, tooltip), stats, help, notifications, and the
// recovery and unsaved-changes prompts. Every edit they make is an Action run through Editor::run.
#pragma once

#include "editor.h"
#include "file_browser.h"
#include "gizmo.h"
#include "presets_panel.h"
#include "timeline_panel.h"

namespace brume::editor {

struct UiState {
    bool showStats = true;
    bool showHelp = false;
    bool closeRequested = false;   // the window's close button with unsaved changes: ask first
    bool closeConfirmed = false;
    GizmoState gizmo;
    bool flying = false;           // a fly key is held: its moves are one undo step   // the user chose Save or Discard
    std::string recoveryPath;      // non-empty: offer to recover this autosave
    FilesUi files;                 // File menu: browser, New/Open prompt (file_browser.h)
    PresetsPanelState presets;     // presets_panel.h
    TimelineState timeline;        // timeline_panel.h
};

void drawUi(Editor& editor, UiState& ui, double now);
// Viewport mouse and keyboard (orbit, pan, zoom, shortcuts) when ImGui does not want the input.
void handleViewportInput(Editor& editor, UiState& ui, double now);

}  // namespace brume::editor
