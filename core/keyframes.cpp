#include "keyframes.h"

#include <algorithm>

namespace brume {

const char* toString(Interpolation i) { return i == Interpolation::Linear ? "linear" : "smooth"; }

namespace {

// Tangent (value per second) at key i of the smooth curve.
glm::vec3 tangentAt(const std::vector<Keyframe>& k, size_t i) {
    const size_t lo = i == 0 ? 0 : i - 1;
    const size_t hi = std::min(i + 1, k.size() - 1);
    const float dt = k[hi].time - k[lo].time;
    return dt > 0.0f ? (k[hi].value - k[lo].value) / dt : glm::vec3(0.0f);
}

}  // namespace

glm::vec3 evaluateTrack(const KeyTrack& track, float t) {
    const std::vector<Keyframe>& k = track.keys;
    if (k.empty()) return glm::vec3(0.0f);
    if (!(t > k.front().time)) return k.front().value;  // also NaN: the first value, never NaN
    if (t >= k.back().time) return k.back().value;
    // First key after t: the segment is [i - 1, i].
    const size_t i = static_cast<size_t>(
        std::upper_bound(k.begin(), k.end(), t, [](float x, const Keyframe& key) { return x < key.time; }) - k.begin());
    const Keyframe& a = k[i - 1];
    const Keyframe& b = k[i];
    const float h = b.time - a.time;
    const float u = (t - a.time) / h;
    if (track.interpolation == Interpolation::Linear) return a.value + (b.value - a.value) * u;
    const float u2 = u * u;
    const float u3 = u2 * u;
    const float h00 = 2.0f * u3 - 3.0f * u2 + 1.0f;
    const float h10 = u3 - 2.0f * u2 + u;
    const float h01 = -2.0f * u3 + 3.0f * u2;
    const float h11 = u3 - u2;
    return h00 * a.value + h10 * h * tangentAt(k, i - 1) + h01 * b.value + h11 * h * tangentAt(k, i);
}

}  // namespace brume
