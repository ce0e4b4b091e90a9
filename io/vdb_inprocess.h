// The OpenVDB reading itself, in the calling process. Only the isolated reader (brume-vdb-read,
// io/vdb_reader_main.cpp) calls these: OpenVDB 10 crashes on some corrupt files, so Brume never runs
// them in its own process; loadVdbDensity and inspectVdb (io/vdb_import.h) spawn that reader.
#pragma once

#include "vdb_import.h"

namespace brume {

Result<VdbLoad> loadVdbDensityInProcess(const std::string& path, const VdbImportOptions& options);
// Uses options.progress and options.beforeRead only.
Result<std::vector<VdbGridInfo>> inspectVdbInProcess(const std::string& path, const VdbImportOptions& options = {});

}  // namespace brume
