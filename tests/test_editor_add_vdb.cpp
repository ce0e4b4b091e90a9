// `add volume vdb NAME FILE` (the outliner's add, and scripts) loads the grid like `import vdb`: the
// new volume renders at once instead of staying empty until the scene is reopened. FILE is relative
// to the scene's folder; a file that cannot be read refuses the add, naming it.
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
