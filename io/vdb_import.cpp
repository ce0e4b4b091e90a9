#include "vdb_import.h"
#include "mesh_import.h"
#include "vdb_inprocess.h"
#include "vdb_stream.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>


#include <openvdb/openvdb.h>
#include <openvdb/io/DelayedLoadMetadata.h>
#include <openvdb/io/Stream.h>
#include <openvdb/tools/LevelSetUtil.h>
#include <nanovdb/util/OpenToNanoVDB.h>

namespace brume {
namespace {

namespace fs = std::filesystem;

// Files above this size get status lines (in-process reads; the reader process reports progress).
constexpr uintmax_t kLargeFileBytes = uintmax_t(32) << 20;

void initOpenVdb() {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

std::string className(openvdb::GridClass c) {
    switch (c) {
        case openvdb::GRID_LEVEL_SET: return "level set";
        case openvdb::GRID_FOG_VOLUME: return "fog volume";
        case openvdb::GRID_STAGGERED: return "staggered";
        default: return "unknown";
    }
}

bool isScalar(const openvdb::GridBase& g) {
    return g.isType<openvdb::FloatGrid>() || g.isType<openvdb::DoubleGrid>();
}

// Every grid of the file, in file order, read through VdbFileBuf (io/vdb_stream.h): a read past the
// end of the file throws. Without delayed loading, so no memory map can fault later.
openvdb::GridPtrVecPtr readGrids(const std::string& path, const std::function<void(float)>& progress) {
    initOpenVdb();
    VdbFileBuf buf(path, progress);
    if (!buf.isOpen()) throw std::runtime_error("cannot open it");
    std::istream in(&buf);
    in.exceptions(std::ios::badbit);  // the buffer's exception reaches the caller, not a quiet failbit
    openvdb::io::Stream stream(in, /*delayLoad=*/false);
    return stream.getGrids();
}

struct FileGrids {
    openvdb::GridPtrVecPtr grids;
    std::vector<std::string> names;  // "name" or "name#i" where names repeat
};

void nameGrids(FileGrids& f) {
    std::map<std::string, int> count, seen;
    for (const auto& g : *f.grids) ++count[g->getName()];
    for (const auto& g : *f.grids) {
        const std::string& n = g->getName();
        f.names.push_back(count[n] > 1 ? n + "#" + std::to_string(seen[n]++) : n);
    }
}

// OpenVDB writes each grid's active voxel count into its metadata (file_voxel_count); a reader that
// hits the end of a truncated uncompressed file fills the rest with zeros without a word, so a grid
// that comes back with another count is truncated or corrupt.
Result<void> checkComplete(const std::string& path, const std::string& name, const openvdb::GridBase& g) {
    const auto declared = g.getMetadata<openvdb::Int64Metadata>(openvdb::GridBase::META_FILE_VOXEL_COUNT);
    if (!declared) return {};
    const uint64_t active = g.activeVoxelCount();
    if (declared->value() >= 0 && static_cast<uint64_t>(declared->value()) == active) return {};
    return Error{path + ": grid '" + name + "' holds " + std::to_string(active) + " active voxels where the file lists " +
                 std::to_string(declared->value()) + " (the file is truncated or corrupt)."};
}

// Reads every grid (file versions, compression and half floats are the library's business).
Result<FileGrids> readAll(const std::string& path, const std::function<void(const std::string&)>& status,
                          const std::function<void(float)>& progress) {
    std::error_code ec;
    const uintmax_t bytes = fs::file_size(path, ec);
    if (ec) return Error{path + ": cannot read the file (" + ec.message() + ")."};
    if (status && bytes >= kLargeFileBytes) status("reading " + path + " (" + std::to_string(bytes >> 20) + " MiB)");
    FileGrids out;
    try {
        out.grids = readGrids(path, progress);
    } catch (const std::exception& e) {
        return Error{path + ": not a readable OpenVDB file (" + std::string(e.what()) + ")."};
    } catch (...) {
        return Error{path + ": not a readable OpenVDB file."};
    }
    if (!out.grids) return Error{path + ": not a readable OpenVDB file."};
    nameGrids(out);
    for (size_t i = 0; i < out.grids->size(); ++i)
        if (auto e = checkComplete(path, out.names[i], *(*out.grids)[i]); !e) return e.error();
    return out;
}

// Grid names, metadata and transforms only (what the grid choice and the memory cap need), read as
// io::File::readAllGridMetadata reads them but through VdbFileBuf, with every length the file states
// checked against the bytes left in it before anything is allocated. OpenVDB's own file stream
// fails quietly at the end of a corrupt file and its readers go on with stale lengths: one flipped
// byte had them build ~1 GB strings again and again (docs/reliability.md, relref).
class MetadataReader : public openvdb::io::Archive {
public:
    MetadataReader(std::istream& in, uint64_t fileSize) : in_(in), size_(fileSize) {}

    // Every grid in file order with an empty tree; null when the file has no grid offsets (written
    // to a stream: its grids can only be read whole).
    openvdb::GridPtrVecPtr read() {
        readHeader(in_);
        if (fileVersion() < openvdb::OPENVDB_FILE_VERSION_NODE_MASK_COMPRESSION)
            throw std::runtime_error("VDB file version " + std::to_string(fileVersion()) +
                                     " is older than 222, which OpenVDB no longer reads");
        auto streamMeta = std::make_shared<openvdb::io::StreamMetadata>();
        streamMeta->setSeekable(true);
        openvdb::io::setStreamMetadataPtr(in_, streamMeta, /*transfer=*/false);
        setFormatVersion(in_);
        setLibraryVersion(in_);
        setDataCompression(in_);
        openvdb::MetaMap fileMeta;
        readMetaMap(fileMeta);
        if (!inputHasGridOffsets()) return nullptr;
        auto grids = std::make_shared<openvdb::GridPtrVec>();
        const int32_t count = readGridCount(in_);
        for (int32_t i = 0; i < count; ++i) {
            // The descriptor: unique name, type, instance parent, then the grid's offsets.
            const std::streamoff at = here();
            skipName();
            skipName();
            if (openvdb::io::getFormatVersion(in_) >= openvdb::OPENVDB_FILE_VERSION_GRID_INSTANCING) skipName();
            seek(at);
            openvdb::io::GridDescriptor gd;
            openvdb::GridBase::Ptr grid = gd.read(in_);
            // Each grid lies after its descriptor and before the next: the loop moves forward only.
            if (gd.getGridPos() < here() || gd.getEndPos() <= gd.getGridPos())
                throw std::runtime_error("grid " + std::to_string(i) + " has offsets out of order (it is corrupt)");
            gd.seekToGrid(in_);
            ok();
            readGridCompression(in_);
            readMetaMap(*grid);
            if ((*grid)[openvdb::GridBase::META_FILE_DELAYED_LOAD]) grid->removeMeta(openvdb::GridBase::META_FILE_DELAYED_LOAD);
            const std::streamoff transform = here();
            skipName();  // the map's type name
            seek(transform);
            grid->readTransform(in_);
            grids->push_back(grid);
            if (i + 1 < count) {  // the next descriptor; the last grid's end is the full read's business
                gd.seekToEnd(in_);
                ok();
            }
        }
        return grids;
    }

private:
    std::streamoff here() { return static_cast<std::streamoff>(in_.tellg()); }
    void seek(std::streamoff at) {
        in_.seekg(at);
        ok();
    }
    // A failed seek sets failbit quietly, and every read after it would leave its value as it was.
    void ok() {
        if (!in_) throw std::runtime_error("an offset outside the file (it is truncated or corrupt)");
    }

    uint32_t readCount() {
        uint32_t n = 0;
        in_.read(reinterpret_cast<char*>(&n), sizeof n);
        return n;
    }

    // A length the file states: refused when it runs past the end of the file.
    void require(uint64_t bytes, const char* what) {
        const std::streamoff at = here();
        if (at < 0 || bytes > size_ - std::min<uint64_t>(size_, static_cast<uint64_t>(at)))
            throw std::runtime_error(std::string(what) + " of " + std::to_string(bytes) + " bytes at offset " +
                                     std::to_string(at) + " runs past the end of the file (it is truncated or corrupt)");
    }

    std::string readName() {
        const uint32_t n = readCount();
        require(n, "a name");
        std::string s(n, '\0');
        if (n > 0) in_.read(s.data(), n);
        return s;
    }
    void skipName() {
        const uint32_t n = readCount();
        require(n, "a name");
        seek(here() + n);
    }

    // MetaMap::readMeta's format: count, then name, type name, byte count and value, consumed as it
    // consumes them: a value of a fixed-size type is read at its own size (the stated count is not
    // used), a string as long as it says; values of types OpenVDB does not know, and the delayed-load
    // metadata (io::File drops it too), are skipped over the stated count: Brume reads neither.
    void readMetaMap(openvdb::MetaMap& out) {
        const uint32_t count = readCount();
        for (uint32_t i = 0; i < count; ++i) {
            const std::string name = readName();
            const std::string type = readName();
            const std::streamoff sizeAt = here();
            const uint32_t bytes = readCount();
            if (openvdb::Metadata::isRegisteredType(type) && type != openvdb::io::DelayedLoadMetadata::staticTypeName()) {
                openvdb::Metadata::Ptr value = openvdb::Metadata::createMetadata(type);
                const openvdb::Index32 fixed = value->size();  // 0: a string, as long as it says
                require(fixed != 0 ? fixed : bytes, "a metadata value");
                seek(sizeAt);
                value->read(in_);
                out.insertMeta(name, *value);
            } else {
                require(bytes, "a metadata value");
                seek(sizeAt + static_cast<std::streamoff>(sizeof(uint32_t)) + bytes);
            }
        }
    }

    std::istream& in_;
    uint64_t size_;
};

Result<FileGrids> readMetadata(const std::string& path) {
    FileGrids out;
    try {
        initOpenVdb();
        VdbFileBuf buf(path, {});
        if (!buf.isOpen()) throw std::runtime_error("cannot open it");
        std::istream in(&buf);
        in.exceptions(std::ios::badbit);  // the buffer's exception at the end of the file reaches us
        out.grids = MetadataReader(in, buf.fileSize()).read();
        if (!out.grids) {
            // No grid offsets: the grids can only be read whole (as io::File::open did for such files).
            out.grids = std::make_shared<openvdb::GridPtrVec>();
            for (const auto& g : *readGrids(path, {})) out.grids->push_back(g->copyGridWithNewTree());
        }
    } catch (const std::exception& e) {
        return Error{path + ": not a readable OpenVDB file (" + std::string(e.what()) + ")."};
    } catch (...) {
        return Error{path + ": not a readable OpenVDB file."};
    }
    nameGrids(out);
    return out;
}

// The grid the metadata read chose, in the full read: by its "name" or "name#i" (the i-th grid of
// that name in both reads' order).
Result<openvdb::GridBase::Ptr> findChosen(const std::string& path, const FileGrids& all, const std::string& name) {
    for (size_t i = 0; i < all.names.size(); ++i)
        if (all.names[i] == name) return (*all.grids)[i];
    return Error{path + ": not a readable OpenVDB file (grid '" + name + "' is missing)."};
}

std::string gridList(const FileGrids& f) {
    std::string s;
    for (size_t i = 0; i < f.grids->size(); ++i) {
        const auto& g = (*f.grids)[i];
        if (!s.empty()) s += ", ";
        s += "'" + f.names[i] + "' (" + g->valueType() + ", " + className(g->getGridClass()) + ")";
    }
    return s.empty() ? "none" : s;
}

// The grid named `want` ("name" or "name#i"); for the default name, else the only usable scalar grid
// (a fog volume first).
Result<size_t> chooseGrid(const std::string& path, const FileGrids& f, const std::string& want,
                          std::vector<std::string>& warnings) {
    for (size_t i = 0; i < f.names.size(); ++i) {
        if (f.names[i] != want) continue;
        if (!isScalar(*(*f.grids)[i]))
            return Error{path + ": grid '" + want + "' holds " + (*f.grids)[i]->valueType() +
                         " values, not a scalar density; grids found: " + gridList(f) + "."};
        return i;
    }
    for (size_t i = 0; i < f.names.size(); ++i) {
        if ((*f.grids)[i]->getName() == want) {  // duplicates addressed without "#i": the first
            warnings.push_back(path + ": several grids are named '" + want + "'; using '" + f.names[i] +
                               "' (address others as name#index).");
            return i;
        }
    }
    if (want == "density") {
        std::vector<size_t> fog, scalar;
        for (size_t i = 0; i < f.grids->size(); ++i) {
            if (!isScalar(*(*f.grids)[i])) continue;
            scalar.push_back(i);
            if ((*f.grids)[i]->getGridClass() == openvdb::GRID_FOG_VOLUME) fog.push_back(i);
        }
        const std::vector<size_t>& pick = fog.size() == 1 ? fog : scalar;
        if (pick.size() == 1) {
            warnings.push_back(path + ": no grid named 'density'; using '" + f.names[pick[0]] + "', the only " +
                               (fog.size() == 1 ? "fog volume" : "scalar grid") + ".");
            return pick[0];
        }
    }
    return Error{path + ": no usable grid named '" + want + "' (a float or double grid); grids found: " +
                 gridList(f) + "."};
}

// Any scalar grid as a float grid (double grids are narrowed).
openvdb::FloatGrid::Ptr asFloat(const openvdb::GridBase::Ptr& base) {
    if (auto f = openvdb::gridPtrCast<openvdb::FloatGrid>(base)) return f;
    auto d = openvdb::gridPtrCast<openvdb::DoubleGrid>(base);
    auto f = openvdb::FloatGrid::create(std::make_shared<openvdb::FloatTree>(d->tree()));
    f->setTransform(d->transform().copy());
    f->setGridClass(d->getGridClass());
    f->setName(d->getName());
    return f;
}

// NaN, Inf and negative values (active, inactive, tiles and background) become 0.
uint64_t sanitize(openvdb::FloatGrid& g) {
    uint64_t bad = 0;
    auto isBad = [](float v) { return !std::isfinite(v) || v < 0.0f; };
    for (auto it = g.tree().beginValueAll(); it; ++it) {
        if (isBad(*it)) {
            it.setValue(0.0f);
            bad += it.isVoxelValue() ? 1 : it.getVoxelCount();
        }
    }
    if (isBad(g.background())) {
        g.tree().root().setBackground(0.0f, /*updateChildNodes=*/true);
        ++bad;
    }
    return bad;
}

std::string mib(uint64_t bytes) {
    std::ostringstream s;
    s.precision(3);
    s << static_cast<double>(bytes) / (1024.0 * 1024.0) << " MiB";
    return s.str();
}

int64_t declaredBytes(const openvdb::GridBase& g) {
    const auto declared = g.getMetadata<openvdb::Int64Metadata>(openvdb::GridBase::META_FILE_MEM_BYTES);
    return declared ? std::max<int64_t>(0, declared->value()) : 0;
}

uint64_t declaredTotal(const FileGrids& meta) {
    uint64_t total = 0;
    for (const auto& g : *meta.grids) total += static_cast<uint64_t>(declaredBytes(*g));
    return total;
}

// The cap, from the grids' metadata (file_mem_bytes: a grid's size in memory when written), so that
// an oversized grid is refused before any buffer is read. The read holds every grid of the file at
// once (io::Stream reads them all), so their sum counts too. Double grids are narrowed to float.
Result<void> checkDeclaredMemory(const std::string& path, const FileGrids& meta, const openvdb::GridBase& chosen,
                                 uint64_t limit) {
    uint64_t bytes = static_cast<uint64_t>(declaredBytes(chosen));
    if (chosen.isType<openvdb::DoubleGrid>()) bytes /= 2;
    if (bytes > limit)
        return Error{path + ": the grid needs " + mib(bytes) + " in memory, over the limit of " + mib(limit) +
                     " (raise it with --vdb-memory-mb)."};
    const uint64_t total = declaredTotal(meta);
    if (total > limit)
        return Error{path + ": its " + std::to_string(meta.grids->size()) + " grids need " + mib(total) +
                     " in memory while it is read, over the limit of " + mib(limit) + " (raise it with --vdb-memory-mb)."};
    return {};
}

Result<DensityGridPtr> toDensityGrid(const std::string& path, const openvdb::FloatGrid& g, uint64_t limit) {
    const uint64_t openBytes = g.memUsage();
    if (openBytes > limit)
        return Error{path + ": the grid needs " + mib(openBytes) + " in memory, over the limit of " + mib(limit) +
                     " (raise it with --vdb-memory-mb)."};
    auto handle = nanovdb::openToNanoVDB<nanovdb::HostBuffer, openvdb::FloatTree, float>(g);
    if (handle.size() > limit)
        return Error{path + ": the grid needs " + mib(handle.size()) + " as NanoVDB, over the limit of " + mib(limit) +
                     " (raise it with --vdb-memory-mb)."};
    return DensityGridPtr(std::make_shared<const DensityGrid>(handle.data(), handle.size()));
}

Result<VdbLoad> convert(const std::string& path, const openvdb::GridBase::Ptr& base, const std::string& name,
                        const VdbImportOptions& options, std::vector<std::string> warnings) {
    if (!base->transform().isLinear())
        return Error{path + ": grid '" + name + "' has a frustum (non-affine) transform, which is not supported."};
    openvdb::FloatGrid::Ptr g = asFloat(base);
    if (g->getGridClass() == openvdb::GRID_LEVEL_SET) {
        // First, while negative distances still mean "inside": inside = 1, a smooth ramp to 0 across
        // the inner half of the narrow band.
        openvdb::tools::sdfToFogVolume(*g);
        warnings.push_back(path + ": grid '" + name + "' is a level set; converted to a fog volume (inside = 1).");
    }
    if (const uint64_t bad = sanitize(*g))
        warnings.push_back(path + ": grid '" + name + "': " + std::to_string(bad) +
                           " NaN, infinite or negative values replaced by 0.");
    if (g->activeVoxelCount() == 0) warnings.push_back(path + ": grid '" + name + "' is empty; the volume is empty.");
    if (options.status && g->activeVoxelCount() > (uint64_t(1) << 22))
        options.status("converting '" + name + "' (" + std::to_string(g->activeVoxelCount()) + " voxels) to NanoVDB");
    VdbLoad load;
    auto grid = toDensityGrid(path, *g, options.memoryLimitBytes);
    if (!grid) return grid.error();
    load.grid = grid.value();
    load.gridName = name;
    load.warnings = std::move(warnings);
    return load;
}

glm::dmat4 gridFromIndexOf(const openvdb::math::Transform& t) {
    const openvdb::Mat4d m = t.baseMap()->getAffineMap()->getMat4();  // row vectors: p' = p * m
    glm::dmat4 r(1.0);
    for (int c = 0; c < 4; ++c)
        for (int row = 0; row < 4; ++row) r[c][row] = m(c, row);
    return r;
}

template <class GridT>
void scalarInfo(const openvdb::GridBase::Ptr& base, VdbGridInfo& info) {
    auto g = openvdb::gridPtrCast<GridT>(base);
    if (!g || info.activeVoxels == 0) return;
    double lo = INFINITY, hi = -INFINITY;
    for (auto it = g->cbeginValueOn(); it; ++it) {
        lo = std::min(lo, static_cast<double>(*it));
        hi = std::max(hi, static_cast<double>(*it));
    }
    info.valueMin = lo;
    info.valueMax = hi;
}

VdbGridInfo describe(const openvdb::GridBase::Ptr& g, const std::string& name) {
    VdbGridInfo info;
    info.name = name;
    info.type = g->valueType();
    info.gridClass = className(g->getGridClass());
    const openvdb::Vec3d vs = g->voxelSize();
    info.voxelSize = glm::dvec3(vs[0], vs[1], vs[2]);
    info.affine = g->transform().isLinear();
    if (info.affine) info.gridFromIndex = gridFromIndexOf(g->transform());
    info.activeVoxels = g->activeVoxelCount();
    if (info.activeVoxels > 0) {
        const openvdb::CoordBBox box = g->evalActiveVoxelBoundingBox();
        info.indexMin = glm::ivec3(box.min()[0], box.min()[1], box.min()[2]);
        info.indexMax = glm::ivec3(box.max()[0], box.max()[1], box.max()[2]);
        const openvdb::BBoxd w = g->transform().indexToWorld(box);
        info.worldMin = glm::dvec3(w.min()[0], w.min()[1], w.min()[2]);
        info.worldMax = glm::dvec3(w.max()[0], w.max()[1], w.max()[2]);
    }
    scalarInfo<openvdb::FloatGrid>(g, info);
    scalarInfo<openvdb::DoubleGrid>(g, info);
    if (isScalar(*g) && info.affine) {
        const openvdb::FloatGrid::Ptr f = asFloat(g);
        info.nanovdbBytes = nanovdb::openToNanoVDB<nanovdb::HostBuffer, openvdb::FloatTree, float>(*f).size();
        info.nanovdbFp16Bytes = nanovdb::openToNanoVDB<nanovdb::HostBuffer, openvdb::FloatTree, nanovdb::Fp16>(*f).size();
        info.nanovdbFp8Bytes = nanovdb::openToNanoVDB<nanovdb::HostBuffer, openvdb::FloatTree, nanovdb::Fp8>(*f).size();
    }
    return info;
}

}  // namespace

Result<std::vector<VdbGridInfo>> inspectVdbInProcess(const std::string& path, const VdbImportOptions& options) {
    auto meta = readMetadata(path);
    if (!meta) return meta.error();
    if (options.beforeRead) options.beforeRead(declaredTotal(meta.value()));
    auto file = readAll(path, {}, options.progress);
    if (!file) return file.error();
    std::vector<VdbGridInfo> out;
    try {
        for (size_t i = 0; i < file.value().grids->size(); ++i)
            out.push_back(describe((*file.value().grids)[i], file.value().names[i]));
    } catch (const std::exception& e) {
        return Error{path + ": cannot inspect the grids (" + std::string(e.what()) + ")."};
    } catch (...) {
        return Error{path + ": cannot inspect the grids."};
    }
    return out;
}

// One layer of volume i's texture: its grid and the mean its strength is measured against. where:
// "SCENE: volumes[i].density_texture." or "...density_texture.detail.".
static Result<void> loadTextureLayer(TextureLayer& t, const Scene& scene, const std::string& where,
                                     uint64_t memoryLimitBytes, std::vector<std::string>& warnings) {
    fs::path p(t.file);
    if (p.is_relative()) p = fs::path(scene.baseDir) / p;
    VdbImportOptions options;
    options.grid = t.grid;
    options.memoryLimitBytes = memoryLimitBytes;
    auto load = loadVdbDensity(p.lexically_normal().string(), options);
    if (!load) return Error{where + "file: " + load.error().message};
    for (std::string& w : load.value().warnings) warnings.push_back(std::move(w));
    const double mean = load.value().grid->activeBoxMean(t.exponent);
    if (!(mean > 0.0))
        return Error{where + "grid: grid '" + load.value().gridName + "' of " + p.lexically_normal().string() +
                     " has no positive values, so it cannot modulate a density (a texture is measured against its "
                     "mean)."};
    t.density = load.value().grid;
    t.mean = static_cast<float>(mean);
    return {};
}

// The texture of volume i and its detail layer.
Result<void> loadDensityTexture(DensityTexture& t, const Scene& scene, const std::string& sceneFile, size_t i,
                                uint64_t memoryLimitBytes, std::vector<std::string>& warnings) {
    const std::string where = sceneFile + ": volumes[" + std::to_string(i) + "].density_texture.";
    if (Result<void> r = loadTextureLayer(t, scene, where, memoryLimitBytes, warnings); !r) return r;
    if (t.detail) return loadTextureLayer(*t.detail, scene, where + "detail.", memoryLimitBytes, warnings);
    return {};
}

Result<void> loadMeshVolume(Volume& v, const Scene& scene, const std::string& sceneFile, size_t i,
                            uint64_t memoryLimitBytes, std::vector<std::string>& warnings) {
    fs::path p(v.file);
    if (p.is_relative()) p = fs::path(scene.baseDir) / p;
    VdbImportOptions options;
    options.memoryLimitBytes = memoryLimitBytes;
    // The GPU samples every grid of a frame with one encoding: the scene's vdb volumes' (float when none).
    for (const Volume& other : scene.volumes)
        if (other.type == VolumeType::Vdb) {
            options.encoding = other.encoding;
            break;
        }
    auto load = loadMeshDensity(p.lexically_normal().string(), v.edge_fade_m, options);
    if (!load) return Error{sceneFile + ": volumes[" + std::to_string(i) + "].file: " + load.error().message};
    v.density = load.value().grid;
    for (std::string& w : load.value().warnings) warnings.push_back(std::move(w));
    return {};
}

Result<void> loadSceneGrids(Scene& scene, const std::string& sceneFile, uint64_t memoryLimitBytes,
                            std::vector<std::string>& warnings,
                            const std::function<void(const std::string&, float)>& progress) {
    for (size_t i = 0; i < scene.volumes.size(); ++i) {
        Volume& v = scene.volumes[i];
        if (v.density_texture) {
            Result<void> t = loadDensityTexture(*v.density_texture, scene, sceneFile, i, memoryLimitBytes, warnings);
            if (!t) return t;
        }
        if (v.type == VolumeType::Mesh) {
            Result<void> m = loadMeshVolume(v, scene, sceneFile, i, memoryLimitBytes, warnings);
            if (!m) return m;
        }
        if (v.type != VolumeType::Vdb) continue;
        fs::path p(v.file);
        if (p.is_relative()) p = fs::path(scene.baseDir) / p;
        VdbImportOptions options;
        options.grid = v.grid;
        options.encoding = v.encoding;
        options.memoryLimitBytes = memoryLimitBytes;
        const std::string path = p.lexically_normal().string();
        std::error_code ec;
        if (progress && fs::file_size(path, ec) >= kVdbProgressBytes && !ec)
            options.progress = [&progress, path](float f) { progress(path, f); };
        auto load = loadVdbDensity(path, options);
        if (!load) return Error{sceneFile + ": volumes[" + std::to_string(i) + "].file: " + load.error().message};
        v.density = load.value().grid;
        for (std::string& w : load.value().warnings) warnings.push_back(std::move(w));
    }
    return {};
}

Result<VdbLoad> loadVdbDensityInProcess(const std::string& path, const VdbImportOptions& options) {
    std::error_code ec;
    const uintmax_t bytes = fs::file_size(path, ec);
    if (ec) return Error{path + ": cannot read the file (" + ec.message() + ")."};
    if (options.status && bytes >= kLargeFileBytes)
        options.status("reading " + path + " (" + std::to_string(bytes >> 20) + " MiB)");
    auto meta = readMetadata(path);
    if (!meta) return meta.error();
    std::vector<std::string> warnings;
    auto index = chooseGrid(path, meta.value(), options.grid, warnings);
    if (!index) return index.error();
    const openvdb::GridBase& chosen = *(*meta.value().grids)[index.value()];
    if (auto e = checkDeclaredMemory(path, meta.value(), chosen, options.memoryLimitBytes); !e) return e.error();
    if (options.beforeRead) options.beforeRead(declaredTotal(meta.value()));
    auto all = readAll(path, {}, options.progress);
    if (!all) return all.error();
    auto grid = findChosen(path, all.value(), meta.value().names[index.value()]);
    if (!grid) return grid.error();
    try {
        return convert(path, grid.value(), meta.value().names[index.value()], options, std::move(warnings));
    } catch (const std::exception& e) {
        return Error{path + ": cannot convert the grid (" + std::string(e.what()) + ")."};
    } catch (...) {
        return Error{path + ": cannot convert the grid."};
    }
}

}  // namespace brume
