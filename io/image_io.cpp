#include "image_io.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <exception>
#include <filesystem>
#include <vector>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfRgbaFile.h>
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include "brume.h"
#include "io/atomic_file.h"

namespace brume {
namespace {

// Checks shared by every writer: something to write, and nothing that is not a number.
Result<void> checkWritable(const Image& img, const std::string& path) {
    if (img.width <= 0 || img.height <= 0 ||
        img.pixels.size() != static_cast<size_t>(img.width) * static_cast<size_t>(img.height))
        return Error{path + ": cannot write an image of " + std::to_string(img.width) + "x" +
                     std::to_string(img.height) + " pixels with " + std::to_string(img.pixels.size()) +
                     " values"};
    if (!allFinite(img)) return Error{path + ": refusing to write an image with NaN or infinite pixels"};
    return {};
}

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

unsigned char toByte(float v) { return static_cast<unsigned char>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); }

float srgbDecode(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

Result<void> writeExrFloat(const Image& img, const std::string& tmpPath) {
    Imf::Header header(img.width, img.height);
    for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
    Imf::OutputFile file(tmpPath.c_str(), header, 1);
    Imf::FrameBuffer fb;
    char* base = const_cast<char*>(reinterpret_cast<const char*>(img.pixels.data()));
    const size_t xStride = sizeof(glm::vec3);
    const size_t yStride = xStride * static_cast<size_t>(img.width);
    fb.insert("R", Imf::Slice(Imf::FLOAT, base, xStride, yStride));
    fb.insert("G", Imf::Slice(Imf::FLOAT, base + sizeof(float), xStride, yStride));
    fb.insert("B", Imf::Slice(Imf::FLOAT, base + 2 * sizeof(float), xStride, yStride));
    file.setFrameBuffer(fb);
    file.writePixels(img.height);
    return {};
}

// Half overflows to Inf above 65504; clamping keeps the file finite (such radiance is rare and is
// still far brighter than any display).
half toHalf(float v) { return half(std::clamp(v, -static_cast<float>(HALF_MAX), static_cast<float>(HALF_MAX))); }

Result<void> writeExrHalf(const Image& img, const std::string& tmpPath) {
    std::vector<Imf::Rgba> rgba(img.pixels.size());
    for (size_t i = 0; i < rgba.size(); ++i)
        rgba[i] = Imf::Rgba(toHalf(img.pixels[i].x), toHalf(img.pixels[i].y), toHalf(img.pixels[i].z), half(1.0f));
    Imf::RgbaOutputFile file(tmpPath.c_str(), img.width, img.height, Imf::WRITE_RGB);
    file.setFrameBuffer(rgba.data(), 1, static_cast<size_t>(img.width));
    file.writePixels(img.height);
    return {};
}

}  // namespace

Result<void> writeImage(const Image& img, const std::string& path, float exposure) {
    const std::string ext = lowerExtension(path);
    if (ext == ".png") return writePng(img, path, exposure);
    if (ext == ".exr") return writeExr(img, path);
    return Error{path + ": unsupported image extension \"" + std::filesystem::path(path).extension().string() +
                 "\"; supported: .png (8-bit sRGB, tone mapped), .exr (linear float)"};
}

// 8 bits per channel of display(pixel) in [0, 1].
template <class Display>
static Result<void> writePngOf(const Image& img, const std::string& path, Display display) {
    std::vector<unsigned char> bytes(img.pixels.size() * 3);
    for (size_t i = 0; i < img.pixels.size(); ++i) {
        const glm::vec3 d = display(img.pixels[i]);
        for (int c = 0; c < 3; ++c) bytes[i * 3 + static_cast<size_t>(c)] = toByte(d[c]);
    }
    return writeFileAtomic(path, [&](const std::string& tmpPath) -> Result<void> {
        if (!stbi_write_png(tmpPath.c_str(), img.width, img.height, 3, bytes.data(), img.width * 3))
            return Error{path + ": cannot write the PNG data"};
        return {};
    });
}

Result<void> writePng(const Image& img, const std::string& path, float exposure) {
    if (Result<void> r = checkWritable(img, path); !r) return r;
    if (!std::isfinite(exposure) || exposure < 0.0f)
        return Error{path + ": exposure " + std::to_string(exposure) + " must be finite and not negative"};
    return writePngOf(img, path, [exposure](glm::vec3 p) { return shd::displayFromRadiance(p, exposure); });
}

Result<void> writeDisplayPng(const Image& img, const std::string& path) {
    if (Result<void> r = checkWritable(img, path); !r) return r;
    return writePngOf(img, path, [](glm::vec3 p) { return p; });
}

Result<void> writeExr(const Image& img, const std::string& path, bool half) {
    if (Result<void> r = checkWritable(img, path); !r) return r;
    return writeFileAtomic(path, [&](const std::string& tmpPath) -> Result<void> {
        try {
            return half ? writeExrHalf(img, tmpPath) : writeExrFloat(img, tmpPath);
        } catch (const std::exception& e) {
            return Error{path + ": cannot write EXR: " + e.what()};
        }
    });
}

Result<Image> readExr(const std::string& path) {
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i dw = file.header().dataWindow();
        const int w = dw.max.x - dw.min.x + 1;
        const int h = dw.max.y - dw.min.y + 1;
        if (w <= 0 || h <= 0) return Error{path + ": EXR has an empty data window"};
        Image img(w, h);
        // OpenEXR addresses the buffer by absolute pixel coordinates, hence the offset base.
        const size_t xStride = sizeof(glm::vec3);
        const size_t yStride = xStride * static_cast<size_t>(w);
        char* base = reinterpret_cast<char*>(img.pixels.data()) - static_cast<ptrdiff_t>(dw.min.x) * static_cast<ptrdiff_t>(xStride) -
                     static_cast<ptrdiff_t>(dw.min.y) * static_cast<ptrdiff_t>(yStride);
        Imf::FrameBuffer fb;
        fb.insert("R", Imf::Slice(Imf::FLOAT, base, xStride, yStride, 1, 1, 0.0));
        fb.insert("G", Imf::Slice(Imf::FLOAT, base + sizeof(float), xStride, yStride, 1, 1, 0.0));
        fb.insert("B", Imf::Slice(Imf::FLOAT, base + 2 * sizeof(float), xStride, yStride, 1, 1, 0.0));
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        return img;
    } catch (const std::exception& e) {
        return Error{path + ": cannot read EXR: " + e.what()};
    }
}

Result<Image> readPngLinear(const std::string& path) {
    int w = 0, h = 0, n = 0;
    unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, 3);
    if (!data) return Error{path + ": cannot read PNG: " + stbi_failure_reason()};
    Image img(w, h);
    for (size_t i = 0; i < img.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c)
            img.pixels[i][c] = srgbDecode(static_cast<float>(data[i * 3 + static_cast<size_t>(c)]) / 255.0f);
    stbi_image_free(data);
    return img;
}

}  // namespace brume
