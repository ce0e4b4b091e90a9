// Linear scene radiance, row-major from the top-left pixel.
#pragma once

#include <vector>

#include <glm/glm.hpp>

namespace brume {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<glm::vec3> pixels;

    Image() = default;
    Image(int w, int h) : width(w), height(h), pixels(static_cast<size_t>(w) * static_cast<size_t>(h), glm::vec3(0.0f)) {}
    glm::vec3& at(int x, int y) { return pixels[static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)]; }
    const glm::vec3& at(int x, int y) const { return pixels[static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)]; }
};

// Relative mean absolute error: sum |a - ref| / sum |ref| over all pixels and channels.
double relativeMeanAbsError(const Image& a, const Image& ref);

// Whether every channel of every pixel is finite.
bool allFinite(const Image& img);

}  // namespace brume
