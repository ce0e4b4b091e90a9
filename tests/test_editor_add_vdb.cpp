// `add volume vdb NAME FILE` (the outliner's add, and scripts) loads the grid like `import vdb`: the
// new volume renders at once instead of staying empty until the scene is reopened. FILE is relative
// to the scene's folder; a file that cannot be read refuses the add, naming it. Edits keep a loaded
// density texture (the JSON form does not carry grids) and read it again when its file changes.
#include <gtest/gtest.h>

#include <string>

#include "app/editor/document.h"

using namespace brume;
using namespace brume::editor;

namespace {

const std::string kNoiseDir = std::string(BRUME_SOURCE_DIR) + "/assets/noise";

Result<void> run(Document& doc, const std::string& line) {
    Result<Action> a = parseAction(line);
    if (!a) return a.error();
    return doc.apply(a.value());
}

Document docIn(const std::string& dir) {
    Scene s;
    s.baseDir = dir;
    return Document(s, "");
}

}  // namespace

TEST(EditorAddVdb, AddedVdbVolumeHasItsGrid) {
    Document doc = docIn(kNoiseDir);
    ASSERT_TRUE(run(doc, "add volume vdb mist mist.vdb").ok());
    ASSERT_EQ(doc.scene().volumes.size(), 1u);
    const Volume& v = doc.scene().volumes[0];
    EXPECT_EQ(v.type, VolumeType::Vdb);
    EXPECT_EQ(v.name, "mist");
    ASSERT_TRUE(v.density) << "the grid is loaded with the add";
    EXPECT_FALSE(v.density->empty());
    EXPECT_NEAR(v.density->activeBoxMean(), 0.5, 1e-3);  // the shipped noise tile (brume noise: mean 0.5)
    // Undo removes it; redo brings it back with its grid.
    ASSERT_TRUE(run(doc, "undo").ok());
    EXPECT_TRUE(doc.scene().volumes.empty());
    ASSERT_TRUE(run(doc, "redo").ok());
    ASSERT_EQ(doc.scene().volumes.size(), 1u);
    EXPECT_TRUE(doc.scene().volumes[0].density);
}

TEST(EditorAddVdb, AbsolutePathWorksFromAnyFolder) {
    Document doc = docIn("/");
    ASSERT_TRUE(run(doc, "add volume vdb mist " + kNoiseDir + "/mist.vdb").ok());
    ASSERT_TRUE(doc.scene().volumes.at(0).density);
    EXPECT_FALSE(doc.scene().volumes[0].density->empty());
}

TEST(EditorAddVdb, UnreadableFileRefusesTheAdd) {
    Document doc = docIn(kNoiseDir);
    Result<void> r = run(doc, "add volume vdb ghost missing.vdb");
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("missing.vdb"), std::string::npos) << r.error().message;
    EXPECT_TRUE(doc.scene().volumes.empty());
    EXPECT_FALSE(doc.dirty());
}

TEST(EditorAddVdb, EditsKeepTheDensityTextureAndReloadItsFile) {
    // A box whose texture names a file of another folder: not loaded yet (as parsed, before loading).
    Scene s;
    s.baseDir = kNoiseDir;
    Volume box;
    box.density_texture = DensityTexture{};
    box.density_texture->file = "../scenes/absent.vdb";
    s.volumes.push_back(box);
    Document doc(s, "");
    Result<void> set = run(doc, "set volumes[0].density_texture.file mist.vdb");
    ASSERT_TRUE(set.ok()) << set.error().message;
    ASSERT_TRUE(doc.scene().volumes[0].density_texture->density) << "setting the file loads the texture";
    EXPECT_NEAR(doc.scene().volumes[0].density_texture->mean, 0.5f, 1e-3f);
    ASSERT_TRUE(run(doc, "set volumes[0].density_texture.strength 0.5").ok());
    ASSERT_TRUE(run(doc, "set volumes[0].edge_fade 0.2").ok());
    EXPECT_TRUE(doc.scene().volumes[0].density_texture->density) << "other edits keep the loaded texture";
    EXPECT_FALSE(run(doc, "set volumes[0].density_texture.file missing.vdb").ok());
    EXPECT_EQ(doc.scene().volumes[0].density_texture->file, "mist.vdb");
}
