#include "atomic_file.h"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

namespace brume {
namespace {

Error osError(const std::string& path, const char* what, int err) {
    return Error{path + ": " + what + ": " + std::strerror(err)};
}

// Temporary names are hidden, unique per process and call, and end in ".tmp" so that a leftover
// from a killed process is recognisable.
std::string tmpPathFor(const std::string& path, int attempt) {
    static std::atomic<unsigned> counter{0};
    const std::filesystem::path p(path);
    const std::string name = "." + p.filename().string() + "." + std::to_string(::getpid()) + "." +
                             std::to_string(counter++) + "." + std::to_string(attempt) + ".tmp";
    return (p.parent_path() / name).string();
}

// Creates the temporary with O_EXCL (never reuses someone else's file) and mode 0666 & ~umask, the
// permissions an ordinary new file gets.
Result<std::string> createTmp(const std::string& path) {
    for (int attempt = 0;; ++attempt) {
        std::string tmp = tmpPathFor(path, attempt);
        const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0) {
            ::close(fd);
            return tmp;
        }
        if (errno != EEXIST || attempt >= 100) return osError(path, "cannot write", errno);
    }
}

// Without the fsync a crash shortly after the rename can leave an empty file under the new name.
Result<void> syncFile(const std::string& path, const std::string& tmp) {
    const int fd = ::open(tmp.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return osError(path, "cannot write", errno);
    const int rc = ::fsync(fd);
    const int err = errno;
    ::close(fd);
    if (rc != 0) return osError(path, "cannot write", err);
    return {};
}

// Makes the rename itself durable. Best effort: some filesystems refuse fsync on a directory, and
// the new content is complete either way.
void syncFolder(const std::string& path) {
    const std::string folder = std::filesystem::path(path).parent_path().string();
    const int fd = ::open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    ::fsync(fd);
    ::close(fd);
}

}  // namespace

Result<void> writeFileAtomic(const std::string& path,
                             const std::function<Result<void>(const std::string& tmpPath)>& write) {
    if (path.empty()) return Error{"cannot write a file with an empty path"};
    Result<std::string> tmp = createTmp(path);
    if (!tmp) return tmp.error();
    const std::string& tmpPath = tmp.value();
    Result<void> r = write(tmpPath);
    if (r) r = syncFile(path, tmpPath);
    if (r && std::rename(tmpPath.c_str(), path.c_str()) != 0) r = osError(path, "cannot replace", errno);
    if (!r) {
        ::unlink(tmpPath.c_str());
        return r;
    }
    syncFolder(path);
    return r;
}

Result<void> writeTextFileAtomic(const std::string& path, std::string_view text) {
    return writeFileAtomic(path, [&](const std::string& tmpPath) -> Result<void> {
        const int fd = ::open(tmpPath.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
        if (fd < 0) return osError(path, "cannot write", errno);
        size_t done = 0;
        while (done < text.size()) {
            const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
            if (n < 0 && errno == EINTR) continue;
            if (n < 0) {
                const int err = errno;
                ::close(fd);
                return osError(path, "cannot write", err);
            }
            done += static_cast<size_t>(n);
        }
        if (::close(fd) != 0) return osError(path, "cannot write", errno);
        return {};
    });
}

int removeStaleTemporaries(const std::string& path) {
    // tmpPathFor's names: ".NAME.PID.COUNTER.ATTEMPT.tmp".
    const std::filesystem::path p(path);
    const std::string prefix = "." + p.filename().string() + ".";
    const std::filesystem::path folder = p.parent_path().empty() ? std::filesystem::path(".") : p.parent_path();
    std::error_code ec;
    int removed = 0;
    for (std::filesystem::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name.size() <= prefix.size() + 4 || name.rfind(prefix, 0) != 0 || !name.ends_with(".tmp")) continue;
        const std::string rest = name.substr(prefix.size());
        char* endp = nullptr;
        const long pid = std::strtol(rest.c_str(), &endp, 10);
        if (endp == rest.c_str() || *endp != '.' || pid <= 0) continue;
        if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;  // running (or not ours to tell)
        if (::unlink(it->path().c_str()) == 0) ++removed;
    }
    return removed;
}

}  // namespace brume
