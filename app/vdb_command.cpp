#include "vdb_command.h"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/vdb_import.h"
#include "progress.h"

namespace brume::app {

Result<void> loadGridsPrintingWarnings(Scene& scene, const std::string& scenePath, int memoryLimitMb) {
    std::vector<std::string> warnings;
    // One progress line per large file, ended before the next starts (files load one after another).
    std::unique_ptr<ProgressLine> line;
    std::string lineFile;
    auto progress = [&](const std::string& file, float fraction) {
        if (!line || lineFile != file) {
            if (line) line->complete();  // the previous file loaded
            line = std::make_unique<ProgressLine>("reading " + file);
            lineFile = file;
        }
        line->update(fraction);
    };
    Result<void> r = loadSceneGrids(scene, scenePath, static_cast<uint64_t>(memoryLimitMb) << 20, warnings, progress);
    if (line && r) line->complete();
    line.reset();
    for (const std::string& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    return r;
}

CLI::App* addInfoCommand(CLI::App& app, InfoOptions& o) {
    CLI::App* cmd = app.add_subcommand("info", "List the grids of an OpenVDB file (name, type, class, transform, "
                                               "active voxels, bounds, values, NanoVDB memory).");
    cmd->add_option("FILE", o.path, "OpenVDB file (.vdb).")->required();
    cmd->add_flag("--json", o.json, "Print JSON instead of text. Default: off.");
    return cmd;
}

namespace {

using nlohmann::json;

json vec(glm::dvec3 v) { return json::array({v.x, v.y, v.z}); }
json ivec(glm::ivec3 v) { return json::array({v.x, v.y, v.z}); }

json toJson(const VdbGridInfo& g) {
    json m = json::array();
    for (int r = 0; r < 4; ++r) m.push_back(json::array({g.gridFromIndex[0][r], g.gridFromIndex[1][r],
                                                         g.gridFromIndex[2][r], g.gridFromIndex[3][r]}));
    json j = {{"name", g.name}, {"type", g.type}, {"class", g.gridClass}, {"voxel_size", vec(g.voxelSize)},
              {"affine", g.affine}, {"world_from_index", m}, {"active_voxels", g.activeVoxels}};
    if (g.activeVoxels > 0) {
        j["index_bbox"] = {ivec(g.indexMin), ivec(g.indexMax)};
        j["world_bbox"] = {vec(g.worldMin), vec(g.worldMax)};
        j["value_range"] = {g.valueMin, g.valueMax};
    }
    if (g.nanovdbBytes > 0)
        j["nanovdb_bytes"] = {{"float", g.nanovdbBytes}, {"fp16", g.nanovdbFp16Bytes}, {"fp8", g.nanovdbFp8Bytes}};
    return j;
}

double mib(uint64_t b) { return static_cast<double>(b) / (1024.0 * 1024.0); }

void printText(const std::string& path, const std::vector<VdbGridInfo>& grids) {
    std::printf("%s: %zu grid%s\n", path.c_str(), grids.size(), grids.size() == 1 ? "" : "s");
    for (const VdbGridInfo& g : grids) {
        std::printf("  %s: %s, %s, %llu active voxels\n", g.name.c_str(), g.type.c_str(), g.gridClass.c_str(),
                    static_cast<unsigned long long>(g.activeVoxels));
        std::printf("    voxel size %g x %g x %g%s\n", g.voxelSize.x, g.voxelSize.y, g.voxelSize.z,
                    g.affine ? "" : " (frustum transform: not supported for rendering)");
        for (int r = 0; r < 3; ++r)
            std::printf("    world_from_index row %d: %g %g %g %g\n", r, g.gridFromIndex[0][r], g.gridFromIndex[1][r],
                        g.gridFromIndex[2][r], g.gridFromIndex[3][r]);
        if (g.activeVoxels > 0) {
            std::printf("    index bbox [%d %d %d]..[%d %d %d]\n", g.indexMin.x, g.indexMin.y, g.indexMin.z,
                        g.indexMax.x, g.indexMax.y, g.indexMax.z);
            std::printf("    world bbox (%g %g %g)..(%g %g %g)\n", g.worldMin.x, g.worldMin.y, g.worldMin.z,
                        g.worldMax.x, g.worldMax.y, g.worldMax.z);
            if (g.type == "float" || g.type == "double") std::printf("    values %g..%g\n", g.valueMin, g.valueMax);
        }
        if (g.nanovdbBytes > 0)
            std::printf("    NanoVDB: %.3f MiB float, %.3f MiB Fp16, %.3f MiB Fp8\n", mib(g.nanovdbBytes),
                        mib(g.nanovdbFp16Bytes), mib(g.nanovdbFp8Bytes));
    }
}

}  // namespace

CommandResult runInfo(const InfoOptions& o) {
    VdbImportOptions options;
    std::unique_ptr<ProgressLine> line;
    std::error_code ec;
    if (std::filesystem::file_size(o.path, ec) >= kVdbProgressBytes && !ec) {
        line = std::make_unique<ProgressLine>("reading " + o.path);
        options.progress = [&line](float fraction) { line->update(fraction); };
    }
    Result<std::vector<VdbGridInfo>> grids = inspectVdb(o.path, options);
    if (line && grids) line->complete();
    line.reset();
    if (!grids) return badInput(grids.error().message);
    if (o.json) {
        json j = {{"file", o.path}, {"grids", json::array()}};
        for (const VdbGridInfo& g : grids.value()) j["grids"].push_back(toJson(g));
        std::printf("%s\n", j.dump(2).c_str());
    } else {
        printText(o.path, grids.value());
    }
    return success();
}

}  // namespace brume::app
