// Crash-safe file output: a reader of `path` sees either the old file or the complete new one,
// never a partial write, because the new content goes to a temporary file in the same folder
// (same filesystem, so rename(2) replaces atomically) and is flushed to disk before the rename.
#pragma once

#include <functional>
#include <string>
#include <string_view>

#include "core/result.h"

namespace brume {

// Writes through `write(tmpPath)` to a temporary file in the destination's folder, then renames over
// `path`. On failure the temporary is removed and `path` is untouched. Error sentences name the path
// and the OS reason.
Result<void> writeFileAtomic(const std::string& path,
                             const std::function<Result<void>(const std::string& tmpPath)>& write);

Result<void> writeTextFileAtomic(const std::string& path, std::string_view text);

// Removes the temporaries that writes of `path` by processes no longer running left behind (a
// kill -9 during a save); those of running processes are left alone. Returns how many it removed.
int removeStaleTemporaries(const std::string& path);

}  // namespace brume
