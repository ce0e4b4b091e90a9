// What keyframes may drive, and the scene at a time: the volume and light settings a KeyTrack may
// target (named by their key relative to the object, with their metadata in core/settings.h), and
// the scene with every track evaluated. compileScene bakes the keys itself, so the three renderers
// see the same keyed values; code that reads a Scene's lights or volumes directly bakes first.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "scene.h"

namespace brume {

// The setting a track on a volume (or light) of this type may target under `target`
// ("medium.scattering"); null when that type has no such keyable setting.
const Setting* volumeKeyTarget(VolumeType type, std::string_view target);
const Setting* lightKeyTarget(LightType type, std::string_view target);

// The targets keyable on that type, in the order of settings.h (for messages and the editor).
std::vector<std::string> volumeKeyTargets(VolumeType type);
std::vector<std::string> lightKeyTargets(LightType type);

// The values of every track at time t written into the object, clamped to the setting's range
// (a smooth curve may overshoot); a light's direction is normalized (a zero one keeps the old) and a
// spot's inner angle is kept within its outer angle. The tracks stay.
void applyKeys(Volume& v, float t);
void applyKeys(Light& l, float t);

bool hasKeys(const Scene& scene);

// The scene at time t: time_s = t, every track applied, and no tracks left, so baking again (or
// compileScene) changes nothing.
Scene bakeKeys(const Scene& scene, float t);

}  // namespace brume
