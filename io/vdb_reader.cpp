// Both sides of the isolated reader (io/vdb_reader.h): the child's main and the parent's spawn, wait
// and decode. The child runs the in-process import (io/vdb_inprocess.h); only bytes and JSON cross.
#include "vdb_reader.h"
#include "vdb_encoding.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nanovdb/NanoVDB.h>
#include <nlohmann/json.hpp>

#include "mesh_import.h"
#include "one_line.h"
#include "vdb_import.h"
#include "vdb_inprocess.h"

extern char** environ;

namespace brume {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr int kProgressFd = 3;
// With OUT "-", the reader writes the grid on descriptor 4 and result.json on 5: memory files the
// parent made (memfd_create), so nothing lands on disk and nothing is left behind by Ctrl-C or kill.
constexpr int kGridFd = 4;
constexpr int kResultFd = 5;
constexpr const char* kToDescriptors = "-";
constexpr const char* kReaderName = "brume-vdb-read";

// ---- wire format: VdbGridInfo <-> JSON ----

json vec3(glm::dvec3 v) { return json::array({v.x, v.y, v.z}); }
glm::dvec3 dvec3(const json& j) { return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()}; }
glm::ivec3 ivec3(const json& j) { return {j.at(0).get<int>(), j.at(1).get<int>(), j.at(2).get<int>()}; }

json toJson(const VdbGridInfo& g) {
    json m = json::array();
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) m.push_back(g.gridFromIndex[c][r]);
    return {{"name", g.name}, {"type", g.type}, {"class", g.gridClass}, {"voxel_size", vec3(g.voxelSize)},
            {"grid_from_index", m}, {"affine", g.affine}, {"active_voxels", g.activeVoxels},
            {"index_min", json::array({g.indexMin.x, g.indexMin.y, g.indexMin.z})},
            {"index_max", json::array({g.indexMax.x, g.indexMax.y, g.indexMax.z})},
            {"world_min", vec3(g.worldMin)}, {"world_max", vec3(g.worldMax)}, {"value_min", g.valueMin},
            {"value_max", g.valueMax}, {"nanovdb", g.nanovdbBytes}, {"nanovdb_fp16", g.nanovdbFp16Bytes},
            {"nanovdb_fp8", g.nanovdbFp8Bytes}};
}

VdbGridInfo fromJson(const json& j) {
    VdbGridInfo g;
    g.name = j.at("name").get<std::string>();
    g.type = j.at("type").get<std::string>();
    g.gridClass = j.at("class").get<std::string>();
    g.voxelSize = dvec3(j.at("voxel_size"));
    const json& m = j.at("grid_from_index");
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) g.gridFromIndex[c][r] = m.at(static_cast<size_t>(c * 4 + r)).get<double>();
    g.affine = j.at("affine").get<bool>();
    g.activeVoxels = j.at("active_voxels").get<uint64_t>();
    g.indexMin = ivec3(j.at("index_min"));
    g.indexMax = ivec3(j.at("index_max"));
    g.worldMin = dvec3(j.at("world_min"));
    g.worldMax = dvec3(j.at("world_max"));
    g.valueMin = j.at("value_min").get<double>();
    g.valueMax = j.at("value_max").get<double>();
    g.nanovdbBytes = j.at("nanovdb").get<uint64_t>();
    g.nanovdbFp16Bytes = j.at("nanovdb_fp16").get<uint64_t>();
    g.nanovdbFp8Bytes = j.at("nanovdb_fp8").get<uint64_t>();
    return g;
}

// ---- the child ----

bool writeFile(const fs::path& path, const void* data, size_t size) {
    std::ofstream out(path, std::ios::binary);
    out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
    return static_cast<bool>(out.flush());
}

bool writeAll(int fd, const void* data, size_t size) {
    const char* p = static_cast<const char*>(data);
    while (size > 0) {
        const ssize_t n = write(fd, p, size);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        p += n;
        size -= static_cast<size_t>(n);
    }
    return true;
}

bool toDescriptors(const fs::path& dir) { return dir == kToDescriptors; }

// Last, by rename (or, to a descriptor, read by the parent only after a clean exit): the parent
// never sees half a result.
bool writeResult(const fs::path& dir, const json& j) {
    // Invalid UTF-8 (an OpenVDB message quoting bytes of a corrupt file) is replaced, not thrown on.
    const std::string text = j.dump(-1, ' ', false, json::error_handler_t::replace);
    if (toDescriptors(dir)) return writeAll(kResultFd, text.data(), text.size());
    return writeFile(dir / "result.json.tmp", text.data(), text.size()) &&
           std::rename((dir / "result.json.tmp").c_str(), (dir / "result.json").c_str()) == 0;
}

// Writes "NN\n" (percent of the file read) on the progress descriptor, when the parent opened it.
std::function<void(float)> progressWriter() {
    if (fcntl(kProgressFd, F_GETFD) == -1) return {};
    return [](float fraction) {
        const std::string line = std::to_string(static_cast<int>(fraction * 100.0f)) + "\n";
        if (write(kProgressFd, line.data(), line.size()) < 0) return;  // the parent went away: keep reading
    };
}

// A corrupt length or count can make OpenVDB allocate and zero-fill gigabytes (a flipped byte in
// oiio_sphere.vdb's header made it touch 2.6 GB). The data-segment limit turns that into
// std::bad_alloc, an error value: small while the header and metadata are read, then what the grids
// declare (3x: the grid, its float copy, its NanoVDB), never above 3x the user's memory cap.
constexpr uint64_t kBaseBytes = uint64_t(512) << 20;

#if defined(__SANITIZE_ADDRESS__)
#define BRUME_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define BRUME_ASAN 1
#endif
#endif

void setDataLimit(uint64_t soft, uint64_t hard) {
#ifdef BRUME_ASAN
    // AddressSanitizer maps terabytes of shadow memory as private data before main(): under any data
    // limit its next allocation fails. Sanitized builds (scripts/test --sanitize, scripts/fuzz) rely
    // on the metadata cap alone.
    (void)soft;
    (void)hard;
#else
    const rlimit r{std::min(soft, hard), hard};
    setrlimit(RLIMIT_DATA, &r);
#endif
}

VdbImportOptions cappedOptions(uint64_t memoryLimitBytes) {
    const uint64_t hard = std::min<uint64_t>(memoryLimitBytes, uint64_t(1) << 40) * 3 + kBaseBytes;
    setDataLimit(kBaseBytes, hard);
    const rlimit noCore{0, 0};  // a crash is an expected outcome here: no core file
    setrlimit(RLIMIT_CORE, &noCore);
    VdbImportOptions options;
    options.memoryLimitBytes = memoryLimitBytes;
    options.progress = progressWriter();
    options.beforeRead = [hard](uint64_t declared) {
        setDataLimit(declared > 0 ? std::min<uint64_t>(declared, uint64_t(1) << 40) * 3 + kBaseBytes : hard, hard);
    };
    return options;
}

json runLoad(const std::string& file, const std::string& grid, uint64_t limit, const fs::path& dir) {
    VdbImportOptions options = cappedOptions(limit);
    options.grid = grid;
    Result<VdbLoad> r = loadVdbDensityInProcess(file, options);
    if (!r) return {{"ok", false}, {"error", r.error().message}};
    const DensityGrid& g = *r.value().grid;
    // The NanoVDB grid alone: the parent builds the occupancy cells that DensityGrid appends again.
    const bool written = toDescriptors(dir) ? writeAll(kGridFd, g.data(), g.nanoVdbSize())
                                            : writeFile(dir / "grid.nvdb", g.data(), g.nanoVdbSize());
    if (!written)
        return {{"ok", false}, {"error", file + ": cannot hand the converted grid to Brume (out of memory or disk)."}};
    return {{"ok", true}, {"grid_name", r.value().gridName}, {"warnings", r.value().warnings}};
}

// A mesh volume's fog grid (io/mesh_import.h): the mesh and OpenVDB's conversion may use the whole
// data limit at once (no metadata declares their size).
json runMesh(const std::string& file, const std::string& edgeFade, uint64_t limit, const fs::path& dir) {
    VdbImportOptions options = cappedOptions(limit);
    options.beforeRead(0);
    float fade = 0.0f;
    if (std::sscanf(edgeFade.c_str(), "%f", &fade) != 1) return {{"ok", false}, {"error", file + ": bad edge fade."}};
    Result<VdbLoad> r = loadMeshDensityInProcess(file, fade, options);
    if (!r) return {{"ok", false}, {"error", r.error().message}};
    const DensityGrid& g = *r.value().grid;
    const bool written = toDescriptors(dir) ? writeAll(kGridFd, g.data(), g.nanoVdbSize())
                                            : writeFile(dir / "grid.nvdb", g.data(), g.nanoVdbSize());
    if (!written)
        return {{"ok", false}, {"error", file + ": cannot hand the converted grid to Brume (out of memory or disk)."}};
    return {{"ok", true}, {"grid_name", r.value().gridName}, {"warnings", r.value().warnings}};
}

json runInfo(const std::string& file, uint64_t limit) {
    Result<std::vector<VdbGridInfo>> r = inspectVdbInProcess(file, cappedOptions(limit));
    if (!r) return {{"ok", false}, {"error", r.error().message}};
    json grids = json::array();
    for (const VdbGridInfo& g : r.value()) grids.push_back(toJson(g));
    return {{"ok", true}, {"grids", grids}};
}

}  // namespace

int vdbReaderMain(int argc, char** argv) {
    const std::string mode = argc > 1 ? argv[1] : "";
    const bool load = mode == "load" && argc == 6, info = mode == "info" && argc == 5;
    const bool mesh = mode == "mesh" && argc == 6;
    if (!load && !info && !mesh) {
        std::fprintf(stderr, "usage: %s load FILE GRID MEMORY_LIMIT_BYTES OUT_DIR | info FILE MEMORY_LIMIT_BYTES "
                             "OUT_DIR | mesh FILE EDGE_FADE_M MEMORY_LIMIT_BYTES OUT_DIR\n(Brume's isolated OpenVDB "
                             "reader; brume runs it.)\n", argv[0]);
        return 2;
    }
    const std::string file = argv[2];
    const uint64_t limit = std::strtoull(argv[load || mesh ? 4 : 3], nullptr, 10);
    const fs::path dir = argv[load || mesh ? 5 : 4];
    json result;
    try {
        result = load ? runLoad(file, argv[3], limit, dir) : mesh ? runMesh(file, argv[3], limit, dir) : runInfo(file, limit);
    } catch (const std::exception& e) {
        result = {{"ok", false}, {"error", file + ": not a readable OpenVDB file (" + std::string(e.what()) + ")."}};
    }
    return writeResult(dir, result) ? 0 : 3;
}

// ---- the parent ----

namespace {

// The reader's two outputs as anonymous memory files (memfd_create): no name on any disk, so a
// Ctrl-C or a kill of Brume at any moment leaves nothing behind (a temp folder did: brume-vdb-*).
class MemoryFiles {
public:
    MemoryFiles() : grid_(memfd_create("brume-vdb-grid", MFD_CLOEXEC)), result_(memfd_create("brume-vdb-result", MFD_CLOEXEC)) {}
    ~MemoryFiles() {
        if (grid_ >= 0) close(grid_);
        if (result_ >= 0) close(result_);
    }
    MemoryFiles(const MemoryFiles&) = delete;
    MemoryFiles& operator=(const MemoryFiles&) = delete;
    bool ok() const { return grid_ >= 0 && result_ >= 0; }
    int grid() const { return grid_; }
    int result() const { return result_; }

private:
    int grid_, result_;
};

// The whole content of a memory file ("" when unreadable).
std::string readAll(int fd) {
    std::string text;
    char buf[4096];
    for (off_t at = 0;;) {
        const ssize_t n = pread(fd, buf, sizeof buf, at);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        text.append(buf, static_cast<size_t>(n));
        at += n;
    }
    return text;
}

// Makes `fd` descriptor `target` (3 to 5) in the child. The source is first copied above them (fd 10
// and up, close-on-exec), so that no dup2 of the chain overwrites another's source and none is onto
// itself (which would keep close-on-exec). Returns that copy, to close after the spawn.
int addDup(posix_spawn_file_actions_t& actions, int fd, int target) {
    const int moved = fcntl(fd, F_DUPFD_CLOEXEC, 10);
    posix_spawn_file_actions_adddup2(&actions, moved, target);
    return moved;
}

// Beside the running executable (brume, brume-editor); else the build tree's, for the tests.
fs::path findReader() {
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    if (!ec && fs::exists(self.parent_path() / kReaderName, ec)) return self.parent_path() / kReaderName;
#ifdef BRUME_VDB_READER_BUILD_PATH
    if (fs::exists(BRUME_VDB_READER_BUILD_PATH, ec)) return BRUME_VDB_READER_BUILD_PATH;
#endif
    return {};
}

std::string crashed(const std::string& file) {
    return file + ": the OpenVDB reader crashed reading this file (it is corrupt or not a VDB file).";
}

// Forwards "NN\n" lines from the reader to options.progress; false at the end of the pipe.
bool forwardProgress(int fd, std::string& pending, const VdbImportOptions& options) {
    char buf[256];
    const ssize_t n = read(fd, buf, sizeof buf);
    if (n <= 0) return false;
    pending.append(buf, static_cast<size_t>(n));
    for (size_t eol; (eol = pending.find('\n')) != std::string::npos; pending.erase(0, eol + 1))
        if (options.progress) options.progress(static_cast<float>(std::atoi(pending.c_str())) / 100.0f);
    return true;
}

// Runs the reader to the end; returns its result.json, or the error sentence.
Result<json> runReader(const std::string& file, std::vector<std::string> args, const MemoryFiles& out,
                       const VdbImportOptions& options) {
    const fs::path reader = findReader();
    if (reader.empty())
        return Error{file + ": cannot read it: " + kReaderName + " (Brume's OpenVDB reader) is not installed beside brume."};
    args.insert(args.begin(), reader.string());
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);

    int fds[2];
    if (pipe2(fds, O_CLOEXEC) != 0) return Error{file + ": cannot start the OpenVDB reader (no pipe)."};
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);  // OpenVDB's own chatter
    const int moved[3] = {addDup(actions, fds[1], kProgressFd), addDup(actions, out.grid(), kGridFd),
                          addDup(actions, out.result(), kResultFd)};
    pid_t pid = 0;
    const int spawned = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    close(fds[1]);
    for (int fd : moved)
        if (fd >= 0) close(fd);
    if (spawned != 0) {
        close(fds[0]);
        return Error{file + ": cannot start the OpenVDB reader " + reader.string() + " (" + std::strerror(spawned) + ")."};
    }

    const auto start = std::chrono::steady_clock::now();
    std::string pending;
    int status = 0;
    bool timedOut = false;
    for (;;) {
        pollfd p{fds[0], POLLIN, 0};
        if (poll(&p, 1, 50) > 0 && (p.revents & POLLIN)) forwardProgress(fds[0], pending, options);
        const pid_t done = waitpid(pid, &status, WNOHANG);
        if (done == pid || (done < 0 && errno != EINTR)) break;
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (options.timeoutSeconds > 0.0 && seconds > options.timeoutSeconds) {
            kill(pid, SIGKILL);
            waitpid(pid, &status, 0);
            timedOut = true;
            break;
        }
    }
    if (!timedOut)  // what the reader wrote before it exited (its write end is closed: no blocking)
        while (forwardProgress(fds[0], pending, options)) {
        }
    close(fds[0]);
    if (timedOut) {
        std::ostringstream s;
        s << file << ": the OpenVDB reader did not finish within " << options.timeoutSeconds
          << " s (the file may be corrupt).";
        return Error{s.str()};
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return Error{crashed(file)};
    try {
        json result = json::parse(readAll(out.result()));
        // OpenVDB's messages can quote bytes of the file (a map type's name): every refusal the reader
        // sends is escaped here, the one place all of them pass, so it stays one line.
        if (!result.at("ok").get<bool>()) return Error{escapeControlCharacters(result.at("error").get<std::string>())};
        return result;
    } catch (const std::exception&) {
        return Error{crashed(file)};
    }
}

// The reader's NanoVDB grid, mapped and checked (a float grid of exactly the file's size) before use.
Result<DensityGridPtr> mapGrid(const std::string& file, int fd) {
    const std::string bad = file + ": the OpenVDB reader returned an unreadable grid.";
    struct stat st {};
    const size_t size = fstat(fd, &st) == 0 ? static_cast<size_t>(st.st_size) : 0;
    void* bytes = size >= sizeof(nanovdb::GridData) ? mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0) : MAP_FAILED;
    if (bytes == MAP_FAILED) return Error{bad};
    const auto* grid = static_cast<const nanovdb::GridData*>(bytes);
    const bool ok = grid->mMagic == NANOVDB_MAGIC_NUMBER && grid->mGridSize == size &&
                    grid->mGridType == nanovdb::GridType::Float;
    DensityGridPtr out = ok ? std::make_shared<const DensityGrid>(bytes, size) : nullptr;
    munmap(bytes, size);
    if (!out) return Error{bad};
    return out;
}

// The grid a "load" or "mesh" run of the reader left in out, in the asked encoding, with the name and
// warnings of its reply.
Result<VdbLoad> finishLoad(const std::string& path, const json& reply, const MemoryFiles& out,
                           const VdbImportOptions& options) {
    Result<DensityGridPtr> grid = mapGrid(path, out.grid());
    if (!grid) return grid.error();
    grid = encodeDensityGrid(grid.value(), options.encoding, path);
    if (!grid) return grid.error();
    VdbLoad load;
    load.grid = grid.value();
    try {
        load.gridName = reply.at("grid_name").get<std::string>();
        load.warnings = reply.at("warnings").get<std::vector<std::string>>();
    } catch (const std::exception&) {
        return Error{crashed(path)};
    }
    return load;
}

}  // namespace

Result<VdbLoad> loadVdbDensity(const std::string& path, const VdbImportOptions& options) {
    const MemoryFiles out;
    if (!out.ok()) return Error{path + ": cannot read it: no memory for the reader's output."};
    Result<json> r = runReader(path, {"load", path, options.grid, std::to_string(options.memoryLimitBytes),
                                      kToDescriptors}, out, options);
    if (!r) return r.error();
    return finishLoad(path, r.value(), out, options);
}

Result<VdbLoad> loadMeshDensity(const std::string& path, float edgeFadeM, const VdbImportOptions& options) {
    const MemoryFiles out;
    if (!out.ok()) return Error{path + ": cannot read it: no memory for the reader's output."};
    char fade[32];
    std::snprintf(fade, sizeof fade, "%.9g", static_cast<double>(edgeFadeM));
    Result<json> r = runReader(path, {"mesh", path, fade, std::to_string(options.memoryLimitBytes), kToDescriptors},
                               out, options);
    if (!r) return r.error();
    return finishLoad(path, r.value(), out, options);
}

Result<std::vector<VdbGridInfo>> inspectVdb(const std::string& path, const VdbImportOptions& options) {
    const MemoryFiles out;
    if (!out.ok()) return Error{path + ": cannot read it: no memory for the reader's output."};
    Result<json> r = runReader(path, {"info", path, std::to_string(options.memoryLimitBytes), kToDescriptors}, out,
                               options);
    if (!r) return r.error();
    std::vector<VdbGridInfo> grids;
    try {
        for (const json& g : r.value().at("grids")) grids.push_back(fromJson(g));
    } catch (const std::exception&) {
        return Error{crashed(path)};
    }
    return grids;
}

}  // namespace brume
