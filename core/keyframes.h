// Keyframed settings: a volume's or light's numeric setting that changes with the scene time
// (docs/scene-format.md, "Keyframes"). A track holds keys in increasing time and interpolates them
// linearly or smoothly (Catmull-Rom); before the first and after the last key it holds the end value.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "settings.h"

namespace brume {

enum class Interpolation { Linear, Smooth };

struct Keyframe {
    float time = 0.0f;       // scene time [s]
    glm::vec3 value{0.0f};   // a scalar setting uses x only
    bool operator==(const Keyframe&) const = default;
};

struct KeyTrack {
    std::string target;      // the setting's key relative to its object: "medium.scattering", "intensity"
    Interpolation interpolation = Interpolation::Linear;
    std::vector<Keyframe> keys;  // at least one, times strictly increasing (the reader checks)
    bool operator==(const KeyTrack&) const = default;
};

const char* toString(Interpolation i);

// The track's value at time t. Smooth: the cubic Hermite curve through the keys whose tangent at an
// inner key is the finite-difference Catmull-Rom one, (v[i+1] - v[i-1]) / (t[i+1] - t[i-1]), and at an
// end key the one-sided difference; it passes through every key, so on a key it is that key's value.
glm::vec3 evaluateTrack(const KeyTrack& track, float t);

}  // namespace brume
