// brume-editor driven by the real mouse and keyboard: xdotool under Xvfb (xvfb-run) clicks the fog
// box to select it, drags the gizmo's X handle, presses Ctrl+S, Ctrl+Z and Ctrl+S again
// (tests/editor_xdotool.sh); the saved scenes show the box moved along X only, then back.
// Skipped with a message when xvfb-run or xdotool is missing.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/scene_json.h"
#include "test_support.h"

namespace fs = std::filesystem;
using namespace brume;

namespace {

using brume::test::quoted;
using brume::test::readText;

bool have(const char* tool) { return std::system((std::string("command -v ") + tool + " > /dev/null 2>&1").c_str()) == 0; }

// One unit fog box at the centre of the view, lit by the sun; no temporal accumulation, so the
// editor renders once per edit and the input is handled at UI speed.
Scene boxInTheMiddle() {
    Scene s;
    s.camera.position = {0.0f, 1.0f, 6.0f};
    s.camera.target = {0.0f, 1.0f, 0.0f};
    s.temporal.enabled = false;
    s.volumes.push_back(test::boxFog({0.0f, 1.0f, 0.0f}, glm::vec3(1.0f), 0.1f, 0.5f, 0.05f));
    Light sun;
    sun.type = LightType::Directional;
    s.lights.push_back(sun);
    return s;
}

}  // namespace

TEST(EditorInput, ClickDragSaveUndoWithTheRealMouseAndKeyboard) {
    if (!have("xvfb-run")) GTEST_SKIP() << "xvfb-run is missing (apt-get install xvfb xauth): skipped";
    if (!have("xdotool")) GTEST_SKIP() << "xdotool is missing (apt-get install xdotool): skipped";
    test::TempDir dir("editor_input", "xdotool");
    const fs::path scene = dir.path / "box.json";
    ASSERT_TRUE(saveSceneFile(boxInTheMiddle(), scene.string()).ok());
    const fs::path record = dir.path / "record.txt", afterDrag = dir.path / "after_drag.json";
    const fs::path log = dir.path / "log.txt";
    const std::string cmd = "xvfb-run -a -s '-screen 0 1024x768x24' bash " +
                            quoted(std::string(BRUME_SOURCE_DIR) + "/tests/editor_xdotool.sh") + " " +
                            quoted(BRUME_EDITOR_EXE) + " " + quoted(scene.string()) + " " + quoted(record.string()) +
                            " " + quoted(afterDrag.string()) + " > " + quoted(log.string()) + " 2>&1";
    const int status = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << readText(log) << "\nrecord:\n" << readText(record);

    // The drag moved the box along X only (the handle was dragged right, slightly off the axis).
    Result<Scene> dragged = loadSceneFile(afterDrag.string());
    ASSERT_TRUE(dragged.ok()) << dragged.error().message;
    const glm::vec3 t = dragged.value().volumes.at(0).transform.translation;
    std::printf("[editor-input] after the drag the box is at %.3f %.3f %.3f\n", t.x, t.y, t.z);
    EXPECT_GT(t.x, 0.3f);
    EXPECT_EQ(t.y, 1.0f);
    EXPECT_EQ(t.z, 0.0f);
    // Ctrl+Z undid the whole drag (one step), and Ctrl+S saved that.
    Result<Scene> undone = loadSceneFile(scene.string());
    ASSERT_TRUE(undone.ok()) << undone.error().message;
    EXPECT_EQ(undone.value().volumes.at(0).transform.translation, glm::vec3(0.0f, 1.0f, 0.0f));
    // What the input produced, as actions: a pick, the drag's group, the saves and the undo.
    const std::string actions = readText(record);
    EXPECT_NE(actions.find("pick "), std::string::npos) << actions;
    EXPECT_EQ(actions.find("orbit"), std::string::npos) << "the drag moved the camera: " << actions;
}
