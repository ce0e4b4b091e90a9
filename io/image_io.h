// Image files. PNG is for looking at (8-bit sRGB through the display transform of
// shaders/shared/tonemap.h); EXR keeps linear radiance for comparisons and compositing.
// No writer lets a NaN or Inf pixel reach a file: such an image is an Error.
#pragma once

#include <string>

#include "core/image.h"
#include "core/result.h"

namespace brume {

// Chooses the format by extension (.png or .exr, any case); anything else is an Error naming the path
// and the supported extensions.
Result<void> writeImage(const Image& img, const std::string& path, float exposure = 1.0f);

// 8-bit sRGB of shd::displayFromRadiance(radiance, exposure). Written atomically.
Result<void> writePng(const Image& img, const std::string& path, float exposure = 1.0f);

// 8-bit values of pixels that already are display values in [0, 1] (debug views): no exposure, no
// tone curve, no sRGB encoding. Written atomically.
Result<void> writeDisplayPng(const Image& img, const std::string& path);

// Linear RGB, no tone map: 32-bit float channels R, G, B, or 16-bit half (RGB only; magnitudes above
// 65504, the largest half, are clamped to it). Written atomically.
Result<void> writeExr(const Image& img, const std::string& path, bool half = false);

// Reads R, G, B of any EXR as float (missing channels read 0). For tests and tools.
Result<Image> readExr(const std::string& path);

// Decodes an 8-bit PNG's sRGB values to linear [0, 1]. It does not invert the tone map: for tests only.
Result<Image> readPngLinear(const std::string& path);

}  // namespace brume
