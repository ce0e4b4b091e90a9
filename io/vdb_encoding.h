// The quantized encodings of a vdb volume's grid (the `encoding` key; docs/vdb.md "Encodings"): the
// OpenVDB reader hands over a float NanoVDB grid, which is re-encoded here as NanoVDB Fp16 or Fp8
// (values quantized per 8^3 leaf between the leaf's min and max) before anything samples it, so
// the CPU renderers and the GPU read the same quantized bytes.
#pragma once

#include <string>

#include "core/density_grid.h"
#include "core/result.h"

namespace brume {

// `grid` re-encoded; the same pointer when it already has that encoding. Only float grids are
// re-encoded (quantizing twice would add both errors). Errors name `path` (the grid's file).
Result<DensityGridPtr> encodeDensityGrid(const DensityGridPtr& grid, VdbEncoding encoding, const std::string& path);

}  // namespace brume
