#include "influence.h"

#include <algorithm>
#include <cmath>

namespace brume {

glm::vec3 influencerPosition(const Influencer& f, float t) {
    if (f.path.keys.empty()) return glm::vec3(0.0f);
    return evaluateTrack(f.path, t);
}

double influenceWakeStep(const Influencer& f) {
    const double step = std::max(static_cast<double>(f.wake_step_s), settings::influencer_wake_step.min);
    if (!(f.wake_half_life_s > 0.0f) || f.wake_samples <= 0 || !(f.strength > shd::INFLUENCE_MIN_STRENGTH)) return step;
    const double live = static_cast<double>(f.wake_half_life_s) *
                        std::log2(static_cast<double>(f.strength) / static_cast<double>(shd::INFLUENCE_MIN_STRENGTH));
    return std::max(step, live / static_cast<double>(f.wake_samples));
}

shd::InfluenceSample influenceSample(const Influencer& f, glm::vec3 centre, float strength) {
    const float half = f.type == InfluencerType::Capsule ? 0.5f * std::max(f.length, 0.0f) : 0.0f;
    const float radius = std::max(f.radius, static_cast<float>(settings::influencer_radius.min));
    shd::InfluenceSample s;
    s.a = glm::vec4(centre - glm::vec3(0.0f, half, 0.0f), radius);
    s.b = glm::vec4(centre + glm::vec3(0.0f, half, 0.0f), strength);
    return s;
}

InfluenceSet compileInfluence(const std::vector<Influencer>& influencers, float t) {
    InfluenceSet set;
    for (const Influencer& f : influencers) {
        const float s = std::clamp(f.strength, 0.0f, 1.0f);
        if (!(s > 0.0f) || f.path.keys.empty()) continue;
        set.samples.push_back(influenceSample(f, influencerPosition(f, t), s));
        if (!(f.wake_half_life_s > 0.0f) || f.wake_samples <= 0) continue;
        const double step = influenceWakeStep(f);
        const double h = static_cast<double>(f.wake_half_life_s);
        glm::vec3 newest = influencerPosition(f, t);
        int taken = 0;
        // tau = k step for k = floor(t / step), floor(t / step) - 1, ... (in double: t may be large).
        for (double k = std::floor(static_cast<double>(t) / step); taken < f.wake_samples; k -= 1.0) {
            const double tau = k * step;
            const float strength = static_cast<float>(static_cast<double>(s) * std::exp2(-(static_cast<double>(t) - tau) / h));
            if (strength < shd::INFLUENCE_MIN_STRENGTH) break;
            ++taken;
            const glm::vec3 p = influencerPosition(f, static_cast<float>(tau));
            // A copy where a stronger (newer) one already is adds nothing: a resting influencer costs one sample.
            if (p == newest) continue;
            set.samples.push_back(influenceSample(f, p, strength));
            newest = p;
        }
    }
    set.header.count = glm::ivec4(static_cast<int>(set.samples.size()), 0, 0, 0);
    glm::vec3 lo(shd::BRUME_HUGE), hi(-shd::BRUME_HUGE);
    for (const shd::InfluenceSample& s : set.samples) {
        lo = glm::min(lo, glm::min(glm::vec3(s.a), glm::vec3(s.b)) - glm::vec3(s.a.w));
        hi = glm::max(hi, glm::max(glm::vec3(s.a), glm::vec3(s.b)) + glm::vec3(s.a.w));
    }
    set.header.boundsMin = glm::vec4(lo, 0.0f);
    set.header.boundsMax = glm::vec4(hi, 0.0f);
    return set;
}

float influenceFactor(const InfluenceSet& set, glm::vec3 p) {
    if (!shd::insideInfluenceBounds(set.header, p)) return 1.0f;
    float r = 0.0f;
    for (const shd::InfluenceSample& s : set.samples) r = std::max(r, shd::influenceSampleReduction(s, p));
    return 1.0f - r;
}

}  // namespace brume
