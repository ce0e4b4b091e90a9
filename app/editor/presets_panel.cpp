#include "presets_panel.h"

#include <algorithm>

#include <imgui.h>
#include <stb/stb_image.h>

namespace brume::editor {
namespace {

namespace fs = std::filesystem;

constexpr int kThumbColumns = 40, kThumbRows = 22;  // corner samples of a 160x90 PNG every 4 px
constexpr float kThumbWidth = 128.0f, kThumbHeight = 72.0f;

fs::file_time_type stamp(const std::string& dir) {
    std::error_code ec;
    if (dir.empty()) return {};
    const fs::file_time_type t = fs::last_write_time(dir, ec);
    return ec ? fs::file_time_type{} : t;
}

ThumbnailColors readThumbnail(const std::string& png) {
    ThumbnailColors t;
    int w = 0, h = 0, n = 0;
    unsigned char* data = stbi_load(png.c_str(), &w, &h, &n, 4);
    if (!data) return t;  // unreadable: drawn as "no thumbnail"
    t.columns = kThumbColumns;
    t.rows = kThumbRows;
    for (int y = 0; y <= t.rows; ++y)
        for (int x = 0; x <= t.columns; ++x) {
            const int px = std::min(w - 1, x * w / t.columns), py = std::min(h - 1, y * h / t.rows);
            const unsigned char* p = data + (static_cast<size_t>(py) * static_cast<size_t>(w) + static_cast<size_t>(px)) * 4;
            t.corners.push_back(IM_COL32(p[0], p[1], p[2], 255));
        }
    stbi_image_free(data);
    return t;
}

void rescanIfChanged(PresetsPanelState& s) {
    const std::string library = presetLibraryDir(), user = userPresetDir();
    const fs::file_time_type l = stamp(library), u = stamp(user);
    if (s.scanned && l == s.libraryStamp && u == s.userStamp) return;
    s.scanned = true;
    s.libraryStamp = l;
    s.userStamp = u;
    s.entries = scanPresetShelf(library, user);
    s.thumbnails.clear();
    for (const ShelfEntry& e : s.entries)
        if (e.hasThumbnail) s.thumbnails[e.path] = readThumbnail(presetThumbnailPath(e.path));
}

void drawThumbnail(const ThumbnailColors* t) {
    const ImVec2 p = ImGui::GetCursorScreenPos();
    ImDrawList* dl = ImGui::GetWindowDrawList();
    ImGui::Dummy(ImVec2(kThumbWidth, kThumbHeight));
    // Outside the panel's visible rectangle: nothing to draw. A thumbnail is 880 shaded quads (3,520
    // vertices) that the UI would build, upload and set up every frame for every preset in the
    // library, shown or not (docs/performance.md, "thumbs").
    if (!ImGui::IsItemVisible()) return;
    if (!t || t->columns == 0) {
        dl->AddRectFilled(p, ImVec2(p.x + kThumbWidth, p.y + kThumbHeight), IM_COL32(40, 40, 40, 255));
        dl->AddText(ImVec2(p.x + 8, p.y + kThumbHeight * 0.5f - 7), IM_COL32(160, 160, 160, 255), "no thumbnail");
        return;
    }
    const float cw = kThumbWidth / static_cast<float>(t->columns), ch = kThumbHeight / static_cast<float>(t->rows);
    const int stride = t->columns + 1;
    for (int y = 0; y < t->rows; ++y)
        for (int x = 0; x < t->columns; ++x) {
            const size_t i = static_cast<size_t>(y * stride + x);
            const ImVec2 a(p.x + static_cast<float>(x) * cw, p.y + static_cast<float>(y) * ch);
            dl->AddRectFilledMultiColor(a, ImVec2(a.x + cw, a.y + ch), t->corners[i], t->corners[i + 1],
                                        t->corners[i + static_cast<size_t>(stride) + 1], t->corners[i + static_cast<size_t>(stride)]);
        }
}

void runOrNotify(Editor& e, const Action& a, double now) {
    Result<void> r = e.run(a);
    if (!r) e.notify(r.error().message, now);
}

void entryRow(Editor& e, PresetsPanelState& s, const ShelfEntry& entry, double now) {
    ImGui::PushID(entry.path.c_str());
    if (!entry.preset) {
        // A file that does not read: its sentence, never a crash.
        ImGui::TextColored(ImVec4(1.0f, 0.6f, 0.4f, 1.0f), "%s", fs::path(entry.path).filename().string().c_str());
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextDisabled("%s", entry.error.c_str());
        ImGui::PopTextWrapPos();
        ImGui::Separator();
        ImGui::PopID();
        return;
    }
    const auto t = s.thumbnails.find(entry.path);
    drawThumbnail(t == s.thumbnails.end() ? nullptr : &t->second);
    if (ImGui::IsItemHovered() && !entry.preset->description.empty())
        ImGui::SetTooltip("%s", entry.preset->description.c_str());
    ImGui::SameLine();
    ImGui::BeginGroup();
    ImGui::TextUnformatted(entry.preset->name.c_str());
    std::string tags;
    for (const std::string& tag : entry.preset->tags) tags += (tags.empty() ? "" : ", ") + tag;
    if (!tags.empty()) ImGui::TextDisabled("%s", tags.c_str());
    if (ImGui::SmallButton("Replace")) runOrNotify(e, {"preset", {"apply", entry.path, "replace"}}, now);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Replace the scene's fog (volumes, ambient, and lights where the look has them); one undo step.");
    ImGui::SameLine();
    if (ImGui::SmallButton("Add")) runOrNotify(e, {"preset", {"apply", entry.path, "add"}}, now);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Add the look's volumes (and lights) to the scene's; one undo step.");
    ImGui::EndGroup();
    ImGui::PopID();
}

void saveSection(Editor& e, PresetsPanelState& s, double now) {
    if (!ImGui::CollapsingHeader("Save fog as preset")) return;
    ImGui::InputText("name", s.name, sizeof s.name);
    ImGui::InputText("description", s.description, sizeof s.description);
    ImGui::InputText("tags", s.tags, sizeof s.tags);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Comma-separated short words to filter by.");
    const std::string folder = userPresetDir();
    ImGui::TextDisabled("into %s", folder.empty() ? "(no user folder)" : folder.c_str());
    if (ImGui::Button("Save")) {
        Action a{"preset", {"save", s.name, s.description}};
        const std::string all = s.tags;
        for (size_t start = 0; start <= all.size();) {
            const size_t comma = std::min(all.find(',', start), all.size());
            std::string tag = all.substr(start, comma - start);
            tag.erase(0, tag.find_first_not_of(' '));
            tag.erase(tag.find_last_not_of(' ') + 1);
            if (!tag.empty()) a.args.push_back(tag);
            start = comma + 1;
        }
        Result<void> r = e.run(a);
        if (r) e.notify(std::string("Saved the look \"") + s.name + "\".", now), s.name[0] = '\0';
        else e.notify(r.error().message, now);
    }
}

}  // namespace

void drawPresetsPanel(Editor& e, PresetsPanelState& s, double now) {
    if (!s.show) return;
    rescanIfChanged(s);
    ImGui::SetNextWindowPos(ImVec2(ImGui::GetIO().DisplaySize.x - 330, 380), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(320, 330), ImGuiCond_FirstUseEver);
    ImGui::Begin("Presets", &s.show);
    saveSection(e, s, now);
    bool shippedHeader = false, userHeader = false;
    for (const ShelfEntry& entry : s.entries) {
        if (entry.shipped && !shippedHeader) ImGui::Separator(), ImGui::TextDisabled("Library"), shippedHeader = true;
        if (!entry.shipped && !userHeader) ImGui::Separator(), ImGui::TextDisabled("Yours"), userHeader = true;
        entryRow(e, s, entry, now);
    }
    if (!userHeader) ImGui::TextDisabled("No looks of your own yet: save one above.");
    ImGui::End();
}

}  // namespace brume::editor
