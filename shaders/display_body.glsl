// The editor's viewport: the renderer's rgba32f output, scaled to the viewport (bilinear, built as
// display_scaled.comp; display.comp reads exact texels and serves a source of the viewport's size),
// through the PNG's display transform, packed into the 8-bit window-sized buffer the presenter copies
// into the swapchain image. One invocation per window pixel.
#include "types.h"
#include "display.h"

layout(local_size_x = SCREEN_GROUP_X, local_size_y = SCREEN_GROUP_Y, local_size_z = 1) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D source;
layout(std430, set = 0, binding = 1) writeonly buffer WindowBlock { uint windowPixels[]; };
layout(push_constant) uniform DisplayBlock { DisplayParams params; };

vec3 texel(ivec2 p) { return imageLoad(source, clamp(p, ivec2(0), params.sourceSize - 1)).rgb; }

vec3 sampleSource(ivec2 pixel) {
#ifndef BRUME_DISPLAY_SCALED
    return texel(pixel);
#else
    vec2 p = (vec2(pixel) + 0.5f) * vec2(params.sourceSize) / vec2(params.viewSize) - 0.5f;
    ivec2 p0 = ivec2(floor(p));
    vec2 w = p - vec2(p0);
    vec3 top = mix(texel(p0), texel(p0 + ivec2(1, 0)), w.x);
    vec3 bottom = mix(texel(p0 + ivec2(0, 1)), texel(p0 + ivec2(1, 1)), w.x);
    return mix(top, bottom, w.y);
#endif
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, params.windowSize))) return;
    uint packed;
    if (any(greaterThanEqual(pixel, params.viewSize))) {
        packed = DISPLAY_BACKGROUND * 0x010101u | (255u << 24u);
    } else {
        vec3 v = sampleSource(pixel);
        packed = packDisplayPixel(params.toneMap != 0 ? displayFromRadiance(v, 1.0f) : v, params.bgra);
    }
    windowPixels[pixel.y * params.windowSize.x + pixel.x] = packed;
}
