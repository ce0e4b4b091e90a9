#include "file_browser.h"

#include <cstdio>
#include <filesystem>

#include <GLFW/glfw3.h>
#include <imgui.h>

namespace brume::editor {
namespace {

namespace fs = std::filesystem;

void runOrNotify(Editor& e, const Action& a, double now) {
    if (Result<void> r = e.run(a); !r) e.notify(r.error().message, now);
}

// New and Open go through the prompt when there are unsaved changes.
void request(Editor& e, FilesUi& f, const std::string& verb, const std::string& path, double now) {
    if (e.doc().dirty()) {
        f.pending = verb == "new" ? verb : verb + " " + path;
        return;
    }
    runOrNotify(e, verb == "new" ? Action{"new", {}} : Action{"open", {path}}, now);
}

const char* extensionFor(BrowseFor b) {
    return b == BrowseFor::ImportVdb ? ".vdb" : b == BrowseFor::ImportMesh ? ".obj|.ply" : ".json";
}

void listDir(FilesUi& f) {
    Result<std::vector<DirEntry>> list = listDirectory(f.dir, extensionFor(f.browsing));
    f.entries = list ? list.value() : std::vector<DirEntry>{};
    f.listError = list ? "" : list.error().message;
}

void browse(Editor& e, FilesUi& f, BrowseFor what) {
    std::error_code ec;
    const std::string& scene = e.doc().path();
    f.dir = !scene.empty() ? fs::path(scene).parent_path().string() : fs::current_path(ec).string();
    f.browsing = what;
    std::snprintf(f.typed, sizeof f.typed, "%s", what == BrowseFor::SaveAs && !scene.empty() ? fs::path(scene).filename().c_str() : "");
    listDir(f);
}

void enter(FilesUi& f, const fs::path& dir) {
    f.dir = dir.lexically_normal().string();
    f.typed[0] = '\0';
    listDir(f);
}

// OK in the browser: a folder is entered, a file runs the purpose's action.
void accept(Editor& e, FilesUi& f, double now) {
    fs::path p(f.typed);
    if (p.empty()) return;
    if (p.is_relative()) p = fs::path(f.dir) / p;
    std::error_code ec;
    if (fs::is_directory(p, ec)) return enter(f, p);
    const std::string path = p.lexically_normal().string();
    const BrowseFor what = f.browsing;
    f.browsing = BrowseFor::None;
    if (what == BrowseFor::Open) request(e, f, "open", path, now);
    else if (what == BrowseFor::SaveAs) runOrNotify(e, {"save", {path}}, now);
    else runOrNotify(e, {"import", {what == BrowseFor::ImportMesh ? "mesh" : "vdb", path}}, now);
}

void browserWindow(Editor& e, FilesUi& f, double now) {
    if (f.browsing == BrowseFor::None) return;
    const char* title = f.browsing == BrowseFor::Open ? "Open scene###browser"
                      : f.browsing == BrowseFor::SaveAs ? "Save scene as###browser"
                      : f.browsing == BrowseFor::ImportMesh ? "Import mesh###browser" : "Import VDB###browser";
    ImGui::SetNextWindowSize(ImVec2(460, 360), ImGuiCond_FirstUseEver);
    bool open = true;
    ImGui::Begin(title, &open);
    if (ImGui::Button("Up")) enter(f, fs::path(f.dir).parent_path());
    ImGui::SameLine();
    ImGui::TextUnformatted(f.dir.c_str());
    ImGui::TextDisabled("showing folders and %s files", extensionFor(f.browsing));
    if (!f.listError.empty()) ImGui::TextColored(ImVec4(1.0f, 0.6f, 0.4f, 1.0f), "%s", f.listError.c_str());
    ImGui::BeginChild("entries", ImVec2(0, -2.2f * ImGui::GetFrameHeightWithSpacing()), true);
    for (const DirEntry& d : f.entries) {
        const std::string label = d.name + (d.isDir ? "/" : "");
        if (ImGui::Selectable(label.c_str(), d.name == f.typed, ImGuiSelectableFlags_AllowDoubleClick)) {
            if (d.isDir && ImGui::IsMouseDoubleClicked(0)) {
                enter(f, fs::path(f.dir) / d.name);
                break;
            }
            std::snprintf(f.typed, sizeof f.typed, "%s", d.name.c_str());
            if (!d.isDir && ImGui::IsMouseDoubleClicked(0)) accept(e, f, now);
        }
    }
    ImGui::EndChild();
    if (ImGui::InputText("path", f.typed, sizeof f.typed, ImGuiInputTextFlags_EnterReturnsTrue)) accept(e, f, now);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("A file name in this folder, or a path (absolute or relative to it).");
    if (ImGui::Button(f.browsing == BrowseFor::SaveAs ? "Save" : f.browsing == BrowseFor::Open ? "Open" : "Import"))
        accept(e, f, now);
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) open = false;
    ImGui::End();
    if (!open) f.browsing = BrowseFor::None;
}

void unsavedPrompt(Editor& e, FilesUi& f, double now) {
    const char* id = "Unsaved changes###files";
    if (!e.pendingOpen.empty()) f.pending = "open " + std::exchange(e.pendingOpen, "");
    if (!f.pending.empty() && !ImGui::IsPopupOpen(id)) ImGui::OpenPopup(id);
    if (!ImGui::BeginPopupModal(id, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
    const Action next = f.pending == "new" ? Action{"new", {}} : Action{"open", {f.pending.substr(5)}};
    ImGui::Text("Save the changes to %s first?", e.doc().path().empty() ? "untitled" : e.doc().path().c_str());
    bool done = false;
    if (ImGui::Button("Save")) {
        Result<void> r = e.run("save");
        if (r) runOrNotify(e, next, now);
        else e.notify(r.error().message, now);
        done = true;
    }
    ImGui::SameLine();
    if (ImGui::Button("Discard")) {
        Action discard = next;
        discard.args.push_back("--discard");
        runOrNotify(e, discard, now);
        done = true;
    }
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) done = true;
    if (done) f.pending.clear(), ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
}

}  // namespace

void fileMenuItems(Editor& e, FilesUi& f, bool& quit, double now) {
    if (ImGui::MenuItem("New", "Ctrl+N")) request(e, f, "new", "", now);
    if (ImGui::MenuItem("Open...", "Ctrl+O")) browse(e, f, BrowseFor::Open);
    if (ImGui::BeginMenu("Open Recent")) {
        for (const std::string& m : e.files().recent().prune()) e.notify(m, now);
        const std::vector<std::string> paths = e.files().recent().paths();
        if (paths.empty()) ImGui::TextDisabled("(none)");
        for (const std::string& p : paths)
            if (ImGui::MenuItem(p.c_str())) request(e, f, "open", p, now);
        ImGui::EndMenu();
    }
    if (ImGui::MenuItem("Save", "Ctrl+S")) runOrNotify(e, {"save", {}}, now);
    if (ImGui::MenuItem("Save As...")) browse(e, f, BrowseFor::SaveAs);
    ImGui::Separator();
    if (ImGui::MenuItem("Import VDB...")) browse(e, f, BrowseFor::ImportVdb);
    if (ImGui::MenuItem("Import Mesh (OBJ, PLY)...")) browse(e, f, BrowseFor::ImportMesh);
    ImGui::Separator();
    if (ImGui::MenuItem("Quit")) quit = true;
}

void drawFiles(Editor& e, FilesUi& f, double now) {
    for (const std::string& m : e.files().takeMessages()) e.notify(m, now);
    const ImGuiIO& io = ImGui::GetIO();
    if (!io.WantCaptureKeyboard && io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_N)) request(e, f, "new", "", now);
    if (!io.WantCaptureKeyboard && io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_O)) browse(e, f, BrowseFor::Open);
    browserWindow(e, f, now);
    unsavedPrompt(e, f, now);
}

}  // namespace brume::editor
