// Private to core/: one frame of the CPU froxel renderer and its temporal pass.
#pragma once

#include "render.h"

namespace brume {

// One frame against `history` (core/froxel_renderer.cpp); request.frames is ignored here.
FroxelResult renderFroxelFrameCpu(const Scene& scene, const RenderRequest& request, CpuHistory& history);

// The temporal pass, between light and integrate (core/temporal.cpp): resolves v.source and
// v.mediaExtinction against history.pair[t.readIndex] (when t.useHistory), writes the result into
// history.pair[t.writeIndex] and back into v.source and v.mediaExtinction for the integrate pass.
void temporalPassCpu(FroxelVolumes& v, CpuHistory& history, const TemporalFrame& t, int threads);

}  // namespace brume
