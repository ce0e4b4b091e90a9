// The editor's viewport on the device: the renderer's output image (GpuRenderer::outputImage) ->
// a buffer of 8-bit pixels (window-sized, or the source's size for the editor's coarse frames,
// app/editor/present_path.h), through the PNG's display transform
// (shaders/display_body.glsl, shaders/shared/display.h), which the presenter copies into the
// swapchain image. It replaces a readback of the rgba32f image, a tone map on the CPU and an
// upload (docs/editor.md).
//
// Its own small descriptor set (the source image and the destination buffer), so the froxel
// frame's table is not involved. One frame in flight: record() rewrites the set, so the previous
// submission that used it must have finished.
#pragma once

#include "gpu_renderer.h"
#include "pipeline.h"
#include "shaders/shared/display.h"

namespace brume::gpu {

class DisplayPass {
public:
    static Result<DisplayPass> create(const Device& device);

    // Records: the renderer's compute writes of `source` made visible, the pass writing `window`
    // (params.windowSize pixels, 4 bytes each), then its writes made visible to transfer reads.
    void record(const Device& device, VkCommandBuffer cmd, const OutputImage& source, VkBuffer window,
                const shd::DisplayParams& params) const;

private:
    DescriptorBindings bindings_;  // binding 0: the source image, 1: the window's pixels
    ComputePass exact_;   // display.comp: a source of the viewport's size
    ComputePass scaled_;  // display_scaled.comp: bilinear from a source of another size
};

}  // namespace brume::gpu
