// The editor's action layer without a window: every edit the UI makes is an Action line, so these
// tests drive the document exactly as the mouse, keyboard and --script do.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include <glm/gtc/matrix_transform.hpp>

#include "app/editor/accumulation.h"
#include "app/editor/autosave.h"
#include "app/editor/document.h"
#include "app/editor/gizmo_math.h"
#include "app/editor/frame_pacing.h"
#include "app/editor/present_path.h"
#include "app/editor/view.h"
#include "io/scene_json.h"
#include "shaders/shared/brume.h"

namespace fs = std::filesystem;
using namespace brume;
using namespace brume::editor;

namespace {

const std::string kDefaultScene = std::string(BRUME_SOURCE_DIR) + "/assets/scenes/default.json";

Document loadDefault(const std::string& path = kDefaultScene) {
    Result<Scene> s = loadSceneFile(kDefaultScene);
    EXPECT_TRUE(s.ok());
    return Document(s.value(), path);
}

void run(Document& doc, const std::string& line) {
    Result<Action> a = parseAction(line);
    ASSERT_TRUE(a.ok()) << a.error().message;
    Result<void> r = doc.apply(a.value());
    ASSERT_TRUE(r.ok()) << line << ": " << r.error().message;
}

fs::path tempDir(const std::string& name) {
    fs::path d = fs::temp_directory_path() / ("brume_editor_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

}  // namespace

TEST(EditorActions, ScriptedSessionSavesTheNewValuesAndUndoRestoresThem) {
    const fs::path dir = tempDir("session");
    Document doc = loadDefault((dir / "scene.json").string());
    const Scene before = doc.scene();
    const size_t n = before.volumes.size();
    run(doc, "add volume box \"my fog\"");
    run(doc, "set volumes[" + std::to_string(n) + "].transform.translation 1.5 0.25 -2");
    run(doc, "set volumes[" + std::to_string(n) + "].medium.scattering 0.75 0.5 0.25");
    EXPECT_TRUE(doc.dirty());
    run(doc, "save");
    EXPECT_FALSE(doc.dirty());

    Result<Scene> saved = loadSceneFile((dir / "scene.json").string());
    ASSERT_TRUE(saved.ok()) << saved.error().message;
    ASSERT_EQ(saved.value().volumes.size(), n + 1);
    const Volume& v = saved.value().volumes[n];
    EXPECT_EQ(v.name, "my fog");
    EXPECT_EQ(v.type, VolumeType::Box);
    EXPECT_EQ(v.transform.translation, glm::vec3(1.5f, 0.25f, -2.0f));
    EXPECT_EQ(v.medium.scattering, glm::vec3(0.75f, 0.5f, 0.25f));

    run(doc, "undo");
    EXPECT_EQ(doc.scene().volumes[n].medium.scattering, Volume{}.medium.scattering);
    run(doc, "undo");
    EXPECT_EQ(doc.scene().volumes[n].transform.translation, glm::vec3(0.0f));
    run(doc, "undo");
    EXPECT_TRUE(doc.scene() == before);
    EXPECT_FALSE(doc.canUndo());
    run(doc, "redo");
    run(doc, "redo");
    run(doc, "redo");
    EXPECT_TRUE(doc.scene() == saved.value());
    EXPECT_FALSE(doc.dirty());
    fs::remove_all(dir);
}

TEST(EditorActions, ADragIsOneUndoStep) {
    Document doc = loadDefault();
    const Scene before = doc.scene();
    run(doc, "begin");
    for (int i = 1; i <= 20; ++i) run(doc, "set volumes[0].transform.translation " + std::to_string(0.1 * i) + " 1 0");
    run(doc, "end");
    run(doc, "set volumes[0].medium.phase_g 0.7");
    run(doc, "undo");
    EXPECT_NEAR(doc.scene().volumes[0].transform.translation.x, 2.0f, 1e-6f);
    run(doc, "undo");
    EXPECT_TRUE(doc.scene() == before);
    EXPECT_FALSE(doc.dirty());
    EXPECT_FALSE(doc.canUndo());
}

TEST(EditorActions, AnOutOfRangeValueIsAnErrorNamingThePathAndChangesNothing) {
    Document doc = loadDefault();
    const Scene before = doc.scene();
    Result<void> r = doc.apply({"set", {"volumes[0].medium.phase_g", "1.5"}});
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("volumes[0].medium.phase_g"), std::string::npos) << r.error().message;
    for (const Action& bad : {Action{"set", {"volumes[0].medium.scattering", "1", "2"}},
                              Action{"set", {"volumes[9].name", "x"}}, Action{"set", {"camera.nonsense", "1"}},
                              Action{"delete", {"light", "7"}}, Action{"add", {"volume", "cone"}},
                              Action{"frobnicate", {}}}) {
        Result<void> e = doc.apply(bad);
        EXPECT_FALSE(e.ok()) << formatAction(bad);
        if (!e.ok()) {
            EXPECT_FALSE(e.error().message.empty());
        }
    }
    EXPECT_TRUE(doc.scene() == before);
    EXPECT_FALSE(doc.canUndo());
}

TEST(EditorActions, DeleteDuplicateRenameAndAddEveryKind) {
    Document doc = loadDefault();
    const Scene before = doc.scene();
    run(doc, "duplicate light 1");
    ASSERT_EQ(doc.scene().lights.size(), before.lights.size() + 1);
    EXPECT_EQ(doc.scene().lights[2].name, before.lights[1].name + " copy");
    EXPECT_EQ(doc.scene().lights[2].position, before.lights[1].position);
    run(doc, "rename light 2 \"warm \\\"glow\\\"\"");
    EXPECT_EQ(doc.scene().lights[2].name, "warm \"glow\"");
    run(doc, "delete volume 0");
    EXPECT_EQ(doc.scene().volumes.size(), before.volumes.size() - 1);
    for (const char* line : {"add volume height", "add volume depth", "add light directional", "add light point",
                             "add light spot", "add geometry plane", "add geometry box", "add geometry sphere"})
        run(doc, line);
    EXPECT_EQ(doc.scene().lights.back().type, LightType::Spot);
    EXPECT_EQ(doc.scene().geometry.back().type, GeometryType::Sphere);
    // The result is still a valid scene file.
    Result<Scene> back = parseScene(sceneToJson(doc.scene()), "roundtrip");
    ASSERT_TRUE(back.ok()) << back.error().message;
    EXPECT_TRUE(back.value() == doc.scene());
}

// Keyframes are not edited in the editor yet (the timeline is to come), but a keyed scene must survive
// it: edits, duplicates, undo and save keep every track.
TEST(EditorActions, KeyedSceneKeepsItsKeysThroughEditsUndoAndSave) {
    const fs::path dir = tempDir("keyed");
    Result<Scene> s = loadSceneFile(kDefaultScene);
    ASSERT_TRUE(s.ok());
    KeyTrack scattering;
    scattering.target = "medium.scattering";
    scattering.keys = {{0.0f, glm::vec3(0.1f)}, {2.0f, glm::vec3(0.5f, 0.4f, 0.3f)}};
    KeyTrack intensity;
    intensity.target = "intensity";
    intensity.interpolation = Interpolation::Smooth;
    intensity.keys = {{0.0f, glm::vec3(1.0f, 0, 0)}, {1.0f, glm::vec3(4.0f, 0, 0)}, {3.0f, glm::vec3(2.0f, 0, 0)}};
    s.value().volumes[0].keys = {scattering};
    s.value().lights[0].keys = {intensity};
    Document doc(s.value(), (dir / "scene.json").string());
    const Scene before = doc.scene();
    run(doc, "set volumes[0].medium.phase_g 0.5");
    run(doc, "set lights[0].color 1 0.5 0.25");
    run(doc, "duplicate light 0");
    EXPECT_EQ(doc.scene().volumes[0].keys, before.volumes[0].keys);
    EXPECT_EQ(doc.scene().lights[0].keys, before.lights[0].keys);
    EXPECT_EQ(doc.scene().lights[1].keys, before.lights[0].keys);  // the copy goes right after
    run(doc, "save");
    Result<Scene> saved = loadSceneFile((dir / "scene.json").string());
    ASSERT_TRUE(saved.ok()) << saved.error().message;
    EXPECT_EQ(saved.value().volumes[0].keys, before.volumes[0].keys);
    EXPECT_EQ(saved.value().lights[0].keys, before.lights[0].keys);
    run(doc, "undo");
    run(doc, "undo");
    run(doc, "undo");
    EXPECT_TRUE(doc.scene() == before);
    fs::remove_all(dir);
}

// Influencers are edited like any object (docs/editor.md): add, set a setting and a path point,
// hide, delete; each an undo step, and a bad path edit is refused with the reader's sentence. A key
// list's interpolation switches with `interpolate`.
TEST(EditorActions, InfluencersAndInterpolationAreUndoableEdits) {
    Document doc = loadDefault();
    const Scene before = doc.scene();
    run(doc, "add influencer capsule walker");
    ASSERT_EQ(doc.scene().influencers.size(), 1u);
    EXPECT_EQ(doc.scene().influencers[0].type, InfluencerType::Capsule);
    run(doc, "set influencers[0].radius 0.6");
    run(doc, "set influencers[0].path[1].position 3 1 -1");
    run(doc, "set influencers[0].path_interpolation smooth");
    EXPECT_EQ(doc.scene().influencers[0].radius, 0.6f);
    EXPECT_EQ(doc.scene().influencers[0].path.keys[1].value, glm::vec3(3.0f, 1.0f, -1.0f));
    EXPECT_EQ(doc.scene().influencers[0].path.interpolation, Interpolation::Smooth);
    Result<Action> bad = parseAction("set influencers[0].path[1].time -5");
    ASSERT_TRUE(bad.ok());
    const Result<void> refused = doc.apply(bad.value());
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().message.find("influencers[0].path[1].time"), std::string::npos) << refused.error().message;
    run(doc, "hide influencer 0");
    EXPECT_TRUE(doc.scene().influencers[0].hidden);
    EXPECT_TRUE(visibleScene(doc.scene()).influencers.empty());
    run(doc, "show influencer 0");
    run(doc, "duplicate influencer 0");
    EXPECT_EQ(doc.scene().influencers.size(), 2u);
    run(doc, "delete influencer 1");
    run(doc, "key volumes[0].medium.scattering 0");
    run(doc, "key volumes[0].medium.scattering 1");
    run(doc, "interpolate volumes[0].medium.scattering smooth");
    EXPECT_EQ(doc.scene().volumes[0].keys[0].interpolation, Interpolation::Smooth);
    run(doc, "undo");
    EXPECT_EQ(doc.scene().volumes[0].keys[0].interpolation, Interpolation::Linear);
    for (int i = 0; i < 10; ++i) run(doc, "undo");
    EXPECT_TRUE(doc.scene() == before);
}

TEST(EditorActions, ActionsFormatAndParseBackExactly) {
    for (const Action& a : {Action{"rename", {"volume", "0", "a \"quoted\" name\\ # x"}}, Action{"undo", {}},
                            Action{"set", {"camera.position", "1", "-2.5", "3e-4"}}}) {
        Result<Action> back = parseAction(formatAction(a));
        ASSERT_TRUE(back.ok()) << formatAction(a);
        EXPECT_EQ(back.value().verb, a.verb);
        EXPECT_EQ(back.value().args, a.args);
    }
    EXPECT_TRUE(parseAction("   # a comment").value().verb.empty());
    EXPECT_FALSE(parseAction("rename volume 0 \"open").ok());
}

TEST(EditorAutosave, WritesWhileDirtyAtMostOncePerIntervalAndRemovesWhenSaved) {
    const fs::path dir = tempDir("autosave");
    const std::string scenePath = (dir / "scene.json").string();
    Document doc = loadDefault(scenePath);
    ASSERT_TRUE(doc.apply({"save", {}}).ok());
    Autosave autosave(recoveryPathFor(scenePath), 2.0);
    ASSERT_TRUE(autosave.tick(doc, 0.0).ok());
    EXPECT_FALSE(fs::exists(autosave.path()));  // clean: nothing to recover

    run(doc, "set volumes[0].medium.phase_g -0.25");
    ASSERT_TRUE(autosave.tick(doc, 10.0).ok());
    ASSERT_TRUE(fs::exists(autosave.path()));
    run(doc, "set volumes[0].edge_fade 0.5");
    ASSERT_TRUE(autosave.tick(doc, 11.0).ok());  // within the interval: not yet
    EXPECT_EQ(autosave.writes(), 1);
    ASSERT_TRUE(autosave.tick(doc, 12.0).ok());
    EXPECT_EQ(autosave.writes(), 2);
    Result<Scene> recovered = loadSceneFile(autosave.path());
    ASSERT_TRUE(recovered.ok()) << recovered.error().message;
    EXPECT_TRUE(recovered.value() == doc.scene());
    ASSERT_TRUE(autosave.tick(doc, 20.0).ok());  // unchanged since: no rewrite
    EXPECT_EQ(autosave.writes(), 2);

    run(doc, "save");
    ASSERT_TRUE(autosave.tick(doc, 21.0).ok());
    EXPECT_FALSE(fs::exists(autosave.path()));
    fs::remove_all(dir);
}

// Frames slower than the interval (a render under load) must not hold an edit back past it: the
// tick writes as soon as waiting for the next one would pass the interval, and no earlier.
TEST(EditorAutosave, ASlowNextFrameWritesNowInsteadOfPastTheInterval) {
    const fs::path dir = tempDir("autosave_slow");
    const std::string scenePath = (dir / "scene.json").string();
    Document doc = loadDefault(scenePath);
    Autosave autosave(recoveryPathFor(scenePath), 2.0);
    run(doc, "set volumes[0].medium.phase_g -0.25");
    ASSERT_TRUE(autosave.tick(doc, 10.0, 0.05).ok());
    EXPECT_EQ(autosave.writes(), 1);
    run(doc, "set volumes[0].edge_fade 0.5");
    ASSERT_TRUE(autosave.tick(doc, 10.5, 1.0).ok());  // next tick at ~11.5: still within the interval
    EXPECT_EQ(autosave.writes(), 1);
    ASSERT_TRUE(autosave.tick(doc, 11.0, 1.5).ok());  // next tick at ~12.5: past it, so now
    EXPECT_EQ(autosave.writes(), 2);
    Result<Scene> recovered = loadSceneFile(autosave.path());
    ASSERT_TRUE(recovered.ok()) << recovered.error().message;
    EXPECT_TRUE(recovered.value() == doc.scene());
    ASSERT_TRUE(autosave.tick(doc, 11.1, 5.0).ok());  // unchanged since: no rewrite, however slow
    EXPECT_EQ(autosave.writes(), 2);
    fs::remove_all(dir);
}

// The viewport keeps rendering a resting view until temporal accumulation has converged, then
// stops; any change (an edit, the preset, the size) starts the count again.
TEST(EditorAccumulation, RendersUntilConvergedThenStopsAndRestartsOnChange) {
    Scene scene = loadDefault().scene();
    scene.temporal.enabled = true;
    scene.temporal.history_weight = 0.9f;
    const int n = convergedFrames(scene);
    // At rest the renderer averages the first 19 frames evenly (shd::temporalRestWeight: up to
    // (1 + w) / (1 - w) frames), then blends with w: the first frame's share is 1/19 = 5.3% after
    // 19 frames and 0.9 / 19 = 4.7% after 20 (the exponential rule alone needed 29: 0.9^29 = 0.047).
    EXPECT_EQ(n, 20);
    double share = 1.0;
    for (int k = 1; k < n; ++k) share *= shd::temporalRestWeight(k, 0.9f);
    EXPECT_LT(share, 0.05);
    EXPECT_GE(share / shd::temporalRestWeight(n - 1, 0.9f), 0.05);
    Accumulation acc;
    const ViewKey view{7, Quality::Low, 160, 90};
    int rendered = 0;
    for (int i = 0; i < 200 && acc.wantsFrame(view, scene, false); ++i) acc.rendered(view), ++rendered;
    EXPECT_EQ(rendered, n);
    EXPECT_EQ(acc.frames(), n);
    EXPECT_TRUE(acc.wantsFrame(view, scene, true));  // --frames times every frame

    ViewKey edited = view;
    edited.revision = 8;
    EXPECT_TRUE(acc.wantsFrame(edited, scene, false));
    acc.rendered(edited);
    EXPECT_EQ(acc.frames(), 1);
    ViewKey resized = edited;
    resized.width = 320;
    EXPECT_TRUE(acc.wantsFrame(resized, scene, false));
    ViewKey preset = edited;
    preset.quality = Quality::High;
    EXPECT_TRUE(acc.wantsFrame(preset, scene, false));

    // Without temporal every frame is the same: one is enough.
    scene.temporal.enabled = false;
    EXPECT_EQ(convergedFrames(scene), 1);
    EXPECT_FALSE(acc.wantsFrame(edited, scene, false));
    scene.temporal.enabled = true;
    // A long memory no longer churns: the progressive mean reaches 1/21 after 21 frames whatever w
    // (the exponential rule needed 299 at 0.99, capped at 64).
    scene.temporal.history_weight = 0.99f;
    EXPECT_EQ(convergedFrames(scene), 21);
    // A short one: the mean of 3 frames (cap (1 + 0.5) / (1 - 0.5) = 3), then halving: 1/3 x 0.5^3 < 5%.
    scene.temporal.history_weight = 0.5f;
    EXPECT_EQ(convergedFrames(scene), 6);
}

// A drag (begin ... end) and each frame that changed the document render coarse: low, at the
// scale of the window; the first frame at rest is full size at the chosen preset and restarts the
// history (so it converges to `brume render`); scale 1 never renders coarse.
TEST(EditorInteraction, CoarseWhileTheDocumentMovesFullWithARestartAtRest) {
    Interaction in(0.5);
    ViewPlan p = in.plan(1, false, Quality::High, 1280, 720);
    EXPECT_FALSE(p.coarse);  // the first frame of a session
    EXPECT_EQ(p.quality, Quality::High);
    EXPECT_EQ(p.width, 1280);
    p = in.plan(1, true, Quality::High, 1280, 720);  // begin: the drag starts, nothing moved yet
    EXPECT_TRUE(p.coarse);
    EXPECT_EQ(p.quality, Quality::Low);
    EXPECT_EQ(p.width, 640);
    EXPECT_EQ(p.height, 360);
    EXPECT_FALSE(p.restartHistory);
    p = in.plan(2, true, Quality::High, 1280, 720);
    EXPECT_TRUE(p.coarse);
    EXPECT_TRUE(p.moving);
    EXPECT_FALSE(p.restartHistory);
    p = in.plan(2, false, Quality::High, 1280, 720);  // end: at rest
    EXPECT_FALSE(p.coarse);
    EXPECT_FALSE(p.moving);
    EXPECT_EQ(p.quality, Quality::High);
    EXPECT_EQ(p.width, 1280);
    EXPECT_TRUE(p.restartHistory);
    p = in.plan(2, false, Quality::High, 1280, 720);
    EXPECT_FALSE(p.restartHistory);  // the accumulation goes on
    p = in.plan(3, false, Quality::High, 1280, 720);  // one edit (a wheel zoom): one coarse frame
    EXPECT_TRUE(p.coarse);
    EXPECT_TRUE(in.plan(3, false, Quality::High, 1280, 720).restartHistory);

    Interaction off(1.0);
    EXPECT_FALSE(off.plan(1, false, Quality::Medium, 320, 180).moving);
    p = off.plan(2, true, Quality::Medium, 320, 180);
    EXPECT_FALSE(p.coarse);
    EXPECT_TRUE(p.moving);  // full size, but still an interaction: the editor prepares only at rest
    EXPECT_EQ(p.quality, Quality::Medium);
    EXPECT_EQ(p.width, 320);
    p = off.plan(2, false, Quality::Medium, 320, 180);
    EXPECT_FALSE(p.restartHistory);
    EXPECT_FALSE(p.moving);
    EXPECT_TRUE(off.plan(3, false, Quality::Medium, 320, 180).moving);  // one edit
}

// The coarse frames' scale follows the measured frame time toward the budget: a frame over budget
// shrinks the next coarse image (pixels ~ budget / time, at most halved a step), one well under it
// grows it back up to the user's --interactive-scale, one inside the band keeps it (each size change
// reallocates); the first frame of a new size is not a measurement (steady false). The scale
// learnt is kept for the next drag; the froxel grid shrinks more slowly than the image.
TEST(EditorInteraction, CoarseScaleFollowsTheFrameTimeWithinTheBudget) {
    Interaction in(0.5, 50.0);
    in.plan(1, false, Quality::High, 1280, 720);
    ViewPlan p = in.plan(2, true, Quality::High, 1280, 720);
    EXPECT_TRUE(p.coarse);
    EXPECT_DOUBLE_EQ(p.scale, 0.5);
    EXPECT_FALSE(p.steady);  // the first coarse frame after a full one
    p = in.plan(3, true, Quality::High, 1280, 720);
    EXPECT_TRUE(p.steady);
    in.measured(160.0);  // 3.2x the budget: pixels x 0.25 (80% of the budget), clamped to halving
    p = in.plan(4, true, Quality::High, 1280, 720);
    EXPECT_NEAR(p.scale, 0.35, 0.02);
    EXPECT_LT(p.width, 640);
    EXPECT_NEAR(static_cast<double>(p.width) / p.height, 16.0 / 9.0, 0.02);
    EXPECT_FALSE(p.steady);
    const double shrunk = p.scale;
    in.measured(45.0);  // inside the band (60%..100% of the budget): no change
    EXPECT_DOUBLE_EQ(in.plan(5, true, Quality::High, 1280, 720).scale, shrunk);
    in.measured(60.0);  // just over: a little smaller, on the 1/40 steps
    p = in.plan(6, true, Quality::High, 1280, 720);
    EXPECT_LT(p.scale, shrunk);
    EXPECT_NEAR(p.scale * 40.0, std::round(p.scale * 40.0), 1e-9);
    // Never below the setting's minimum, however slow.
    for (int i = 0; i < 20; ++i) in.measured(10000.0);
    EXPECT_DOUBLE_EQ(in.scale(), Interaction::minScale());
    // At rest: the preset at full size, whatever was learnt; the next drag starts where it left.
    p = in.plan(7, false, Quality::High, 1280, 720);
    p = in.plan(7, false, Quality::High, 1280, 720);
    EXPECT_FALSE(p.coarse);
    EXPECT_EQ(p.width, 1280);
    EXPECT_DOUBLE_EQ(in.plan(8, true, Quality::High, 1280, 720).scale, Interaction::minScale());
    // Fast frames grow it back, to the user's scale and no further.
    for (int i = 0; i < 20; ++i) in.measured(5.0);
    EXPECT_DOUBLE_EQ(in.scale(), 0.5);
    // No budget: the scale stays where the user put it.
    Interaction fixed(0.5, 0.0);
    fixed.measured(10000.0);
    EXPECT_DOUBLE_EQ(fixed.scale(), 0.5);
    // The froxel grid of a coarse frame: the low grid of half the window at scale 0.5, its columns
    // going with the square root of the scale below (the image's with the scale itself).
    for (double s : {0.1, 0.25, 0.35, 0.5}) {
        const int w = static_cast<int>(std::lround(1280 * s));
        const int tile = coarseTilePx(16, s);
        EXPECT_NEAR((w + tile - 1) / tile, 40 * std::sqrt(s / 0.5), 40 * std::sqrt(s / 0.5) * 0.15) << s;
    }
    EXPECT_EQ(coarseTilePx(16, 0.5), 16);
    EXPECT_GE(coarseTilePx(1, 0.1), 1);
}

// Hiding is an undoable edit of view state: the viewport renders the scene without the object, a
// file never holds it, and it does not make the scene dirty.
TEST(EditorView, HideIsUndoableNotRenderedAndNotSaved) {
    const fs::path dir = tempDir("hide");
    Document doc = loadDefault((dir / "scene.json").string());
    ASSERT_GE(doc.scene().volumes.size(), 2u);
    run(doc, "hide volume 0");
    EXPECT_TRUE(doc.scene().volumes[0].hidden);
    EXPECT_FALSE(doc.dirty());
    EXPECT_TRUE(doc.canUndo());
    Scene without = doc.scene();
    without.volumes.erase(without.volumes.begin());
    EXPECT_EQ(withoutViewState(visibleScene(doc.scene())), withoutViewState(without));
    run(doc, "set volumes[1].medium.phase_g 0.5");  // an edit through the JSON form keeps it hidden
    EXPECT_TRUE(doc.scene().volumes[0].hidden);
    run(doc, "save");
    Result<Scene> saved = loadSceneFile((dir / "scene.json").string());
    ASSERT_TRUE(saved.ok());
    EXPECT_EQ(saved.value().volumes.size(), doc.scene().volumes.size());
    EXPECT_FALSE(saved.value().volumes[0].hidden);
    run(doc, "undo");
    run(doc, "undo");
    EXPECT_FALSE(doc.scene().volumes[0].hidden);
    EXPECT_EQ(visibleScene(doc.scene()).volumes.size(), doc.scene().volumes.size());
    EXPECT_FALSE(doc.apply(parseAction("hide volume 99").value()).ok());
    fs::remove_all(dir);
}

TEST(EditorView, FlyMovesAlongTheViewAndLookTurnsAboutTheEye) {
    Camera c;
    c.position = {0.0f, 2.0f, 10.0f};
    c.target = {0.0f, 2.0f, 0.0f};
    const Camera f = flyCamera(c, {1.0f, 0.5f, 2.0f});  // right, up, forward
    EXPECT_NEAR(glm::distance(f.position, glm::vec3(1.0f, 2.5f, 8.0f)), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::distance(f.target - f.position, c.target - c.position), 0.0f, 1e-5f);
    const Camera l = lookCamera(c, 30.0f, 0.0f);
    EXPECT_EQ(l.position, c.position);
    const glm::vec3 a = glm::normalize(c.target - c.position), b = glm::normalize(l.target - l.position);
    EXPECT_NEAR(glm::degrees(std::acos(glm::dot(a, b))), 30.0f, 1e-2f);
    EXPECT_LT(b.x, 0.0f);  // positive yaw turns left (counter-clockwise about +Y)
    const Camera p = lookCamera(c, 0.0f, 120.0f);  // stops short of straight up
    EXPECT_NEAR(glm::degrees(std::asin(glm::normalize(p.target - p.position).y)), 89.0f, 1e-2f);
}

TEST(EditorView, FrameSelectedFitsTheObjectInTheView) {
    Scene s;
    s.camera.position = {0.0f, 1.0f, 20.0f};
    s.camera.target = {0.0f, 0.0f, 0.0f};
    Volume v;
    v.type = VolumeType::Box;
    v.transform.translation = {5.0f, 1.0f, -3.0f};
    v.transform.scale = {4.0f, 2.0f, 1.0f};
    s.volumes.push_back(v);
    Result<Bounds> b = objectBounds(s, "volume", 0);
    ASSERT_TRUE(b.ok());
    const Camera c = frameCamera(s.camera, b.value());
    EXPECT_EQ(c.target, v.transform.translation);
    const glm::vec3 fwd = glm::normalize(c.target - c.position);
    EXPECT_NEAR(glm::dot(fwd, glm::normalize(s.camera.target - s.camera.position)), 1.0f, 1e-5f);
    // Every corner of the box lies inside the vertical field of view's cone.
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner = v.transform.translation + 0.5f * v.transform.scale *
                                 glm::vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
        const float angle = glm::degrees(std::acos(glm::dot(glm::normalize(corner - c.position), fwd)));
        EXPECT_LT(angle, 0.5f * c.fov_y_deg) << "corner " << i;
    }
    Volume fog;
    fog.type = VolumeType::Height;
    s.volumes.push_back(fog);
    EXPECT_FALSE(objectBounds(s, "volume", 1).ok());  // fills the world
    EXPECT_FALSE(objectBounds(s, "light", 0).ok());   // no such light
}

TEST(EditorView, PickSelectsTheNearestVolumeOrTheLightUnderTheCursor) {
    Scene s;
    s.camera.position = {0.0f, 0.0f, 10.0f};
    s.camera.target = {0.0f, 0.0f, 0.0f};
    s.camera.fov_y_deg = 60.0f;
    Volume far, near;
    far.type = near.type = VolumeType::Box;
    far.transform.scale = glm::vec3(2.0f);
    near.transform.translation = {0.0f, 0.0f, 4.0f};
    s.volumes = {far, near};
    Light light = makeLight(LightType::Point);
    light.position = {2.0f, 0.0f, 0.0f};
    s.lights = {light};
    const float aspect = 16.0f / 9.0f;
    auto at = [&](float u, float v) {
        std::optional<Picked> p = pick(s, aspect, u, v);
        return p ? p->kind + " " + std::to_string(p->index) : std::string("none");
    };
    EXPECT_EQ(at(0.5f, 0.5f), "volume 1");  // the near box hides the far one
    EXPECT_EQ(at(0.02f, 0.02f), "none");
    const float tanY = std::tan(glm::radians(30.0f));
    const float lightU = 0.5f + 0.5f * 2.0f / (10.0f * tanY * aspect);
    EXPECT_EQ(at(lightU, 0.5f), "light 0");
    EXPECT_EQ(at(lightU, 0.5f + 0.015f), "light 0");  // within 2% of the view height
    EXPECT_EQ(at(lightU, 0.5f + 0.03f), "none");
    s.volumes[1].hidden = true;                       // hidden objects are not picked
    EXPECT_EQ(at(0.5f, 0.5f), "volume 0");
    s.lights[0].hidden = true;
    EXPECT_EQ(at(lightU, 0.5f), "none");
}

// An ellipsoid or a cylinder is picked by its own surface, not its box: a ray through the box's
// corner misses them; the selection outline lies on the shape (points at radius 1 of a sphere of
// scale 2), and `add volume ellipsoid|cylinder` adds them.
TEST(EditorView, EllipsoidAndCylinderArePickedByTheirSurfaceAndOutlined) {
    Scene s;
    s.camera.position = {0.0f, 0.0f, 10.0f};
    s.camera.target = {0.0f, 0.0f, 0.0f};
    s.camera.fov_y_deg = 60.0f;
    Volume v;
    v.type = VolumeType::Ellipsoid;
    v.transform.scale = glm::vec3(2.0f);
    s.volumes = {v};
    const float aspect = 1.0f, tanY = std::tan(glm::radians(30.0f));
    // Window fraction of world (x, y, 0) seen from z = 9 (the box's front face is at z = 1).
    auto u = [&](float x) { return 0.5f + 0.5f * x / (9.0f * tanY * aspect); };
    auto v01 = [&](float y) { return 0.5f - 0.5f * y / (9.0f * tanY); };
    EXPECT_TRUE(pick(s, aspect, u(0.0f), v01(0.0f)).has_value());
    EXPECT_FALSE(pick(s, aspect, u(0.95f), v01(0.95f)).has_value());  // inside the box's front face, off the sphere
    s.volumes[0].type = VolumeType::Cylinder;
    EXPECT_TRUE(pick(s, aspect, u(0.6f), v01(0.5f)).has_value());
    EXPECT_FALSE(pick(s, aspect, u(0.95f), v01(0.95f)).has_value());
    s.volumes[0].type = VolumeType::Box;
    EXPECT_TRUE(pick(s, aspect, u(0.95f), v01(0.95f)).has_value());
    s.volumes[0].type = VolumeType::Ellipsoid;
    const auto lines = volumeWireframe(s.volumes[0]);
    ASSERT_FALSE(lines.empty());
    for (const auto& l : lines) EXPECT_NEAR(glm::length(l[0]), 1.0f, 1e-5f);
    s.volumes[0].type = VolumeType::Box;
    EXPECT_EQ(volumeWireframe(s.volumes[0]).size(), 12u);
    Document doc;
    run(doc, "add volume cylinder smoke");
    run(doc, "add volume ellipsoid cloud");
    EXPECT_EQ(doc.scene().volumes.back().type, VolumeType::Ellipsoid);
    EXPECT_EQ(doc.scene().volumes[doc.scene().volumes.size() - 2].type, VolumeType::Cylinder);
}

// The translate gizmo's drag: the object follows the cursor along one world axis only, snapped
// when asked; a ray along the axis gives no drag rather than a jump.
TEST(EditorView, GizmoDragMovesAlongOneAxisWithSnapping) {
    Camera c;
    c.position = {0.0f, 0.0f, 10.0f};
    c.target = {0.0f, 0.0f, 0.0f};
    const float aspect = 16.0f / 9.0f;
    auto rayAt = [&](glm::vec3 p) {
        const std::optional<glm::vec2> w = windowFromWorld(c, aspect, p);
        EXPECT_TRUE(w.has_value());
        return rayDirection(c, aspect, w->x, w->y);
    };
    const std::optional<glm::vec2> centre = windowFromWorld(c, aspect, c.target);
    ASSERT_TRUE(centre);
    EXPECT_NEAR(centre->x, 0.5f, 1e-6f);
    EXPECT_NEAR(centre->y, 0.5f, 1e-6f);
    EXPECT_FALSE(windowFromWorld(c, aspect, {0.0f, 0.0f, 20.0f}));  // behind the camera

    const glm::vec3 start{1.0f, 0.0f, 0.0f}, x{1.0f, 0.0f, 0.0f};
    const std::optional<float> s0 = axisParam(start, x, c.position, rayAt(start));
    ASSERT_TRUE(s0);
    EXPECT_NEAR(*s0, 0.0f, 1e-4f);
    // The cursor over the axis at x = 3.1: the object follows it there.
    const std::optional<float> s = axisParam(start, x, c.position, rayAt({3.1f, 0.0f, 0.0f}));
    ASSERT_TRUE(s);
    EXPECT_NEAR(axisDrag(start, x, *s0, *s, 0.0f).x, 3.1f, 1e-3f);
    EXPECT_NEAR(axisDrag(start, x, *s0, *s, 0.25f).x, 3.0f, 1e-5f);  // a 2.1 m move snaps to 2
    // The cursor also drifted up off the axis: only x changes.
    const std::optional<float> sUp = axisParam(start, x, c.position, rayAt({3.1f, 0.7f, 0.0f}));
    ASSERT_TRUE(sUp);
    const glm::vec3 drifted = axisDrag(start, x, *s0, *sUp, 0.0f);
    EXPECT_NEAR(drifted.x, 3.1f, 0.05f);
    EXPECT_EQ(drifted.y, 0.0f);
    EXPECT_EQ(drifted.z, 0.0f);
    EXPECT_FALSE(axisParam(start, {0.0f, 0.0f, 1.0f}, c.position, glm::vec3(0.0f, 0.0f, -1.0f)));

    Scene scene = loadDefault().scene();
    EXPECT_EQ(positionPath(scene, "volume", 0), "volumes[0].transform.translation");
    EXPECT_EQ(positionPath(scene, "light", 1), "lights[1].position");
    EXPECT_EQ(positionPath(scene, "light", 0), "");  // the sun has no position
}

namespace {

// A camera looking down at the origin from above and to the side, so every ring is seen at an angle.
Camera obliqueCamera() {
    Camera c;
    c.position = {3.0f, 8.0f, 6.0f};
    c.target = {0.0f, 0.0f, 0.0f};
    return c;
}

glm::vec3 cursorRay(const Camera& c, float aspect, glm::vec3 p) {
    const std::optional<glm::vec2> w = windowFromWorld(c, aspect, p);
    EXPECT_TRUE(w.has_value());
    return rayDirection(c, aspect, w->x, w->y);
}

}  // namespace

TEST(EditorGizmo, AQuarterTurnOfTheCursorAroundTheYRingRotatesNinetyDegrees) {
    const Camera c = obliqueCamera();
    const float aspect = 16.0f / 9.0f;
    const glm::vec3 pivot{0.0f, 0.0f, 0.0f}, y{0.0f, 1.0f, 0.0f};
    // The cursor on the ring over +X, then a quarter turn counter-clockwise (seen from +Y) at -Z.
    const std::optional<float> a0 = ringAngle(pivot, y, c.position, cursorRay(c, aspect, {1.0f, 0.0f, 0.0f}));
    const std::optional<float> a1 = ringAngle(pivot, y, c.position, cursorRay(c, aspect, {0.0f, 0.0f, -1.0f}));
    ASSERT_TRUE(a0 && a1);
    const float turn = wrapDegrees(*a1 - *a0);
    EXPECT_NEAR(turn, 90.0f, 1e-3f);
    // The object turns with the cursor: its local +X, under the cursor at the start, ends under it.
    const glm::vec3 r = rotateEuler({0.0f, 0.0f, 0.0f}, 1, turn);
    EXPECT_NEAR(r.y, 90.0f, 1e-3f);
    const glm::vec3 x = localAxis(r, 0);
    EXPECT_NEAR(x.x, 0.0f, 1e-4f);
    EXPECT_NEAR(x.z, -1.0f, 1e-4f);
    // Ctrl snaps to 15 degrees; a ring seen edge-on gives no angle.
    EXPECT_EQ(snapped(47.0f, 15.0f), 45.0f);
    EXPECT_EQ(snapped(53.0f, 15.0f), 60.0f);
    EXPECT_EQ(snapped(53.0f, 0.0f), 53.0f);
    EXPECT_FALSE(ringAngle(pivot, y, {5.0f, 0.0f, 0.0f}, {-1.0f, 0.0f, 0.0f}));
    // Steps a frame apart add up past half a turn instead of jumping back.
    float total = 0.0f, prev = 0.0f;
    for (float a : {100.0f, -160.0f, -60.0f}) total += wrapDegrees(a - prev), prev = a;
    EXPECT_NEAR(total, 300.0f, 1e-3f);
}

TEST(EditorGizmo, RotationsAboutWorldAxesComposeWithTheTransform) {
    // A box already tilted 30 degrees about X, turned 90 about world Y: R' = Ry(90) * Rx(30).
    const glm::vec3 start{30.0f, 0.0f, 0.0f};
    const glm::vec3 r = rotateEuler(start, 1, 90.0f);
    const glm::mat4 got = Transform{glm::vec3(0.0f), r, glm::vec3(1.0f)}.worldFromLocal();
    const glm::mat4 want = glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(0, 1, 0)) *
                           glm::rotate(glm::mat4(1.0f), glm::radians(30.0f), glm::vec3(1, 0, 0));
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) EXPECT_NEAR(got[i][j], want[i][j], 1e-5f) << i << "," << j;
    // Turning about the axis it already turns about keeps the numbers readable (no 180 flips),
    // also past the 90 degrees where the other Euler solution begins.
    EXPECT_NEAR(rotateEuler({0.0f, 80.0f, 0.0f}, 1, 20.0f).y, 100.0f, 1e-3f);
    EXPECT_NEAR(rotateEuler({0.0f, 0.0f, 350.0f}, 2, 20.0f).z, 370.0f, 1e-3f);
    EXPECT_EQ(rotateEuler({10.0f, 20.0f, 30.0f}, 0, 0.0f), glm::vec3(10.0f, 20.0f, 30.0f));
    const glm::vec3 d = rotateDirection({1.0f, 0.0f, 0.0f}, 2, 90.0f);  // about Z: +X to +Y
    EXPECT_NEAR(d.y, 1.0f, 1e-6f);
    EXPECT_NEAR(d.x, 0.0f, 1e-6f);
}

TEST(EditorGizmo, ScalingAlongXDoublesOnlyXWithSnapping) {
    const Camera c = obliqueCamera();
    const float aspect = 16.0f / 9.0f;
    const glm::vec3 pivot{0.0f, 0.0f, 0.0f}, x = localAxis({0.0f, 0.0f, 0.0f}, 0);
    // Grab the X handle's tip 1 m out, drag the cursor to 2 m along X.
    const std::optional<float> s0 = axisParam(pivot, x, c.position, cursorRay(c, aspect, {1.0f, 0.0f, 0.0f}));
    const std::optional<float> s = axisParam(pivot, x, c.position, cursorRay(c, aspect, {2.0f, 0.0f, 0.0f}));
    ASSERT_TRUE(s0 && s);
    const std::optional<float> f = axisScaleFactor(*s0, *s);
    ASSERT_TRUE(f);
    EXPECT_NEAR(*f, 2.0f, 1e-3f);
    const glm::vec3 start{0.5f, 2.0f, 3.0f};
    const glm::vec3 scaled = scaleDrag(start, 0, *f, 0.0f, 1e-4f);
    EXPECT_NEAR(scaled.x, 1.0f, 1e-3f);
    EXPECT_EQ(scaled.y, 2.0f);
    EXPECT_EQ(scaled.z, 3.0f);
    EXPECT_NEAR(scaleDrag(start, 0, 2.73f, 0.1f, 1e-4f).x, 1.4f, 1e-6f);  // 1.365 snaps to 1.4
    EXPECT_EQ(scaleDrag(start, 1, -3.0f, 0.0f, 1e-4f).y, 1e-4f);          // past the pivot: the minimum
    // The centre handle scales all three; a handle length right doubles.
    EXPECT_EQ(scaleDrag(start, 3, uniformScaleFactor(100.0f, 0.0f, 100.0f), 0.0f, 1e-4f), start * 2.0f);
    EXPECT_FALSE(axisScaleFactor(0.0f, 1.0f));
    // Scale handles follow the object's own axes: after 90 about Z, local X points along world Y.
    EXPECT_NEAR(localAxis({0.0f, 0.0f, 90.0f}, 0).y, 1.0f, 1e-6f);

    Scene scene = loadDefault().scene();
    scene.lights.push_back(makeLight(LightType::Spot));
    const size_t spot = scene.lights.size() - 1;
    EXPECT_EQ(rotationPath(scene, "volume", 0), "volumes[0].transform.rotation_deg");
    EXPECT_EQ(scalePath(scene, "volume", 0), "volumes[0].transform.scale");
    EXPECT_EQ(rotationPath(scene, "light", spot), "lights[" + std::to_string(spot) + "].direction");
    EXPECT_EQ(scalePath(scene, "light", spot), "");
    EXPECT_EQ(rotationPath(scene, "light", 0), "");  // the sun: no pivot to turn about
}

// Found by fuzzing (tests/fuzz/fuzz_action; the input is in its corpus): a byte that is not UTF-8 in
// a settings path ("set volumsedge_fa\xFEe 0.5") made the JSON writer throw, and the editor end on an
// uncaught exception. Now one sentence, and the document is unchanged; valid UTF-8 names still work.
TEST(EditorActions, TextThatIsNotUtf8IsAnErrorNotACrash) {
    Document doc = loadDefault();
    const std::string before = sceneToJson(doc.scene());
    for (const std::string& line : {std::string("set volumsedge_fa\xFE" "e 0.5"), std::string("rename volume 0 \"a\xC0\xAF\""),
                                    std::string("set volumes[0].name \"\xED\xA0\x80\"")}) {
        Result<Action> a = parseAction(line);
        ASSERT_FALSE(a.ok()) << line;
        EXPECT_EQ(a.error().message, "The action line is not valid UTF-8 text.");
        Result<void> r = doc.apply(Action{"set", {"volumes[0].name", line}});  // past the parser
        ASSERT_FALSE(r.ok());
        EXPECT_EQ(r.error().message, "set: an argument is not valid UTF-8 text.");
    }
    EXPECT_EQ(sceneToJson(doc.scene()), before);
    run(doc, "rename volume 0 \"brume \xC3\xA9t\xC3\xA9 \xE2\x9B\x85\"");
    // Also from fuzzing: a settings path with an empty step threw from the JSON pointer code.
    for (const char* path : {"volumes][.medium.phase_g", "volumes[0]..edge_fade", "volumes[]", "camera."}) {
        Result<void> r = doc.apply(Action{"set", {path, "0.5"}});
        ASSERT_FALSE(r.ok()) << path;
        EXPECT_EQ(r.error().message.find('\n'), std::string::npos);
    }
    // Also from fuzzing: a verb holding a space or a quote is written back quoted, as one word; so is
    // a word holding a carriage return (a separator outside quotes) or NUL bytes.
    for (const std::string& line : {std::string("dup\"key \\\"lamp\\\"\" x"), std::string("\"#not a comment\" 1"),
                                   std::string("add volume box \"R\r\0\0og\"", 23)}) {
        Result<Action> a = parseAction(line);
        ASSERT_TRUE(a.ok()) << line;
        Result<Action> back = parseAction(formatAction(a.value()));
        ASSERT_TRUE(back.ok()) << formatAction(a.value());
        EXPECT_EQ(back.value().verb, a.value().verb) << formatAction(a.value());
        EXPECT_EQ(back.value().args, a.value().args) << formatAction(a.value());
    }
    EXPECT_EQ(doc.scene().volumes[0].name, "brume \xC3\xA9t\xC3\xA9 \xE2\x9B\x85");
}

// The presenter's choice of path (app/editor/present_path.h): frames at the view's size (every
// frame at rest) keep the exact per-pixel display pass; smaller ones are tone mapped at their own
// size and blitted up, unless the window's format cannot be blitted with linear filtering.
TEST(EditorPresentPath, RestIsExactCoarseIsBlittedAndWithoutBlitFallsBack) {
    using editor::PresentPath;
    using editor::choosePresentPath;
    const glm::ivec2 window(1280, 720), coarse(256, 144);
    EXPECT_EQ(choosePresentPath(false, glm::ivec2(0), window, true), PresentPath::Background);
    EXPECT_EQ(choosePresentPath(false, glm::ivec2(0), window, false), PresentPath::Background);
    EXPECT_EQ(choosePresentPath(true, window, window, true), PresentPath::Window);
    EXPECT_EQ(choosePresentPath(true, window, window, false), PresentPath::Window);
    EXPECT_EQ(choosePresentPath(true, coarse, window, true), PresentPath::Upscale);
    EXPECT_EQ(choosePresentPath(true, coarse, window, false), PresentPath::Window);
    // A source of another aspect (a frame after a resize, before the next render) is scaled too.
    EXPECT_EQ(choosePresentPath(true, glm::ivec2(1280, 700), window, true), PresentPath::Upscale);
}

// The loop's sleep (app/editor/frame_pacing.h): none while anything moves; after a few quiet frames
// the idle sleep, shorter while a job's progress shows or a script's wait ends sooner; any activity or
// an early wake starts the count again.
TEST(EditorFramePacing, SleepsOnlyAfterQuietFramesAndWakesForActivity) {
    using editor::FrameActivity;
    using editor::FramePacer;
    FramePacer p;
    const FrameActivity quiet;
    auto busy = [](auto set) {
        FrameActivity a;
        set(a);
        return a;
    };
    EXPECT_EQ(p.next(busy([](FrameActivity& a) { a.rendered = true; })), 0.0);
    for (int i = 1; i < FramePacer::kSettleFrames; ++i) EXPECT_EQ(p.next(quiet), 0.0) << i;
    EXPECT_EQ(p.next(quiet), FramePacer::kIdleWaitSeconds);
    EXPECT_EQ(p.next(quiet), FramePacer::kIdleWaitSeconds);
    for (const FrameActivity& a : {busy([](FrameActivity& a) { a.rendered = true; }),
                                   busy([](FrameActivity& a) { a.scriptStepDue = true; }),
                                   busy([](FrameActivity& a) { a.playing = true; }),
                                   busy([](FrameActivity& a) { a.fixedFrames = true; }),
                                   busy([](FrameActivity& a) { a.woken = true; })}) {
        EXPECT_EQ(p.next(a), 0.0);
        for (int i = 1; i < FramePacer::kSettleFrames; ++i) EXPECT_EQ(p.next(quiet), 0.0) << i;
        EXPECT_GT(p.next(quiet), 0.0);
    }
    // A running job: redrawn at its progress rate, not at once and not at the idle rate.
    const FrameActivity job = busy([](FrameActivity& a) { a.jobRunning = true; });
    EXPECT_EQ(p.next(job), FramePacer::kProgressWaitSeconds);
    EXPECT_LT(FramePacer::kProgressWaitSeconds, FramePacer::kIdleWaitSeconds);
    // A script's pending wait that ends sooner than the sleep cuts it short; a longer one does not.
    EXPECT_EQ(p.next(busy([](FrameActivity& a) { a.scriptWaitLeft = 0.2; })), 0.2);
    EXPECT_EQ(p.next(busy([](FrameActivity& a) { a.scriptWaitLeft = 7.0; })), FramePacer::kIdleWaitSeconds);
    EXPECT_EQ(p.next(busy([](FrameActivity& a) {
                  a.jobRunning = true;
                  a.scriptWaitLeft = 0.05;
              })),
              0.05);
}

// The stand-ins' list (app/editor/view.h withStandIns): the shown volumes in their order, a dark copy of
// each volume of before that is gone, at its place; none when nothing is gone or when the shown list
// is not an ordered subset of before's by kind.
TEST(EditorStandIns, MissingVolumesComeBackDarkAtTheirPlaceAndNothingElse) {
    Volume box;
    box.type = VolumeType::Box;
    box.name = "box";
    box.medium.scattering = glm::vec3(0.5f);
    box.medium.emission = glm::vec3(0.1f);
    Volume fog = box;
    fog.type = VolumeType::Height;
    fog.name = "fog";
    Volume ellipsoid = box;
    ellipsoid.type = VolumeType::Ellipsoid;
    ellipsoid.name = "ellipsoid";
    KeyTrack track;
    track.target = "medium.scattering";
    ellipsoid.keys.push_back(track);
    Scene before;
    before.volumes = {box, fog, ellipsoid};

    Scene shown = before;
    shown.volumes.erase(shown.volumes.begin() + 1);  // the fog hidden or deleted
    shown.volumes[1].transform.translation.x = 3.0f;  // and the ellipsoid moved since
    const std::optional<Scene> s = withStandIns(shown, before.volumes);
    ASSERT_TRUE(s);
    ASSERT_EQ(s->volumes.size(), 3u);
    EXPECT_EQ(s->volumes[0], shown.volumes[0]);
    EXPECT_EQ(s->volumes[2], shown.volumes[1]);  // the moved one, as shown
    const Volume& dark = s->volumes[1];
    EXPECT_EQ(dark.name, "fog");
    EXPECT_EQ(dark.type, VolumeType::Height);
    EXPECT_EQ(dark.medium.scattering, glm::vec3(0.0f));
    EXPECT_EQ(dark.medium.absorption, glm::vec3(0.0f));
    EXPECT_EQ(dark.medium.emission, glm::vec3(0.0f));

    // A keyed volume's stand-in has no keys (a keyed medium would light it).
    Scene noEllipsoid = before;
    noEllipsoid.volumes.pop_back();
    const std::optional<Scene> k = withStandIns(noEllipsoid, before.volumes);
    ASSERT_TRUE(k);
    EXPECT_TRUE(k->volumes[2].keys.empty());
    EXPECT_EQ(k->volumes[2].medium.scattering, glm::vec3(0.0f));

    // Nothing gone, a volume added, or the shown list in another order: no stand-ins.
    EXPECT_FALSE(withStandIns(before, before.volumes));
    Scene reordered;
    reordered.volumes = {ellipsoid, box};
    EXPECT_FALSE(withStandIns(reordered, before.volumes));
    Scene added;
    added.volumes = {box, box};  // two boxes where before had one: not a subset by kind
    EXPECT_FALSE(withStandIns(added, before.volumes));
}
