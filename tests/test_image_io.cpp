// Image output: PNG through the documented display transform, EXR lossless (float) or within half
// precision, and no file at all for bad input (non-finite pixels, unknown extensions, bad folders).
#include <gtest/gtest.h>

#include "test_support.h"

#include <cmath>
#include <filesystem>
#include <limits>

#include <unistd.h>

#include "brume.h"
#include "io/image_io.h"

namespace brume {
namespace {

namespace fs = std::filesystem;

// Each test's folder: brume_test_image_io_NAME_PID under the system temp folder.
struct TempDir : test::TempDir {
    explicit TempDir(const std::string& name) : test::TempDir("test_image_io", name) {}
};
using test::fileCount;

// A 64x36 gradient spanning 0 to ~100 in radiance, with different values per channel.
Image gradient() {
    Image img(64, 36);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            img.at(x, y) = glm::vec3(std::pow(2.0f, 0.1f * static_cast<float>(x)) - 1.0f, 0.03f * static_cast<float>(y),
                                     0.001f * static_cast<float>(x * y));
    return img;
}

float srgbFromLinear(float c) { return shd::srgbEncode(c); }

TEST(ImageIo, PngStoresTheDisplayTransformTo8Bits) {
    const TempDir tmp("png");
    const fs::path path = tmp.path / "a.png";
    const Image img = gradient();
    const float exposure = 0.7f;
    ASSERT_TRUE(writeImage(img, path.string(), exposure));
    Result<Image> back = readPngLinear(path.string());
    ASSERT_TRUE(back) << back.error().message;
    ASSERT_EQ(back.value().width, 64);
    ASSERT_EQ(back.value().height, 36);
    for (size_t i = 0; i < img.pixels.size(); ++i) {
        const glm::vec3 display = shd::displayFromRadiance(img.pixels[i], exposure);
        for (int c = 0; c < 3; ++c)  // 8-bit rounding: half a code value, plus float slack
            ASSERT_NEAR(srgbFromLinear(back.value().pixels[i][c]), display[c], 0.5f / 255.0f + 1e-5f) << i;
    }
}

TEST(ImageIo, PngKnownValues) {
    Image img(2, 1);
    img.at(0, 0) = glm::vec3(0.0f, 1.0f, 1.0e6f);
    img.at(1, 0) = glm::vec3(0.5f);
    const TempDir tmp("png_known");
    const fs::path path = tmp.path / "k.png";
    ASSERT_TRUE(writePng(img, path.string(), 2.0f));
    Result<Image> back = readPngLinear(path.string());
    ASSERT_TRUE(back) << back.error().message;
    const Image& b = back.value();
    EXPECT_EQ(b.at(0, 0).x, 0.0f);  // black stays black
    // ACES(2) = 2*(5.02+0.03) / (2*(4.86+0.59)+0.14) = 10.1/11.04, decoded from 8 bits.
    EXPECT_NEAR(b.at(0, 0).y, 10.1f / 11.04f, 0.005f);
    EXPECT_EQ(b.at(0, 0).z, 1.0f);  // the curve saturates at white
    // ACES(0.5 * 2) = (2.51 + 0.03) / (2.43 + 0.59 + 0.14).
    EXPECT_NEAR(b.at(1, 0).x, 2.54f / 3.16f, 0.005f);
    // Exposure scales radiance before the curve: twice the radiance at exposure 1 is the same image.
    Image doubled = img;
    for (glm::vec3& p : doubled.pixels) p *= 2.0f;
    const fs::path path1 = path.parent_path() / "k1.png";
    ASSERT_TRUE(writePng(doubled, path1.string(), 1.0f));
    Result<Image> back1 = readPngLinear(path1.string());
    ASSERT_TRUE(back1) << back1.error().message;
    EXPECT_EQ(back1.value().pixels, b.pixels);
}

TEST(ImageIo, ExrFloatRoundTripIsExact) {
    Image img = gradient();
    img.at(0, 0) = glm::vec3(1.0e-30f, 3.0e38f, -2.5f);  // extremes and a negative survive untouched
    img.at(1, 0) = glm::vec3(std::numeric_limits<float>::denorm_min(), 1.0f / 3.0f, 65504.0f * 4.0f);
    const TempDir tmp("exr");
    const fs::path path = tmp.path / "f.exr";
    ASSERT_TRUE(writeImage(img, path.string(), 123.0f));  // exposure does not apply to EXR
    Result<Image> back = readExr(path.string());
    ASSERT_TRUE(back) << back.error().message;
    ASSERT_EQ(back.value().width, img.width);
    ASSERT_EQ(back.value().height, img.height);
    EXPECT_EQ(back.value().pixels, img.pixels);
}

TEST(ImageIo, ExrHalfWithinHalfPrecision) {
    const Image img = gradient();
    const TempDir tmp("exr_half");
    const fs::path path = tmp.path / "h.exr";
    ASSERT_TRUE(writeExr(img, path.string(), true));
    Result<Image> back = readExr(path.string());
    ASSERT_TRUE(back) << back.error().message;
    for (size_t i = 0; i < img.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const float v = img.pixels[i][c];
            // Round to nearest with an 11-bit significand: relative 2^-11 for normals, and an
            // absolute 2^-25 (half the smallest subnormal step) below 2^-14.
            const float tol = std::max(std::abs(v) * 0x1p-11f, 0x1p-25f);
            ASSERT_NEAR(back.value().pixels[i][c], v, tol) << i << " " << c;
        }
}

TEST(ImageIo, ExrHalfClampsInsteadOfWritingInfinity) {
    Image img(1, 1);
    img.at(0, 0) = glm::vec3(1.0e6f, -1.0e6f, 1.0f);
    const TempDir tmp("exr_clamp");
    const fs::path path = tmp.path / "c.exr";
    ASSERT_TRUE(writeExr(img, path.string(), true));
    Result<Image> back = readExr(path.string());
    ASSERT_TRUE(back) << back.error().message;
    EXPECT_EQ(back.value().at(0, 0), glm::vec3(65504.0f, -65504.0f, 1.0f));
}

TEST(ImageIo, UnknownExtensionIsAnErrorAndWritesNothing) {
    const TempDir tmp("ext");
    const fs::path& dir = tmp.path;
    const std::string path = (dir / "out.jpg").string();
    Result<void> r = writeImage(gradient(), path);
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find(path), std::string::npos) << r.error().message;
    EXPECT_NE(r.error().message.find(".png"), std::string::npos) << r.error().message;
    EXPECT_NE(r.error().message.find(".exr"), std::string::npos) << r.error().message;
    EXPECT_EQ(fileCount(dir), 0u);
    EXPECT_TRUE(writeImage(gradient(), (dir / "UPPER.PNG").string()));  // extensions are case-blind
}

TEST(ImageIo, NonFinitePixelsNeverReachAFile) {
    const TempDir tmp("nan");
    const fs::path& dir = tmp.path;
    const fs::path png = dir / "a.png";
    ASSERT_TRUE(writeImage(gradient(), png.string()));
    const auto before = fs::file_size(png);
    for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
        Image img = gradient();
        img.at(5, 7).y = bad;
        EXPECT_FALSE(writeImage(img, png.string()));
        EXPECT_FALSE(writeImage(img, (dir / "b.exr").string()));
        EXPECT_FALSE(writeExr(img, (dir / "c.exr").string(), true));
    }
    EXPECT_EQ(fs::file_size(png), before);  // the old file is untouched
    EXPECT_EQ(fileCount(dir), 1u);
}

TEST(ImageIo, UnwritableFolderIsAnErrorWithoutLeftovers) {
    const TempDir tmp("unwritable");
    const fs::path& dir = tmp.path;
    for (const char* name : {"a.png", "a.exr"}) {
        const std::string path = (dir / "missing" / name).string();
        Result<void> r = writeImage(gradient(), path);
        ASSERT_FALSE(r);
        EXPECT_EQ(r.error().message, path + ": cannot write: No such file or directory");
    }
    fs::create_directory(dir / "taken.exr");  // a folder in the way: the rename fails, the temporary goes
    Result<void> r = writeImage(gradient(), (dir / "taken.exr").string());
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("taken.exr"), std::string::npos) << r.error().message;
    EXPECT_EQ(fileCount(dir), 1u);
}

TEST(ImageIo, ReadingMissingFilesIsAnError) {
    const TempDir tmp("read");
    const std::string missing = (tmp.path / "none.exr").string();
    Result<Image> e = readExr(missing);
    ASSERT_FALSE(e);
    EXPECT_NE(e.error().message.find(missing), std::string::npos);
    EXPECT_FALSE(readPngLinear(missing));
}

}  // namespace
}  // namespace brume
