#include "noise.h"

#include <algorithm>
#include <cmath>

#include "parallel.h"

namespace brume {

namespace {

// A 32-bit integer mix (xor-shift-multiply rounds): every input bit reaches every output bit, so
// neighbouring lattice points get unrelated gradients.
uint32_t mix(uint32_t h) {
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return h;
}

uint32_t hashLattice(glm::ivec3 c, uint32_t seed) {
    uint32_t h = mix(seed ^ 0x9e3779b9u);
    h = mix(h ^ static_cast<uint32_t>(c.x));
    h = mix(h ^ static_cast<uint32_t>(c.y));
    return mix(h ^ static_cast<uint32_t>(c.z));
}

// The 12 cube-edge directions: no axis is favoured and the dot product needs no normalization.
float gradientDot(uint32_t h, glm::vec3 d) {
    switch (h % 12u) {
        case 0: return d.x + d.y;
        case 1: return -d.x + d.y;
        case 2: return d.x - d.y;
        case 3: return -d.x - d.y;
        case 4: return d.x + d.z;
        case 5: return -d.x + d.z;
        case 6: return d.x - d.z;
        case 7: return -d.x - d.z;
        case 8: return d.y + d.z;
        case 9: return -d.y + d.z;
        case 10: return d.y - d.z;
        default: return -d.y - d.z;
    }
}

// C2-continuous blend: the field's second derivative is continuous across cells.
float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }

int wrap(int i, int period) {
    const int m = i % period;
    return m < 0 ? m + period : m;
}

}  // namespace

float periodicGradientNoise(glm::vec3 p, int period, uint32_t seed) {
    const glm::vec3 cell = glm::floor(p);
    const glm::vec3 f = p - cell;
    const glm::ivec3 c(cell);
    float corner[8];
    for (int n = 0; n < 8; ++n) {
        const glm::ivec3 o(n & 1, (n >> 1) & 1, (n >> 2) & 1);
        const glm::ivec3 lattice(wrap(c.x + o.x, period), wrap(c.y + o.y, period), wrap(c.z + o.z, period));
        corner[n] = gradientDot(hashLattice(lattice, seed), f - glm::vec3(o));
    }
    const glm::vec3 w(fade(f.x), fade(f.y), fade(f.z));
    const float x0 = glm::mix(corner[0], corner[1], w.x), x1 = glm::mix(corner[2], corner[3], w.x);
    const float x2 = glm::mix(corner[4], corner[5], w.x), x3 = glm::mix(corner[6], corner[7], w.x);
    return glm::mix(glm::mix(x0, x1, w.y), glm::mix(x2, x3, w.y), w.z);
}

namespace {

// fBm at tile coordinate t in [0, 1)^3: octave o has (frequency << o) cells per tile, so every
// octave's lattice period divides the tile and the sum stays periodic.
float fbm(glm::vec3 t, const NoiseTileParams& p) {
    float sum = 0.0f, amplitude = 1.0f;
    for (int o = 0; o < p.octaves; ++o) {
        const int cells = p.frequency << o;
        sum += amplitude * periodicGradientNoise(t * static_cast<float>(cells), cells, p.seed + 0x632be5abu * static_cast<uint32_t>(o));
        amplitude *= 0.5f;
    }
    return sum;
}

// Mean 0.5, largest deviation 0.5: the whole [0, 1] range is used and nothing is clipped.
void normalize(std::vector<float>& values) {
    double mean = 0.0;
    for (float v : values) mean += v;
    mean /= static_cast<double>(values.size());
    double deviation = 0.0;
    for (float v : values) deviation = std::max(deviation, std::abs(v - mean));
    const double scale = deviation > 0.0 ? 0.5 / deviation : 0.0;
    for (float& v : values) v = std::clamp(static_cast<float>(0.5 + (v - mean) * scale), 0.0f, 1.0f);
}

}  // namespace

std::vector<float> makeNoiseTile(const NoiseTileParams& p, int threads, const std::function<void(float)>& progress) {
    const size_t n = static_cast<size_t>(p.size);
    std::vector<float> values(n * n * n);
    const float inv = 1.0f / static_cast<float>(p.size);
    parallelFor(
        p.size, threads,
        [&](int k) {
            for (int j = 0; j < p.size; ++j)
                for (int i = 0; i < p.size; ++i) {
                    const glm::vec3 t = (glm::vec3(i, j, k) + 0.5f) * inv;
                    values[(static_cast<size_t>(k) * n + static_cast<size_t>(j)) * n + static_cast<size_t>(i)] = fbm(t, p);
                }
        },
        [&](int done) {
            if (progress) progress(static_cast<float>(done) / static_cast<float>(p.size));
        });
    normalize(values);
    return values;
}

}  // namespace brume
