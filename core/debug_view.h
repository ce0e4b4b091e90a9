// Debug views of the froxel renderers (RenderRequest::debugView): one depth slice of density,
// scattering or transmittance as a display image, with the ramp of shaders/shared/debug_view.h.
#pragma once

#include <string>

#include "render.h"

namespace brume {

// The slice image of `v` (the volumes of a finished frame) at v.frame's image size. Its pixels are
// display values in [0, 1]: write them without exposure or tone curve (io writeDisplayPng).
Image debugViewImage(const FroxelVolumes& v, int view, int slice);

// "final", "density", "scattering", "transmittance" <-> shd::DEBUG_VIEW_*.
bool parseDebugView(const std::string& text, int& view);
const char* debugViewName(int view);

// View depth range [m] of `slice` (clamped to the grid): its near and far side. Slice 0 also
// holds the gap from the camera to the froxel near (shaders/shared/froxel.h).
glm::vec2 debugSliceDepths(const shd::FrameUniforms& frame, int slice);

// One line for people: the view, the slice and its depths, the ramp's range and unit.
std::string debugViewLegend(const shd::FrameUniforms& frame, int view, int slice);
// The same for the frame a froxel renderer makes of scene and request.
std::string debugViewLegend(const Scene& scene, const RenderRequest& request);

}  // namespace brume
