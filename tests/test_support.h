// Helpers shared by the test binaries.
#pragma once

#include <filesystem>
#include <iterator>
#include <string>
#include <system_error>

#include <unistd.h>

namespace brume::test {

// A fresh, empty folder per test, unique per process (other build folders may run the same test
// at the same time), removed at the end of the test.
struct TempDir {
    std::filesystem::path path;
    TempDir(const std::string& prefix, const std::string& name)
        : path(std::filesystem::temp_directory_path() / ("brume_" + prefix + "_" + name + "_" + std::to_string(::getpid()))) {
        std::filesystem::remove_all(path);
        std::filesystem::create_directories(path);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
};

inline size_t fileCount(const std::filesystem::path& dir) {
    return static_cast<size_t>(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()));
}

}  // namespace brume::test
