// The editor's window from the renderer's output, on the device (shaders/display_body.glsl,
// gpu/display_pass.h): the same display transform and rounding as the PNG writer
// (io/image_io.cpp: displayFromRadiance, then round(clamp(v) * 255)), so the viewport's bytes are
// the PNG's, plus a bilinear upscale for the editor's coarse frames while the user interacts.
#ifndef BRUME_SHARED_DISPLAY_H
#define BRUME_SHARED_DISPLAY_H

#include "common.h"
#include "tonemap.h"

BRUME_NAMESPACE_BEGIN

// The window outside the viewport (before the first render, or a frame after a resize).
BRUME_CONST uint DISPLAY_BACKGROUND = 24u;

// Push constants of the display pass; 32 bytes (std430 and C++ agree: ivec2 is 8-byte aligned).
struct DisplayParams {
    ivec2 sourceSize;  // the renderer's output [px]
    ivec2 viewSize;    // the viewport in the window, from its top-left [px]; the source is scaled to it
    ivec2 windowSize;  // the window's image and the destination buffer [px]
    int toneMap;       // 1: radiance -> displayFromRadiance; 0: the source holds display values (debug views)
    int bgra;          // 1: store bytes as B, G, R, A (a B8G8R8A8 swapchain); 0: R, G, B, A
};

BRUME_FUNC uint displayByte(float v) { return uint(clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f); }

// One pixel as the window stores it: little-endian, the first channel in the low byte.
BRUME_FUNC uint packDisplayPixel(vec3 display, int bgra) {
    uint r = displayByte(display.x), g = displayByte(display.y), b = displayByte(display.z);
    if (bgra != 0) return b | (g << 8u) | (r << 16u) | (255u << 24u);
    return r | (g << 8u) | (b << 16u) | (255u << 24u);
}

BRUME_NAMESPACE_END

#endif
