// The Presets panel (issue 13): the looks of the shipped library and the user's folder with their
// thumbnails, Replace / Add on each (one undo step each: `preset apply`), files that do not read
// listed with their sentence, and "Save fog as preset" (`preset save`: the JSON and its thumbnail,
// rendered by the reference renderer, written atomically into the user's folder).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "editor.h"
#include "preset_shelf.h"

namespace brume::editor {

// A thumbnail kept as a small grid of sRGB colours, drawn as Gouraud-shaded quads (bilinear
// upsampling) by ImGui's draw list: no texture, so no descriptor set per look.
struct ThumbnailColors {
    int columns = 0, rows = 0;      // cells; (columns + 1) x (rows + 1) corner colours
    std::vector<uint32_t> corners;  // ImU32, row-major from the top-left
};

struct PresetsPanelState {
    bool show = true;
    bool scanned = false;
    std::filesystem::file_time_type libraryStamp{}, userStamp{};  // rescan when a folder changes
    std::vector<ShelfEntry> entries;
    std::map<std::string, ThumbnailColors> thumbnails;  // by preset path
    char name[96] = "";
    char description[256] = "";
    char tags[160] = "";  // comma separated
};

void drawPresetsPanel(Editor& editor, PresetsPanelState& state, double now);

}  // namespace brume::editor
