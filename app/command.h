// What a `brume` subcommand hands back to main: an exit code and, on failure, the one sentence
// that main prints as "error: SENTENCE" (the whole of stderr on failure, so scripts can show it).
#pragma once

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

}  // namespace brume::app
