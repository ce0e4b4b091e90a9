// Display transform for PNG and the editor viewport: exposure, then the ACES filmic curve fitted by
// Narkowicz (2015) per channel, then the sRGB transfer function. EXR output skips all of it.
#ifndef BRUME_SHARED_TONEMAP_H
#define BRUME_SHARED_TONEMAP_H

#include "common.h"

BRUME_NAMESPACE_BEGIN

BRUME_FUNC float acesFilmic(float x) {
    float v = max(x, 0.0f);
    return clamp((v * (2.51f * v + 0.03f)) / (v * (2.43f * v + 0.59f) + 0.14f), 0.0f, 1.0f);
}

BRUME_FUNC float srgbEncode(float linear) {
    float c = clamp(linear, 0.0f, 1.0f);
    return c <= 0.0031308f ? 12.92f * c : 1.055f * pow(c, 1.0f / 2.4f) - 0.055f;
}

BRUME_FUNC vec3 displayFromRadiance(vec3 radiance, float exposure) {
    vec3 e = radiance * exposure;
    return vec3(srgbEncode(acesFilmic(e.x)), srgbEncode(acesFilmic(e.y)), srgbEncode(acesFilmic(e.z)));
}

BRUME_NAMESPACE_END

#endif
