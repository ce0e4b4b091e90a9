#include "image.h"

#include <cmath>
#include <stdexcept>

namespace brume {

double relativeMeanAbsError(const Image& a, const Image& ref) {
    if (a.width != ref.width || a.height != ref.height) throw std::invalid_argument("image sizes differ");
    double num = 0.0, den = 0.0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            num += std::abs(static_cast<double>(a.pixels[i][c]) - static_cast<double>(ref.pixels[i][c]));
            den += std::abs(static_cast<double>(ref.pixels[i][c]));
        }
    }
    return den > 0.0 ? num / den : num;
}

bool allFinite(const Image& img) {
    for (const glm::vec3& p : img.pixels)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
    return true;
}

}  // namespace brume
