// Influencers at a scene time: each one's shape now and its wake, as the shared samples that every
// renderer evaluates (shaders/shared/influence.h; docs/scene-format.md, "Influencers").
//
// The wake rule. An influencer with strength s and half-life h leaves, at every scene time tau that
// is a multiple of its wake step D (tau = k D, k an integer), a copy of its shape whose strength at
// scene time t >= tau is s 2^(-(t - tau) / h). The samples at time t are the shape at t (strength s)
// and the copies with tau <= t, newest first, until a copy's strength falls below
// INFLUENCE_MIN_STRENGTH or wake_samples copies are taken. A point's reduction is the max over the
// samples (never more than s, so the density never goes below (1 - s) x its value), and
//     D = max(wake_step_s, h log2(s / INFLUENCE_MIN_STRENGTH) / wake_samples),
// so the samples reach the end of the live wake. Nothing here depends on the frame times or on
// earlier frames: the samples are a closed function of the path and t, so any frame renders alone.
// The bound: where the influencer moved at most its radius per step D, the sampled wake is within the
// falloff's change over D x speed / 2 of the continuous one (max over every past tau); dropped copies
// change the density by less than INFLUENCE_MIN_STRENGTH.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "../shaders/shared/brume.h"
#include "scene.h"

namespace brume {

struct InfluenceSet {
    shd::InfluenceHeader header{};
    std::vector<shd::InfluenceSample> samples;
};

// The influencer's centre at scene time t (its path, held at the ends).
glm::vec3 influencerPosition(const Influencer& f, float t);

// The wake step D [s] (see above).
double influenceWakeStep(const Influencer& f);

// The shape of f centred at `centre` with the given strength.
shd::InfluenceSample influenceSample(const Influencer& f, glm::vec3 centre, float strength);

// Every influencer's samples at scene time t, with their bounding box (count 0 when none).
InfluenceSet compileInfluence(const std::vector<Influencer>& influencers, float t);

// The factor every volume's density is multiplied by at p: 1 - the max reduction, in [0, 1].
float influenceFactor(const InfluenceSet& set, glm::vec3 p);

}  // namespace brume
