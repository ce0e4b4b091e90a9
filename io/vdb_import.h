// OpenVDB import (io/ only: core/ sees the result as a DensityGrid, a NanoVDB buffer).
// Reads any file the OpenVDB library reads (half/float/double, blosc/zip/none, every file version),
// picks one scalar grid, turns a level set into a fog volume, replaces NaN/Inf/negative values by 0,
// refuses grids over a memory cap and converts the result to a float NanoVDB grid.
// Every OpenVDB exception stops here: errors are values, one sentence naming the file.
// OpenVDB runs in a separate process (brume-vdb-read, found beside the running executable): a file
// that crashes the library gives an error, never a crash of Brume (io/vdb_reader.cpp).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/density_grid.h"
#include "core/result.h"
#include "core/scene.h"

namespace brume {

struct VdbImportOptions {
    // "density" (the default) falls back to the only float fog-volume grid; "name#i" picks the i-th
    // (0-based) of several grids with that name.
    std::string grid = "density";
    uint64_t memoryLimitBytes = uint64_t(4096) << 20;
    // The grid handed back is re-encoded so (io/vdb_encoding.h); density textures stay float.
    VdbEncoding encoding = VdbEncoding::Float;
    // Status lines for large files ("reading ...", "converting ..."); optional. In-process reads only.
    std::function<void(const std::string&)> status;
    // Fraction of the file read so far (0..1), reported by the reader process; optional.
    std::function<void(float)> progress;
    // The reader is killed and the load fails after this long; 0: no limit (a large file is slow).
    double timeoutSeconds = 0.0;
    // In-process reads: called with the memory the file's grids declare (their metadata; 0 when
    // unknown) once it is known, before any voxel is read; the reader process caps its memory there.
    std::function<void(uint64_t)> beforeRead;
};

struct VdbLoad {
    DensityGridPtr grid;                // never null; empty() for an empty grid
    std::string gridName;               // the grid chosen, as "name" or "name#i"
    std::vector<std::string> warnings;  // one sentence each, naming the file
};

Result<VdbLoad> loadVdbDensity(const std::string& path, const VdbImportOptions& options);

// What `brume info` lists for one grid.
struct VdbGridInfo {
    std::string name;       // "name#i" when several grids share the name
    std::string type;       // OpenVDB value type: float, double, vec3s, int32, ...
    std::string gridClass;  // fog volume, level set, staggered, unknown
    glm::dvec3 voxelSize{0.0};
    glm::dmat4 gridFromIndex{1.0};
    bool affine = true;     // false for frustum (non-linear) transforms
    uint64_t activeVoxels = 0;
    glm::ivec3 indexMin{0}, indexMax{0};     // active voxels, inclusive; meaningless when activeVoxels = 0
    glm::dvec3 worldMin{0.0}, worldMax{0.0};
    double valueMin = 0.0, valueMax = 0.0;   // scalar grids' active values
    uint64_t nanovdbBytes = 0;               // float NanoVDB size (scalar grids), 0 otherwise
    uint64_t nanovdbFp16Bytes = 0, nanovdbFp8Bytes = 0;
};

Result<std::vector<VdbGridInfo>> inspectVdb(const std::string& path, const VdbImportOptions& options = {});

// Files at least this large report reading progress (loadSceneGrids passes `progress` on for them).
inline constexpr uint64_t kVdbProgressBytes = uint64_t(4) << 20;

// Loads volume i's density texture: its grid and mean (file relative to scene.baseDir). Errors read
// "SCENE: volumes[i].density_texture.file: ..." (or .grid: for a grid without positive values).
Result<void> loadDensityTexture(DensityTexture& texture, const Scene& scene, const std::string& sceneFile, size_t i,
                                uint64_t memoryLimitBytes, std::vector<std::string>& warnings);

// Makes mesh volume i's fog grid from its file (io/mesh_import.h) into Volume::density, encoded like the
// scene's vdb volumes. Errors read "SCENE: volumes[i].file: ...".
Result<void> loadMeshVolume(Volume& volume, const Scene& scene, const std::string& sceneFile, size_t i,
                            uint64_t memoryLimitBytes, std::vector<std::string>& warnings);

// Loads the grid of every vdb volume (and mesh volume) (file relative to scene.baseDir) into Volume::density.
// Errors read "SCENE: volumes[i].file: what is wrong"; warnings go to `warnings`.
// progress(file, fraction), for files of kVdbProgressBytes or more; optional.
Result<void> loadSceneGrids(Scene& scene, const std::string& sceneFile, uint64_t memoryLimitBytes,
                            std::vector<std::string>& warnings,
                            const std::function<void(const std::string&, float)>& progress = {});

}  // namespace brume
