// Mesh fog hulls (`mesh` volumes, docs/vdb.md "Mesh fog hulls"): a closed triangle mesh (Wavefront
// OBJ or PLY) turned into a fog grid with OpenVDB's mesh-to-volume tools: a signed distance grid, then
// density smoothstep(0, edge_fade_m, -distance) inside the surface (1 deeper in), 0 outside, kept
// sparse as a float NanoVDB grid and sampled like a vdb volume by every renderer (core/compile.cpp).
//
// Meshes with holes are refused, never voxelized into a wrong volume: after welding vertices at equal
// positions, every edge must border an even number of triangles (a closed surface; non-manifold
// edges shared by 4 triangles are closed too, and OpenVDB's conversion handles them). Bad input (an
// unreadable file, no triangles, a non-finite vertex, a face index out of range, more than
// kMeshMaxTriangles triangles) is one sentence naming the file.
//
// The conversion runs in the isolated reader process (brume-vdb-read mesh ..., io/vdb_reader.h), like
// every OpenVDB read, so a hostile file cannot crash Brume; the *InProcess functions are what it runs.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/result.h"
#include "vdb_import.h"

namespace brume {

// The stated caps: the reader refuses larger meshes before converting them.
inline constexpr size_t kMeshMaxTriangles = 2'000'000;
inline constexpr size_t kMeshMaxVertices = 3 * kMeshMaxTriangles;
// Voxels along the mesh's longest side: at most (memory: a filled cube of 128^3 voxels is 8 MiB as
// float NanoVDB) and at least (a coarser grid rounds the hull's shape off).
inline constexpr float kMeshMaxVoxelsPerSide = 128.0f;
inline constexpr float kMeshMinVoxelsPerSide = 32.0f;
// Voxels across the edge fade when the caps allow: the smoothstep ramp sampled trilinearly.
inline constexpr float kMeshVoxelsPerFade = 4.0f;

struct TriangleMesh {
    std::vector<glm::vec3> points;     // welded: one point per distinct position
    std::vector<glm::uvec3> triangles; // indices into points; degenerate ones (a repeated point) dropped
};

// Reads an OBJ file's `v` and `f` lines (polygons fan-triangulated; `a`, `a/b`, `a//c`, `a/b/c` and
// negative indices; every other line ignored), welds equal positions and drops degenerate triangles.
Result<TriangleMesh> readObjMesh(const std::string& path);

// Reads a PLY file (ASCII or binary little-endian; big-endian is refused): the vertex element's x, y,
// z and the face element's vertex_indices (or vertex_index) list, polygons fan-triangulated; other
// elements and properties skipped. The same checks, welding and sentences as readObjMesh.
Result<TriangleMesh> readPlyMesh(const std::string& path);

// readPlyMesh for a .ply file (any case), readObjMesh otherwise.
Result<TriangleMesh> readMesh(const std::string& path);

// Edges that border an odd number of triangles (0 for a closed mesh).
size_t openEdgeCount(const TriangleMesh& mesh);

// The grid's voxel edge for a mesh whose bounding box's longest side is `extent` (the mesh's units):
// edgeFadeM / kMeshVoxelsPerFade, clamped to [extent / 128, extent / 32].
float meshVoxelSize(float extent, float edgeFadeM);

// Density at signed distance `distance` from the surface (negative inside), for the fade and voxel
// size of a mesh volume: smoothstep(0, edgeFadeM, -distance); with no fade, a one-voxel linear ramp
// centred on the surface (whose integral across the surface is the hard edge's).
float meshFogDensity(float distance, float edgeFadeM, float voxel);

// Reads, checks and converts in the calling process (the isolated reader calls this).
Result<VdbLoad> loadMeshDensityInProcess(const std::string& path, float edgeFadeM, const VdbImportOptions& options);

// The same, in the isolated reader process (defined in io/vdb_reader.cpp); the grid is re-encoded
// to options.encoding.
Result<VdbLoad> loadMeshDensity(const std::string& path, float edgeFadeM, const VdbImportOptions& options);

}  // namespace brume
