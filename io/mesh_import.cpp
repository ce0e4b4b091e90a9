#include "mesh_import.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <sstream>
#include <unordered_map>

#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tools/Prune.h>
#include <nanovdb/util/OpenToNanoVDB.h>

namespace brume {
namespace {

std::string count(size_t n) { return std::to_string(n); }

// Position -> welded index (exact equality: exporters that split vertices at seams repeat them bit
// for bit).
struct PointKey {
    uint32_t x, y, z;
    bool operator==(const PointKey&) const = default;
};
struct PointKeyHash {
    size_t operator()(const PointKey& k) const {
        return (size_t(k.x) * 73856093u) ^ (size_t(k.y) * 19349663u) ^ (size_t(k.z) * 83492791u);
    }
};
PointKey keyOf(glm::vec3 p) {
    p += glm::vec3(0.0f);  // -0 and +0 weld
    PointKey k{};
    std::memcpy(&k.x, &p.x, 4);
    std::memcpy(&k.y, &p.y, 4);
    std::memcpy(&k.z, &p.z, 4);
    return k;
}

bool parseFloat(std::string_view s, float& out) {
    // from_chars for float is in GCC 11+: strict, no locale.
    const auto r = std::from_chars(s.data(), s.data() + s.size(), out);
    return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

std::vector<std::string_view> tokens(std::string_view line) {
    std::vector<std::string_view> out;
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
        size_t j = i;
        while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != '\r') ++j;
        if (j > i) out.push_back(line.substr(i, j - i));
        i = j;
    }
    return out;
}

struct ObjReader {
    std::string path;
    std::vector<glm::vec3> raw;            // as written
    std::vector<int64_t> faceIndices;      // 0-based into raw, 3 per triangle (resolved, unchecked)
    std::vector<size_t> faceLines;         // the line of each triangle (for range errors)

    Result<void> vertex(const std::vector<std::string_view>& t, size_t line) {
        glm::vec3 p;
        if (t.size() < 4 || !parseFloat(t[1], p.x) || !parseFloat(t[2], p.y) || !parseFloat(t[3], p.z))
            return Error{path + ": line " + count(line) + ": a vertex ('v') needs three numbers."};
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            return Error{path + ": line " + count(line) + ": vertex " + count(raw.size() + 1) +
                         " has a non-finite coordinate (NaN or infinite)."};
        if (raw.size() >= kMeshMaxVertices)
            return Error{path + ": more than " + count(kMeshMaxVertices) + " vertices, over Brume's limit for a mesh volume."};
        raw.push_back(p);
        return {};
    }

    Result<void> face(const std::vector<std::string_view>& t, size_t line) {
        if (t.size() < 4) return Error{path + ": line " + count(line) + ": a face ('f') needs at least three vertices."};
        std::vector<int64_t> corners;
        for (size_t i = 1; i < t.size(); ++i) {
            const std::string_view idx = t[i].substr(0, t[i].find('/'));
            int64_t n = 0;
            const auto r = std::from_chars(idx.data(), idx.data() + idx.size(), n);
            if (r.ec != std::errc() || r.ptr != idx.data() + idx.size() || n == 0)
                return Error{path + ": line " + count(line) + ": a face ('f') has a corner that is not a vertex index."};
            // Negative: relative to the vertices read so far (-1 is the last).
            corners.push_back(n > 0 ? n - 1 : static_cast<int64_t>(raw.size()) + n);
        }
        if (faceIndices.size() / 3 + (corners.size() - 2) > kMeshMaxTriangles)
            return Error{path + ": more than " + count(kMeshMaxTriangles) +
                         " triangles, over Brume's limit for a mesh volume (simplify the mesh)."};
        for (size_t i = 1; i + 1 < corners.size(); ++i) {  // a fan: the polygons of OBJ files are convex
            faceIndices.insert(faceIndices.end(), {corners[0], corners[i], corners[i + 1]});
            faceLines.push_back(line);
        }
        return {};
    }

    Result<void> read() {
        std::ifstream in(path, std::ios::binary);
        if (!in) return Error{path + ": cannot read the file (" + std::strerror(errno) + ")."};
        std::string text;
        size_t line = 0;
        while (std::getline(in, text)) {
            ++line;
            const std::vector<std::string_view> t = tokens(text);
            if (t.empty()) continue;
            Result<void> r;
            if (t[0] == "v") r = vertex(t, line);
            else if (t[0] == "f") r = face(t, line);
            if (!r) return r;
        }
        if (in.bad()) return Error{path + ": cannot read the file (a read error)."};
        return {};
    }
};

// PLY (ASCII or binary little-endian): a header of elements and their properties, then each element's
// rows. The vertex element's x, y, z and the face element's vertex_indices (or vertex_index) list are
// read; every other element and property is skipped by its size.
struct PlyReader {
    enum class Format { Ascii, BinaryLe };
    struct Property {
        std::string name;
        std::string type;       // scalar type, or the list's item type
        std::string countType;  // list length type; empty for a scalar
    };
    struct Element {
        std::string name;
        uint64_t count = 0;
        std::vector<Property> properties;
    };

    std::string path;
    std::vector<glm::vec3> raw;
    std::vector<int64_t> faceIndices;
    std::vector<size_t> faceNumbers;  // the face (0-based) each triangle came from
    Format format = Format::Ascii;
    std::vector<Element> elements;
    std::ifstream in;

    Error bad(const std::string& what) const { return Error{path + ": " + what}; }

    static int typeSize(const std::string& t) {
        if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
        if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
        if (t == "int" || t == "uint" || t == "int32" || t == "uint32" || t == "float" || t == "float32") return 4;
        if (t == "double" || t == "float64") return 8;
        return 0;
    }

    Result<void> header() {
        std::string line;
        if (!std::getline(in, line) || tokens(line) != std::vector<std::string_view>{"ply"})
            return bad("not a PLY file (the first line is not 'ply').");
        bool sawFormat = false;
        while (std::getline(in, line)) {
            const std::vector<std::string_view> t = tokens(line);
            if (t.empty() || t[0] == "comment" || t[0] == "obj_info") continue;
            if (t[0] == "end_header") {
                if (!sawFormat) return bad("the PLY header has no 'format' line.");
                return {};
            }
            if (t[0] == "format") {
                if (t.size() < 2) return bad("the PLY header's 'format' line names no format.");
                if (t[1] == "ascii") format = Format::Ascii;
                else if (t[1] == "binary_little_endian") format = Format::BinaryLe;
                else return bad("PLY format '" + std::string(t[1]) + "' is not supported (ascii or binary_little_endian).");
                sawFormat = true;
            } else if (t[0] == "element") {
                uint64_t n = 0;
                if (t.size() != 3 || std::from_chars(t[2].data(), t[2].data() + t[2].size(), n).ec != std::errc())
                    return bad("a PLY 'element' line needs a name and a count.");
                elements.push_back(Element{std::string(t[1]), n, {}});
            } else if (t[0] == "property") {
                if (elements.empty()) return bad("a PLY 'property' line comes before any 'element'.");
                Property p;
                if (t.size() == 5 && t[1] == "list") p = Property{std::string(t[4]), std::string(t[3]), std::string(t[2])};
                else if (t.size() == 3) p = Property{std::string(t[2]), std::string(t[1]), ""};
                else return bad("a PLY 'property' line is malformed.");
                if (typeSize(p.type) == 0 || (!p.countType.empty() && typeSize(p.countType) == 0))
                    return bad("PLY property '" + p.name + "' has an unknown type.");
                elements.back().properties.push_back(p);
            }
        }
        return bad("the PLY header has no 'end_header' line.");
    }

    // One value of type t, as a double (binary: little-endian bytes; ASCII: the next token).
    bool value(const std::string& t, std::vector<std::string_view>& row, size_t& at, double& out) {
        if (format == Format::Ascii) {
            if (at >= row.size()) return false;
            const std::string_view s = row[at++];
            const auto r = std::from_chars(s.data(), s.data() + s.size(), out);
            return r.ec == std::errc() && r.ptr == s.data() + s.size();
        }
        unsigned char b[8];
        const int n = typeSize(t);
        if (!in.read(reinterpret_cast<char*>(b), n)) return false;
        uint64_t u = 0;
        for (int i = n - 1; i >= 0; --i) u = (u << 8) | b[i];
        if (t == "float" || t == "float32") {
            float f;
            const uint32_t u32 = static_cast<uint32_t>(u);
            std::memcpy(&f, &u32, 4);
            out = f;
        } else if (t == "double" || t == "float64") {
            std::memcpy(&out, &u, 8);
        } else if (t[0] == 'u') {
            out = static_cast<double>(u);
        } else {  // signed: extend from n bytes
            const int shift = 64 - 8 * n;
            out = static_cast<double>(static_cast<int64_t>(u << shift) >> shift);
        }
        return true;
    }

    Result<void> read() {
        in.open(path, std::ios::binary);
        if (!in) return Error{path + ": cannot read the file (" + std::strerror(errno) + ")."};
        if (Result<void> h = header(); !h) return h;
        // The caps, from the header's counts, before any data is read.
        for (const Element& e : elements) {
            if (e.name == "vertex" && e.count > kMeshMaxVertices)
                return bad("more than " + count(kMeshMaxVertices) + " vertices, over Brume's limit for a mesh volume.");
            if (e.name == "face" && e.count > kMeshMaxTriangles)
                return bad("more than " + count(kMeshMaxTriangles) +
                           " triangles, over Brume's limit for a mesh volume (simplify the mesh).");
        }
        std::string line;
        std::vector<std::string_view> row;
        for (const Element& e : elements) {
            const bool vertices = e.name == "vertex", faces = e.name == "face";
            if (e.properties.empty() && !vertices) continue;  // rows of nothing: no data to skip
            int axis[3] = {-1, -1, -1};
            int list = -1;
            for (size_t i = 0; i < e.properties.size(); ++i) {
                const Property& p = e.properties[i];
                if (vertices && p.countType.empty() && p.name.size() == 1 && p.name[0] >= 'x' && p.name[0] <= 'z')
                    axis[p.name[0] - 'x'] = static_cast<int>(i);
                if (faces && !p.countType.empty() && (p.name == "vertex_indices" || p.name == "vertex_index"))
                    list = static_cast<int>(i);
            }
            if (vertices && (axis[0] < 0 || axis[1] < 0 || axis[2] < 0))
                return bad("the PLY vertex element lacks an x, y or z property.");
            if (faces && list < 0) return bad("the PLY face element has no vertex_indices list.");
            // ASCII rows are lines (the PLY header is small, the rows are not: a row's tokens, then
            // its values).
            for (uint64_t r = 0; r < e.count; ++r) {
                size_t at = 0;
                if (format == Format::Ascii) {
                    do {
                        if (!std::getline(in, line)) return bad("the PLY data is cut short before " + e.name + " " + count(r) + ".");
                        row = tokens(line);
                    } while (row.empty());
                }
                glm::vec3 p(0.0f);
                for (size_t i = 0; i < e.properties.size(); ++i) {
                    const Property& prop = e.properties[i];
                    double v = 0.0;
                    const std::string& scalar = prop.countType.empty() ? prop.type : prop.countType;
                    if (!value(scalar, row, at, v))
                        return bad("the PLY data of " + e.name + " " + count(r) + " is cut short or not a number.");
                    if (prop.countType.empty()) {
                        for (int a = 0; a < 3; ++a)
                            if (axis[a] == static_cast<int>(i)) p[a] = static_cast<float>(v);
                        continue;
                    }
                    if (!(v >= 0.0) || v > 1.0e6)
                        return bad("the PLY " + e.name + " " + count(r) + " has a list length of " + std::to_string(v) + ".");
                    const size_t n = static_cast<size_t>(v);
                    std::vector<int64_t> corners(n);
                    for (size_t c = 0; c < n; ++c) {
                        double idx = 0.0;
                        if (!value(prop.type, row, at, idx))
                            return bad("the PLY data of " + e.name + " " + count(r) + " is cut short or not a number.");
                        corners[c] = static_cast<int64_t>(idx);
                    }
                    if (static_cast<int>(i) != list) continue;
                    if (n < 3) return bad("PLY face " + count(r) + " has fewer than three vertices.");
                    if (faceIndices.size() / 3 + (n - 2) > kMeshMaxTriangles)
                        return bad("more than " + count(kMeshMaxTriangles) +
                                   " triangles, over Brume's limit for a mesh volume (simplify the mesh).");
                    for (size_t c = 1; c + 1 < n; ++c) {  // a fan, as for OBJ polygons
                        faceIndices.insert(faceIndices.end(), {corners[0], corners[c], corners[c + 1]});
                        faceNumbers.push_back(static_cast<size_t>(r));
                    }
                }
                if (vertices) {
                    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                        return bad("vertex " + count(raw.size()) + " has a non-finite coordinate (NaN or infinite).");
                    raw.push_back(p);
                }
            }
        }
        if (in.bad()) return Error{path + ": cannot read the file (a read error)."};
        return {};
    }
};

// Welds equal positions and drops degenerate triangles; faceIndices index raw (checked here), where(i)
// names triangle i's source in a range error.
Result<TriangleMesh> weldMesh(const std::string& path, const std::vector<glm::vec3>& raw, const std::vector<int64_t>& faceIndices,
                              const std::function<std::string(size_t)>& where) {
    for (size_t i = 0; i < faceIndices.size(); ++i)
        if (faceIndices[i] < 0 || faceIndices[i] >= static_cast<int64_t>(raw.size()))
            return Error{path + ": " + where(i / 3) + " uses vertex " + std::to_string(faceIndices[i] + 1) + " but the file has " +
                         count(raw.size()) + " vertices."};
    TriangleMesh mesh;
    std::unordered_map<PointKey, uint32_t, PointKeyHash> welded;
    std::vector<uint32_t> remap(raw.size());
    for (size_t i = 0; i < raw.size(); ++i) {
        const auto [it, added] = welded.try_emplace(keyOf(raw[i]), static_cast<uint32_t>(mesh.points.size()));
        if (added) mesh.points.push_back(raw[i]);
        remap[i] = it->second;
    }
    for (size_t i = 0; i < faceIndices.size(); i += 3) {
        const glm::uvec3 t(remap[static_cast<size_t>(faceIndices[i])], remap[static_cast<size_t>(faceIndices[i + 1])],
                           remap[static_cast<size_t>(faceIndices[i + 2])]);
        if (t.x != t.y && t.y != t.z && t.x != t.z) mesh.triangles.push_back(t);
    }
    if (mesh.triangles.empty())
        return Error{path + ": the mesh has no triangles with three distinct vertices (every face is degenerate)."};
    return mesh;
}

}  // namespace

Result<TriangleMesh> readObjMesh(const std::string& path) {
    ObjReader r{path, {}, {}, {}};
    if (Result<void> ok = r.read(); !ok) return ok.error();
    if (r.faceIndices.empty())
        return Error{path + ": the mesh has no triangles (no 'f' lines; a mesh volume needs a closed triangle mesh in "
                            "OBJ format)."};
    return weldMesh(path, r.raw, r.faceIndices, [&](size_t t) { return "line " + count(r.faceLines[t]) + ": a face"; });
}

Result<TriangleMesh> readPlyMesh(const std::string& path) {
    PlyReader r;
    r.path = path;
    if (Result<void> ok = r.read(); !ok) return ok.error();
    if (r.faceIndices.empty())
        return Error{path + ": the mesh has no triangles (no faces; a mesh volume needs a closed triangle mesh)."};
    // A range error counts vertices from 1, as for OBJ (PLY's own indices start at 0).
    return weldMesh(path, r.raw, r.faceIndices, [&](size_t t) { return "face " + count(r.faceNumbers[t]); });
}

Result<TriangleMesh> readMesh(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".ply" ? readPlyMesh(path) : readObjMesh(path);
}

size_t openEdgeCount(const TriangleMesh& mesh) {
    std::vector<uint64_t> edges;
    edges.reserve(mesh.triangles.size() * 3);
    for (const glm::uvec3& t : mesh.triangles)
        for (int e = 0; e < 3; ++e) {
            const uint32_t a = t[e], b = t[(e + 1) % 3];
            edges.push_back((uint64_t(std::min(a, b)) << 32) | std::max(a, b));
        }
    std::sort(edges.begin(), edges.end());
    size_t open = 0;
    for (size_t i = 0; i < edges.size();) {
        size_t j = i;
        while (j < edges.size() && edges[j] == edges[i]) ++j;
        open += (j - i) % 2;
        i = j;
    }
    return open;
}

float meshVoxelSize(float extent, float edgeFadeM) {
    return std::clamp(edgeFadeM / kMeshVoxelsPerFade, extent / kMeshMaxVoxelsPerSide, extent / kMeshMinVoxelsPerSide);
}

float meshFogDensity(float distance, float edgeFadeM, float voxel) {
    if (edgeFadeM <= 0.0f) return std::clamp(0.5f - distance / voxel, 0.0f, 1.0f);
    const float t = std::clamp(-distance / edgeFadeM, 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

Result<VdbLoad> loadMeshDensityInProcess(const std::string& path, float edgeFadeM, const VdbImportOptions& options) {
    Result<TriangleMesh> read = readMesh(path);
    if (!read) return read.error();
    const TriangleMesh& mesh = read.value();
    if (const size_t open = openEdgeCount(mesh); open > 0)
        return Error{path + ": the mesh is not closed: " + count(open) +
                     " edges border an odd number of triangles (holes or open borders), and a fog hull needs a "
                     "watertight mesh to know its inside (close the holes in a modelling tool)."};
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const glm::vec3& p : mesh.points) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const float extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    if (!(extent > 0.0f) || !std::isfinite(extent))
        return Error{path + ": the mesh has no usable extent (all its vertices at one point, or coordinates too large for "
                            "a float)."};
    const float fade = std::max(edgeFadeM, 0.0f);
    const float voxel = meshVoxelSize(extent, fade);

    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
    std::vector<openvdb::Vec3s> points;
    points.reserve(mesh.points.size());
    for (const glm::vec3& p : mesh.points) points.emplace_back(p.x, p.y, p.z);
    std::vector<openvdb::Vec3I> triangles;
    triangles.reserve(mesh.triangles.size());
    for (const glm::uvec3& t : mesh.triangles) triangles.emplace_back(t.x, t.y, t.z);
    // Exact distances where the density is not yet 1 (the fade's depth, plus the trilinear support);
    // deeper inside, the sign alone (inactive tiles at -background).
    const float inBand = std::min(fade / voxel + 2.0f, 2.0f * kMeshMaxVoxelsPerSide);
    // Index (0, 0, 0) a few voxels below the mesh's corner: all index coordinates positive, so the
    // grid lies in one NanoVDB upper node (a grid across the origin takes 8, ~300 KiB each).
    const auto xform = openvdb::math::Transform::createLinearTransform(voxel);
    xform->postTranslate(openvdb::Vec3d(lo.x, lo.y, lo.z) - openvdb::Vec3d(4.0 * voxel));
    openvdb::FloatGrid::Ptr grid = openvdb::tools::meshToSignedDistanceField<openvdb::FloatGrid>(
        *xform, points, triangles, std::vector<openvdb::Vec4I>(), 2.0f, inBand);

    // Distance -> density, tiles included: the inside's inactive tiles (-background) become active 1.
    for (auto it = grid->tree().beginValueAll(); it; ++it) {
        const float d = meshFogDensity(*it, fade, voxel);
        it.setValue(d);
        it.setActiveState(d > 0.0f);
    }
    grid->tree().root().setBackground(0.0f, /*updateChildNodes=*/true);
    openvdb::tools::pruneInactive(grid->tree());
    // Voxels rather than tiles, so the occupancy cells (core/density_grid.h) can skip the empty space
    // of a concave hull; the voxel-size cap bounds the cost.
    grid->tree().voxelizeActiveTiles();
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    grid->setName("mesh");

    VdbLoad load;
    load.gridName = "mesh";
    if (grid->activeVoxelCount() == 0)
        load.warnings.push_back(path + ": the mesh encloses no voxel centre at voxel size " + std::to_string(voxel) +
                                "; the volume is empty.");
    if (grid->memUsage() > options.memoryLimitBytes)
        return Error{path + ": the mesh's fog grid needs more memory than the limit (raise it with --vdb-memory-mb)."};
    auto handle = nanovdb::openToNanoVDB<nanovdb::HostBuffer, openvdb::FloatTree, float>(*grid);
    if (handle.size() > options.memoryLimitBytes)
        return Error{path + ": the mesh's fog grid needs more memory as NanoVDB than the limit (raise it with "
                            "--vdb-memory-mb)."};
    load.grid = std::make_shared<const DensityGrid>(handle.data(), handle.size());
    return load;
}

}  // namespace brume
