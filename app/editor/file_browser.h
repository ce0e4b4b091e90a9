// File > New, Open, Open Recent, Save As and Import VDB in the window: the in-app file browser
// (folder listing, parent folder, filter by extension, typed path), the unsaved-changes prompt
// before New and Open (from the menu, Ctrl+N / Ctrl+O, a recent file or a dropped scene), and the
// notifications Files queued. Every choice ends as an action through Editor::run (files.h).
#pragma once

#include <string>
#include <vector>

#include "editor.h"
#include "files.h"

namespace brume::editor {

enum class BrowseFor { None, Open, SaveAs, ImportVdb, ImportMesh };

struct FilesUi {
    BrowseFor browsing = BrowseFor::None;
    std::string dir;             // the folder shown
    char typed[1024] = {};       // a file name in `dir`, or a path (absolute, or relative to `dir`)
    std::vector<DirEntry> entries;
    std::string listError;
    std::string pending;         // "new" or "open PATH": waits for the unsaved-changes prompt
};

// The items of the File menu (inside BeginMenu("File")); Quit sets `quit`.
void fileMenuItems(Editor& e, FilesUi& f, bool& quit, double now);
// The browser window, the prompt, Ctrl+N / Ctrl+O and the queued notifications; once per frame.
void drawFiles(Editor& e, FilesUi& f, double now);

}  // namespace brume::editor
