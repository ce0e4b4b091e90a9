// Density textures (VDB as tiled 3D noise): a synthetic periodic grid with a known field, applied to
// a box. Sampling is the known field with wrapping at the seam; the CPU froxel renderer matches the
// reference; one tile of translation changes nothing; scrolling by v for t equals the texture offset
// by v t; strength 0 is the plain volume exactly; fog shadows stay finite; bad input is one sentence
// with exit code 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sys/wait.h>

#include "core/compile.h"
#include "core/render.h"
#include "io/scene_json.h"
#include "io/vdb_import.h"
#include "test_support.h"
#include "vdb_test_util.h"

using namespace brume;
namespace fs = std::filesystem;

namespace {

using brume::test::readText;

constexpr int kN = 16;          // voxels per tile and axis
constexpr float kTile = 4.0f;   // tile_size_m
constexpr double kTwoPi = 6.283185307179586;

// Period kN in every index, mean exactly 1 over a tile (the sines sum to 0), minimum 0.1 > 0.
double field(int i, int j, int k) {
    return 1.0 + 0.6 * std::sin(kTwoPi * i / kN) + 0.3 * std::sin(kTwoPi * (j + k) / kN);
}

// The field on index box [0, kN - 1]^3, shifted by `shift` voxels along x (value at i is field(i - shift)).
DensityGridPtr writeTexture(const fs::path& file, int shift = 0) {
    auto g = test::makeGrid("noise", 0, kN - 1,
                            [shift](openvdb::Coord c) { return static_cast<float>(field(c.x() - shift, c.y(), c.z())); },
                            openvdb::math::Transform::createLinearTransform(0.1));
    test::writeGrids(file, {g});
    VdbImportOptions o;
    o.grid = "noise";
    Result<VdbLoad> r = loadVdbDensity(file.string(), o);
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
    return r.ok() ? r.value().grid : nullptr;
}

DensityTexture texture(const DensityGridPtr& grid, float strength = 1.0f, glm::vec3 scroll = glm::vec3(0.0f)) {
    DensityTexture t;
    t.file = "noise.vdb";
    t.grid = "noise";
    t.tile_size_m = kTile;
    t.scroll_mps = scroll;
    t.strength = strength;
    t.density = grid;
    t.mean = grid ? static_cast<float>(grid->activeBoxMean()) : 0.0f;
    return t;
}

// A 5 x 2 x 5 m box of dense, emissive fog under the shared test view, lit by a sun (with fog shadows)
// and the sky; froxels fine enough to resolve the 4 m texture period.
Scene texturedScene(const std::optional<DensityTexture>& tex) {
    Scene s = test::sceneWithTestView();
    Volume box = test::boxFog({0.0f, 1.0f, 0.0f}, {5.0f, 2.0f, 5.0f}, 0.1f, {0.5f, 0.6f, 0.7f}, glm::vec3(0.2f));
    box.medium.emission = {0.3f, 0.15f, 0.05f};
    box.density_texture = tex;
    s.volumes.push_back(box);
    Light sun = makeLight(LightType::Directional);
    sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    s.lights.push_back(sun);
    s.froxels.tile_px = 4;
    s.froxels.slices = 64;
    s.froxels.far = 20.0f;
    return s;
}

RenderRequest smallRequest() {
    RenderRequest r;
    r.width = 80;
    r.height = 45;
    r.threads = 2;
    return r;
}

double maxAbsDiff(const Image& a, const Image& b) {
    double m = 0.0;
    for (size_t i = 0; i < a.pixels.size(); ++i)
        m = std::max(m, static_cast<double>(glm::length(a.pixels[i] - b.pixels[i])));
    return m;
}

class DensityTextureTest : public ::testing::Test {
protected:
    DensityTextureTest()
        : dir_("density_texture", ::testing::UnitTest::GetInstance()->current_test_info()->name()),
          grid_(writeTexture(dir_.path / "noise.vdb")) {}
    test::TempDir dir_;
    DensityGridPtr grid_;
};

}  // namespace

// At voxel centres of the tile the factor is field / mean; half way across the seam (between voxel
// kN - 1 and the next tile's voxel 0) it is their average; a tile away, or at negative coordinates,
// the same. Strength 2 doubles the contrast and is held at >= 0.
TEST_F(DensityTextureTest, SamplesTheKnownPeriodicFieldWrappingAtTheSeam) {
    ASSERT_TRUE(grid_);
    EXPECT_NEAR(grid_->activeBoxMean(), 1.0, 1e-6);
    Scene s = texturedScene(texture(grid_));
    const CompiledScene cs = compileScene(s);
    const float voxel = kTile / kN;
    auto factor = [&](glm::vec3 p) { return densityTextureFactor(cs, 0, p); };
    for (int i : {0, 3, 7, 12, 15}) {
        const glm::vec3 p(static_cast<float>(i) * voxel, 2.0f * voxel, 5.0f * voxel);
        EXPECT_NEAR(factor(p), field(i, 2, 5), 1e-4) << i;
        EXPECT_NEAR(factor(p + glm::vec3(kTile, -kTile, 2.0f * kTile)), field(i, 2, 5), 1e-4) << i;
        EXPECT_NEAR(factor(p - glm::vec3(3.0f * kTile, 0.0f, 0.0f)), field(i, 2, 5), 1e-4) << i;
    }
    const glm::vec3 seam((kN - 0.5f) * voxel, 0.0f, 0.0f);
    EXPECT_NEAR(factor(seam), 0.5 * (field(kN - 1, 0, 0) + field(0, 0, 0)), 1e-4);
    s.volumes[0].density_texture->strength = 2.0f;
    const CompiledScene cs2 = compileScene(s);
    const glm::vec3 p(4.0f * voxel, 0.0f, 0.0f);  // field 1.6: factor 1 + 2 * 0.6
    EXPECT_NEAR(densityTextureFactor(cs2, 0, p), 1.0 + 2.0 * (field(4, 0, 0) - 1.0), 1e-4);
    const glm::vec3 q(12.0f * voxel, 0.0f, 0.0f);  // field 0.4: 1 + 2 * -0.6 < 0, held at 0
    EXPECT_EQ(densityTextureFactor(cs2, 0, q), 0.0f);
}

// The contrast exponent raises each voxel's value to it before the trilinear mix, and the texture
// is measured against the mean of value^exponent: at voxel centres the factor is field^e / mean(field^e),
// half way across the seam the average of the two voxels' field^e over that mean; strength 0 is the
// plain volume, exponent 0 a flat texture (factor 1).
TEST_F(DensityTextureTest, ExponentShapesEachVoxelAndKeepsTheMeanRule) {
    ASSERT_TRUE(grid_);
    const double e = 2.5;
    double mean = 0.0;
    for (int i = 0; i < kN; ++i)
        for (int j = 0; j < kN; ++j)
            for (int k = 0; k < kN; ++k) mean += std::pow(field(i, j, k), e);
    mean /= double(kN) * kN * kN;
    DensityTexture t = texture(grid_);
    t.exponent = static_cast<float>(e);
    t.mean = static_cast<float>(grid_->activeBoxMean(t.exponent));
    EXPECT_NEAR(t.mean, mean, 1e-5 * mean);
    Scene s = texturedScene(t);
    const CompiledScene cs = compileScene(s);
    const float voxel = kTile / kN;
    for (int i : {0, 4, 9, 12}) {
        const glm::vec3 p(static_cast<float>(i) * voxel, 3.0f * voxel, 1.0f * voxel);
        EXPECT_NEAR(densityTextureFactor(cs, 0, p), std::pow(field(i, 3, 1), e) / mean, 2e-4) << i;
    }
    const glm::vec3 seam((kN - 0.5f) * voxel, 0.0f, 0.0f);
    EXPECT_NEAR(densityTextureFactor(cs, 0, seam), 0.5 * (std::pow(field(kN - 1, 0, 0), e) + std::pow(field(0, 0, 0), e)) / mean, 2e-4);
    s.volumes[0].density_texture->strength = 0.0f;
    EXPECT_EQ(densityTextureFactor(compileScene(s), 0, seam), 1.0f);
    s.volumes[0].density_texture->strength = 1.0f;
    s.volumes[0].density_texture->exponent = 0.0f;
    s.volumes[0].density_texture->mean = static_cast<float>(grid_->activeBoxMean(0.0f));
    EXPECT_NEAR(densityTextureFactor(compileScene(s), 0, seam), 1.0f, 1e-6);
}

// The CPU froxel renderer (the GPU's oracle) matches the reference on the textured box about as well
// as on the plain one, and the texture changes the image far more than that error (so this can fail).
// Thin emissive fog over a black sky, unlit (lights add their own froxel error, the same with and
// without a texture), so the image is close to linear in the texture.
TEST_F(DensityTextureTest, FroxelCpuMatchesTheReference) {
    ASSERT_TRUE(grid_);
    auto thin = [&](const std::optional<DensityTexture>& tex) {
        Scene s = texturedScene(tex);
        s.lights.clear();
        s.ambient = glm::vec3(0.0f);
        s.volumes[0].medium.emission = {0.5f, 0.3f, 0.2f};
        s.volumes[0].medium.scattering = glm::vec3(0.15f);
        s.volumes[0].medium.absorption = glm::vec3(0.05f);
        // One froxel column per pixel and fine slices: the froxel renderer's footprint error (21% of
        // the texture's effect at 4 px tiles and 64 slices, 9% at 2 px) is gone, so what is compared
        // is the sampling of the texture.
        s.froxels.tile_px = 1;
        s.froxels.slices = 256;
        return s;
    };
    const Image ref = renderReference(thin(texture(grid_)), smallRequest());
    const Image froxel = renderFroxelCpu(thin(texture(grid_)), smallRequest()).image;
    const Image refPlain = renderReference(thin(std::nullopt), smallRequest());
    const Image froxelPlain = renderFroxelCpu(thin(std::nullopt), smallRequest()).image;
    // The texture's effect (textured minus plain) in each renderer: the froxel renderer's own edge
    // and depth error cancels, what is left is how it samples the texture.
    double deltaErr = 0.0, deltaRef = 0.0;
    for (size_t p = 0; p < ref.pixels.size(); ++p) {
        const glm::vec3 dRef = ref.pixels[p] - refPlain.pixels[p];
        const glm::vec3 dFroxel = froxel.pixels[p] - froxelPlain.pixels[p];
        deltaErr += static_cast<double>(glm::length(dFroxel - dRef));
        deltaRef += static_cast<double>(glm::length(dRef));
    }
    const double err = relativeMeanAbsError(froxel, ref);
    const double errPlain = relativeMeanAbsError(froxelPlain, refPlain);
    const double textureShare = relativeMeanAbsError(refPlain, ref);
    std::printf("froxel vs reference: textured %.3g, plain %.3g; texture's effect %.3g, its error %.3g\n", err,
                errPlain, textureShare, deltaErr / deltaRef);
    EXPECT_TRUE(allFinite(ref) && allFinite(froxel));
    EXPECT_LT(deltaErr / deltaRef, 0.01);
    EXPECT_LT(err, 0.01);
    EXPECT_GT(textureShare, 0.15);
}

// Translating the camera and the volume by exactly one tile (along x and z) gives the same image;
// half a tile does not.
TEST_F(DensityTextureTest, OneTileOfTranslationChangesNothing) {
    ASSERT_TRUE(grid_);
    const Scene s = texturedScene(texture(grid_));
    auto shifted = [&](glm::vec3 d) {
        Scene t = s;
        t.camera.position += d;
        t.camera.target += d;
        t.volumes[0].transform.translation += d;
        return renderFroxelCpu(t, smallRequest()).image;
    };
    const Image base = renderFroxelCpu(s, smallRequest()).image;
    const double tile = relativeMeanAbsError(shifted({kTile, 0.0f, -kTile}), base);
    const double half = relativeMeanAbsError(shifted({0.5f * kTile, 0.0f, 0.0f}), base);
    std::printf("one tile: %.3g, half a tile: %.3g\n", tile, half);
    EXPECT_LT(tile, 1e-4);
    EXPECT_GT(half, 0.02);
}

// Scene time t with scroll v equals time 0 with the texture grid shifted by v t (here 3 voxels along
// x, so the shifted grid is exact), and differs from time 0 with the unshifted grid.
TEST_F(DensityTextureTest, ScrollingForATimeEqualsTheTextureOffset) {
    ASSERT_TRUE(grid_);
    const DensityGridPtr shiftedGrid = writeTexture(dir_.path / "shifted.vdb", 3);
    ASSERT_TRUE(shiftedGrid);
    const float t = 1.5f;
    const glm::vec3 v(3.0f * kTile / kN / t, 0.0f, 0.0f);  // 3 voxels in 1.5 s
    Scene scrolled = texturedScene(texture(grid_, 1.0f, v));
    scrolled.time_s = t;
    const Image a = renderFroxelCpu(scrolled, smallRequest()).image;
    const Image b = renderFroxelCpu(texturedScene(texture(shiftedGrid)), smallRequest()).image;
    scrolled.time_s = 0.0f;
    const Image still = renderFroxelCpu(scrolled, smallRequest()).image;
    const double err = relativeMeanAbsError(a, b);
    const double moved = relativeMeanAbsError(still, b);
    std::printf("scrolled vs shifted grid %.3g; time 0 vs shifted grid %.3g\n", err, moved);
    EXPECT_LT(err, 1e-4);
    EXPECT_GT(moved, 0.01);
}

// Strength 0 is the plain volume to the bit, however the texture scrolls.
TEST_F(DensityTextureTest, StrengthZeroIsThePlainVolumeExactly) {
    ASSERT_TRUE(grid_);
    Scene s = texturedScene(texture(grid_, 0.0f, {0.7f, 0.1f, -0.3f}));
    s.time_s = 12.5f;
    const Image zero = renderFroxelCpu(s, smallRequest()).image;
    const Image plain = renderFroxelCpu(texturedScene(std::nullopt), smallRequest()).image;
    EXPECT_EQ(maxAbsDiff(zero, plain), 0.0);
}

// Time moves the noise, not the history: the temporal scene key ignores the scene time, so a drifting
// texture accumulates like a static one (the history clamp follows the drift).
TEST_F(DensityTextureTest, SceneTimeDoesNotResetTemporalHistory) {
    ASSERT_TRUE(grid_);
    Scene s = texturedScene(texture(grid_, 1.0f, {1.0f, 0.0f, 0.0f}));
    const glm::ivec3 dims(20, 12, 64);
    const uint64_t k0 = temporalSceneKey(compileScene(s), s, dims);
    s.time_s = 0.75f;
    EXPECT_EQ(temporalSceneKey(compileScene(s), s, dims), k0);
    s.volumes[0].density_texture->scroll_mps.x = 2.0f;  // a real change of the scene does reset it
    EXPECT_NE(temporalSceneKey(compileScene(s), s, dims), k0);
}

// Fog shadows see the texture's mean (the plain volume for strength <= 1): a textured box under a
// sun renders finite in both CPU renderers, and its mean radiance stays near the plain box's.
TEST_F(DensityTextureTest, FogShadowsStayFiniteAndNearThePlainVolume) {
    ASSERT_TRUE(grid_);
    for (float strength : {1.0f, 5.0f}) {
        const Scene s = texturedScene(texture(grid_, strength));
        const Image froxel = renderFroxelCpu(s, smallRequest()).image;
        EXPECT_TRUE(allFinite(froxel)) << strength;
        const double change = relativeMeanAbsError(froxel, renderFroxelCpu(texturedScene(std::nullopt), smallRequest()).image);
        std::printf("strength %.0f: textured vs plain %.3g\n", strength, change);
        EXPECT_LT(change, 0.5) << strength;
    }
}

// The detail layer (layered noise): the same known field as a second grid, tiled 4x finer, scrolled
// and sharpened, its factor multiplied into the texture's. Its own mean rule: strength 0 is the
// texture alone.
TextureLayer detailLayer(const DensityGridPtr& grid, float strength, float exponent, glm::vec3 scroll) {
    TextureLayer d = makeDetailLayer();
    d.file = "noise.vdb";
    d.grid = "noise";
    d.tile_size_m = kTile / 4.0f;
    d.scroll_mps = scroll;
    d.strength = strength;
    d.exponent = exponent;
    d.density = grid;
    d.mean = grid ? static_cast<float>(grid->activeBoxMean(exponent)) : 0.0f;
    return d;
}

// The box's density at texture voxel centres inside its full-density core is the closed form
// field(i, j, k) x (1 + s (field(i', j', k')^e / mean(field^e) - 1)), with (i', j', k') the detail
// voxel under the point after the detail's scroll (one detail voxel along x here).
TEST_F(DensityTextureTest, DetailLayerMultipliesItsOwnFactorIntoTheDensity) {
    ASSERT_TRUE(grid_);
    const float s = 0.6f, e = 2.0f, t = 0.5f;
    const float detailVoxel = kTile / 4.0f / kN;
    DensityTexture tex = texture(grid_);
    tex.detail = detailLayer(grid_, s, e, glm::vec3(detailVoxel / t, 0.0f, 0.0f));
    Scene scene = texturedScene(tex);
    scene.time_s = t;
    const CompiledScene cs = compileScene(scene);
    double mean = 0.0;
    for (int i = 0; i < kN; ++i)
        for (int j = 0; j < kN; ++j)
            for (int k = 0; k < kN; ++k) mean += std::pow(field(i, j, k), e);
    mean /= double(kN) * kN * kN;
    const float voxel = kTile / kN;  // 4 detail voxels
    auto wrap = [](int i) { return ((i % kN) + kN) % kN; };
    int checked = 0;
    for (int a : {1, 3, 6, 8})
        for (int b : {1, 4, 7})
            for (int c : {-8, -3, 2, 5}) {
                const glm::vec3 p(static_cast<float>(a) * voxel, static_cast<float>(b) * voxel, static_cast<float>(c) * voxel);
                const double detail = 1.0 + s * (std::pow(field(wrap(4 * a - 1), wrap(4 * b), wrap(4 * c)), e) / mean - 1.0);
                const double expected = field(wrap(a), wrap(b), wrap(c)) * std::max(detail, 0.0);
                EXPECT_NEAR(volumeDensity(cs, 0, p), expected, 1e-3 * expected + 1e-5) << a << " " << b << " " << c;
                ++checked;
            }
    EXPECT_EQ(checked, 48);
    // Without the detail the density is the texture's alone: the detail changed it (the test can fail).
    Scene plain = texturedScene(texture(grid_));
    const glm::vec3 p(3 * voxel, 4 * voxel, 2 * voxel);
    EXPECT_GT(std::abs(volumeDensity(compileScene(plain), 0, p) - volumeDensity(cs, 0, p)), 0.05);
}

// A detail of strength 0 renders the texture alone, to the bit, however it scrolls and whatever its
// exponent; a detail the size of the scene's features changes the image.
TEST_F(DensityTextureTest, DetailStrengthZeroIsTheTextureAloneExactly) {
    ASSERT_TRUE(grid_);
    DensityTexture tex = texture(grid_);
    tex.detail = detailLayer(grid_, 0.0f, 3.0f, {0.4f, -0.2f, 0.1f});
    Scene s = texturedScene(tex);
    s.time_s = 7.25f;
    Scene alone = texturedScene(texture(grid_));
    alone.time_s = 7.25f;
    const Image zero = renderFroxelCpu(s, smallRequest()).image;
    const Image textureAlone = renderFroxelCpu(alone, smallRequest()).image;
    EXPECT_EQ(maxAbsDiff(zero, textureAlone), 0.0);
    s.volumes[0].density_texture->detail->strength = 1.0f;
    s.volumes[0].density_texture->detail->tile_size_m = kTile;
    EXPECT_GT(relativeMeanAbsError(renderFroxelCpu(s, smallRequest()).image, textureAlone), 0.02);
}

// The CPU froxel renderer against the reference with both layers, as for the texture alone
// (FroxelCpuMatchesTheReference): the detail's effect (both layers minus the texture alone) is
// sampled within 1% and the image within 1%.
TEST_F(DensityTextureTest, DetailLayerFroxelCpuMatchesTheReference) {
    ASSERT_TRUE(grid_);
    auto thin = [&](bool detail) {
        DensityTexture tex = texture(grid_);
        if (detail) tex.detail = detailLayer(grid_, 0.8f, 1.5f, glm::vec3(0.0f));
        if (detail) tex.detail->tile_size_m = kTile / 2.0f;
        Scene s = texturedScene(tex);
        s.lights.clear();
        s.ambient = glm::vec3(0.0f);
        s.volumes[0].medium.emission = {0.5f, 0.3f, 0.2f};
        s.volumes[0].medium.scattering = glm::vec3(0.15f);
        s.volumes[0].medium.absorption = glm::vec3(0.05f);
        s.froxels.tile_px = 1;
        s.froxels.slices = 256;
        return s;
    };
    const Image ref = renderReference(thin(true), smallRequest());
    const Image froxel = renderFroxelCpu(thin(true), smallRequest()).image;
    const Image refAlone = renderReference(thin(false), smallRequest());
    const Image froxelAlone = renderFroxelCpu(thin(false), smallRequest()).image;
    double deltaErr = 0.0, deltaRef = 0.0;
    for (size_t p = 0; p < ref.pixels.size(); ++p) {
        const glm::vec3 dRef = ref.pixels[p] - refAlone.pixels[p];
        deltaErr += static_cast<double>(glm::length(froxel.pixels[p] - froxelAlone.pixels[p] - dRef));
        deltaRef += static_cast<double>(glm::length(dRef));
    }
    const double err = relativeMeanAbsError(froxel, ref);
    const double detailShare = relativeMeanAbsError(refAlone, ref);
    std::printf("froxel vs reference with a detail layer: %.3g; the detail's effect %.3g, its error %.3g\n", err,
                detailShare, deltaErr / deltaRef);
    EXPECT_TRUE(allFinite(ref) && allFinite(froxel));
    EXPECT_LT(deltaErr / deltaRef, 0.01);
    EXPECT_LT(err, 0.01);
    EXPECT_GT(detailShare, 0.05);
}

// The scene format: density_texture on every volume type round-trips; relative files resolve against
// the scene file's folder; loading fills the grid and its mean.
TEST_F(DensityTextureTest, SceneFilesReadWriteAndLoadTextures) {
    const std::string json = R"({"brume_scene": 1, "volumes": [
        {"type": "box", "density_texture": {"file": "noise.vdb", "grid": "noise", "tile_size_m": 4, "scroll_mps": [1, 0, -0.5], "strength": 0.7,
                                           "detail": {"file": "noise.vdb", "grid": "noise", "scroll_mps": [0, 0.5, 0], "exponent": 2}}},
        {"type": "height", "density_texture": {"file": "noise.vdb", "grid": "noise"}},
        {"type": "depth", "density_texture": {"file": "noise.vdb", "grid": "noise", "tile_size_m": 30}}]})";
    const fs::path file = dir_.path / "scene.json";
    std::ofstream(file) << json;
    Result<Scene> scene = loadSceneFile(file.string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const DensityTexture& t = *scene.value().volumes[0].density_texture;
    EXPECT_EQ(t.tile_size_m, 4.0f);
    EXPECT_EQ(t.scroll_mps, glm::vec3(1.0f, 0.0f, -0.5f));
    EXPECT_EQ(t.strength, 0.7f);
    EXPECT_EQ(scene.value().volumes[1].density_texture->tile_size_m, settings::texture_tile_size.f());
    ASSERT_TRUE(t.detail);
    EXPECT_EQ(t.detail->tile_size_m, settings::detail_tile_size.f());
    EXPECT_EQ(t.detail->scroll_mps, glm::vec3(0.0f, 0.5f, 0.0f));
    EXPECT_EQ(t.detail->strength, settings::detail_strength.f());
    EXPECT_EQ(t.detail->exponent, 2.0f);
    EXPECT_FALSE(scene.value().volumes[1].density_texture->detail);
    Result<Scene> again = parseScene(sceneToJson(scene.value()), "again.json");
    ASSERT_TRUE(again.ok()) << again.error().message;
    EXPECT_EQ(again.value(), scene.value());
    std::vector<std::string> warnings;
    ASSERT_TRUE(loadSceneGrids(scene.value(), file.string(), 1ull << 30, warnings).ok());
    for (const Volume& v : scene.value().volumes) {
        ASSERT_TRUE(v.density_texture->density);
        EXPECT_NEAR(v.density_texture->mean, 1.0f, 1e-5f);
    }
    ASSERT_TRUE(scene.value().volumes[0].density_texture->detail->density);
    EXPECT_NEAR(scene.value().volumes[0].density_texture->detail->mean, grid_->activeBoxMean(2.0f), 1e-5);
}

// Bad input: exit code 2 and one line naming the scene file and the JSON path.
TEST_F(DensityTextureTest, BadInputIsOneSentenceAndExitCodeTwo) {
    auto box = [](const std::string& tex) {
        return R"({"brume_scene": 1, "volumes": [{"type": "box", "density_texture": )" + tex + "}]}";
    };
    auto zero = test::makeGrid("noise", 0, 3, [](openvdb::Coord) { return 0.0f; },
                               openvdb::math::Transform::createLinearTransform(0.1), true);
    test::writeGrids(dir_.path / "zero.vdb", {zero});
    const struct {
        std::string tex, mention;
    } cases[] = {
        {R"({"file": "missing.vdb"})", "volumes[0].density_texture.file"},
        {R"({"file": "noise.vdb", "grid": "wind"})", "volumes[0].density_texture.file"},
        {R"({"file": "noise.vdb", "grid": "noise", "tile_size_m": 0})", "volumes[0].density_texture.tile_size_m"},
        {R"({"file": "noise.vdb", "strength": -1})", "volumes[0].density_texture.strength"},
        {R"({"file": "noise.vdb", "grid": "noise", "exponent": -0.5})", "volumes[0].density_texture.exponent"},
        {R"({"file": "noise.vdb", "octaves": 3})", "volumes[0].density_texture.octaves"},
        {R"({"grid": "noise"})", "volumes[0].density_texture.file"},
        {R"({"file": "zero.vdb", "grid": "noise"})", "volumes[0].density_texture.grid"},
        {R"({"file": "noise.vdb", "grid": "noise", "detail": {"file": "noise.vdb", "grid": "noise", "exponent": -1}})",
         "volumes[0].density_texture.detail.exponent"},
        {R"({"file": "noise.vdb", "grid": "noise", "detail": {"file": "noise.vdb", "grid": "noise", "strength": -0.1}})",
         "volumes[0].density_texture.detail.strength"},
        {R"({"file": "noise.vdb", "grid": "noise", "detail": {"grid": "noise"}})", "volumes[0].density_texture.detail.file"},
        {R"({"file": "noise.vdb", "grid": "noise", "detail": {"file": "missing.vdb"}})", "volumes[0].density_texture.detail.file"},
        {R"({"file": "noise.vdb", "grid": "noise", "detail": {"file": "zero.vdb", "grid": "noise"}})",
         "volumes[0].density_texture.detail.grid"},
    };
    for (const auto& c : cases) {
        std::ofstream(dir_.path / "scene.json") << box(c.tex);
        const std::string cmd = "cd '" + dir_.path.string() + "' && '" + BRUME_EXE +
                                "' render scene.json -o x.png --cpu --width 16 --height 9 >/dev/null 2>err.txt";
        const int status = std::system(cmd.c_str());
        ASSERT_TRUE(WIFEXITED(status)) << c.tex;
        EXPECT_EQ(WEXITSTATUS(status), 2) << c.tex;
        const std::string err = readText(dir_.path / "err.txt");
        EXPECT_EQ(err.rfind("error: ", 0), 0u) << err;
        EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
        EXPECT_NE(err.find("scene.json: " + c.mention), std::string::npos) << err;
    }
}

// brume render --time moves a scrolling texture (the image changes), --fps is range-checked.
TEST_F(DensityTextureTest, RenderTimeOptionScrollsTheTexture) {
    std::ofstream(dir_.path / "scene.json") << R"({"brume_scene": 1, "camera": {"position": [0, 1.8, 7], "target": [0, 1, 0]},
        "ambient": [0.2, 0.2, 0.2], "volumes": [{"type": "box", "transform": {"translation": [0, 1, 0], "scale": [5, 2, 5]},
        "medium": {"scattering": [0.6, 0.6, 0.6]},
        "density_texture": {"file": "noise.vdb", "grid": "noise", "tile_size_m": 4, "scroll_mps": [1, 0, 0]}}]})";
    auto render = [&](const std::string& args) {
        const std::string cmd = "cd '" + dir_.path.string() + "' && '" + BRUME_EXE +
                                "' render scene.json --cpu --width 32 --height 18 " + args + " >/dev/null 2>err.txt";
        const int status = std::system(cmd.c_str());
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    };
    ASSERT_EQ(render("-o t0.png"), 0) << readText(dir_.path / "err.txt");
    ASSERT_EQ(render("-o t0b.png --time 0"), 0);
    ASSERT_EQ(render("-o t1.png --time 1"), 0);
    ASSERT_EQ(render("-o seq.png --time 1 --frames 3 --fps 10"), 0) << readText(dir_.path / "err.txt");
    EXPECT_EQ(readText(dir_.path / "t0.png"), readText(dir_.path / "t0b.png"));
    EXPECT_NE(readText(dir_.path / "t0.png"), readText(dir_.path / "t1.png"));
    EXPECT_EQ(render("-o x.png --fps 0"), 2);
    EXPECT_NE(readText(dir_.path / "err.txt").find("--fps"), std::string::npos);
}
