// What a `brume` subcommand hands back to main: an exit code and, on failure, the one sentence
// that main prints as "error: SENTENCE" (the whole of stderr on failure, so scripts can show it).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace brume::app {

// Exit codes are a contract with scripts and tests: 2 means the user can fix the input.
inline constexpr int kExitOk = 0;
inline constexpr int kExitInternal = 1;
inline constexpr int kExitBadInput = 2;

struct CommandResult {
    int exitCode = kExitOk;
    std::string error;  // empty on success
};

inline CommandResult success() { return {}; }
inline CommandResult badInput(std::string message) { return {kExitBadInput, std::move(message)}; }
inline CommandResult internalFailure(std::string message) { return {kExitInternal, std::move(message)}; }

// An output path the command can write: ending in `extension` (".vdb") in a folder that exists.
inline std::optional<CommandResult> checkOutputPath(const std::string& out, const std::string& extension) {
    const std::filesystem::path path(out);
    if (path.extension() != extension) return badInput(out + ": the output must be a " + extension + " file.");
    const std::filesystem::path dir = path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
    if (!std::filesystem::is_directory(dir)) return badInput(out + ": the folder " + dir.string() + " does not exist.");
    return std::nullopt;
}

}  // namespace brume::app
