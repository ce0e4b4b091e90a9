#include "fog_bake.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <vector>

#include <openvdb/openvdb.h>

#include "core/compile.h"
#include "core/parallel.h"
#include "io/atomic_file.h"

#ifndef BRUME_VERSION_STRING
#define BRUME_VERSION_STRING "unknown"
#endif

namespace brume {
namespace {

// A bound at least this far out is "unbounded" (the compiled volumes use 1e30).
constexpr float kUnbounded = 1.0e29f;
// Slices of voxels evaluated together between two progress reports and grid insertions.
constexpr int kSlab = 8;

bool finite(const WorldBox& b) {
    for (int a = 0; a < 3; ++a)
        if (!(std::abs(b.min[a]) < kUnbounded && std::abs(b.max[a]) < kUnbounded)) return false;
    return true;
}

}  // namespace

Result<WorldBox> bakeBox(const Scene& scene, const BakeOptions& options, const std::string& sceneName) {
    const CompiledScene cs = compileScene(scene);
    WorldBox box{glm::vec3(kUnbounded * 10.0f), glm::vec3(-kUnbounded * 10.0f)};
    bool any = false;
    for (size_t i = 0; i < cs.volumes.size(); ++i) {
        WorldBox b{glm::vec3(cs.volumes[i].worldMin), glm::vec3(cs.volumes[i].worldMax)};
        if (glm::any(glm::greaterThan(b.min, b.max))) continue;  // an empty vdb grid
        if (!finite(b) && !options.bounds)
            return Error{sceneName + ": volumes[" + std::to_string(i) + "]" +
                             (scene.volumes[i].name.empty() ? "" : " \"" + scene.volumes[i].name + "\"") + " is a " +
                             toString(scene.volumes[i].type) +
                             " fog without bounds; give --bounds XMIN YMIN ZMIN XMAX YMAX ZMAX to bake it",
                         true};
        box.min = glm::min(box.min, b.min);
        box.max = glm::max(box.max, b.max);
        any = true;
    }
    if (!any) return Error{sceneName + ": volumes: nothing to bake (no volume with fog)", true};
    if (options.bounds) {
        box.min = glm::max(box.min, options.bounds->min);
        box.max = glm::min(box.max, options.bounds->max);
        if (glm::any(glm::greaterThanEqual(box.min, box.max)))
            return Error{sceneName + ": --bounds does not overlap any volume", true};
    }
    return box;
}

Result<BakeResult> bakeFogVdb(const Scene& scene, const BakeOptions& options, const std::string& sceneName,
                              const std::string& path) {
    Result<WorldBox> box = bakeBox(scene, options, sceneName);
    if (!box) return box.error();
    const float h = options.voxelSize;
    // Voxel centres i * h inside the box.
    const glm::ivec3 lo = glm::ivec3(glm::ceil(box.value().min / h));
    const glm::ivec3 hi = glm::ivec3(glm::floor(box.value().max / h));
    const glm::ivec3 n = glm::max(hi - lo + 1, glm::ivec3(0));
    const uint64_t total = uint64_t(n.x) * uint64_t(n.y) * uint64_t(n.z);
    if (total == 0) return Error{sceneName + ": the baked box holds no voxel centre; use a smaller --voxel-size", true};
    if (total > options.maxVoxels)
        return Error{sceneName + ": the bake would cover " + std::to_string(total) + " voxels (" + std::to_string(n.x) + " x " +
                         std::to_string(n.y) + " x " + std::to_string(n.z) + "), over the limit of " +
                         std::to_string(options.maxVoxels) + "; use a larger --voxel-size or smaller --bounds",
                     true};

    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
    const openvdb::math::Transform::Ptr xform = openvdb::math::Transform::createLinearTransform(h);
    openvdb::FloatGrid::Ptr density = openvdb::FloatGrid::create(0.0f);
    density->setName("density");
    density->setGridClass(openvdb::GRID_FOG_VOLUME);
    openvdb::Vec3SGrid::Ptr albedo = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
    albedo->setName("Cd");
    openvdb::Vec3SGrid::Ptr emission = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
    emission->setName("emission");
    for (openvdb::GridBase::Ptr g : {openvdb::GridBase::Ptr(density), openvdb::GridBase::Ptr(albedo), openvdb::GridBase::Ptr(emission)})
        g->setTransform(xform);
    density->insertMeta("units", openvdb::StringMetadata("sigma_t [1/m]"));
    albedo->insertMeta("units", openvdb::StringMetadata("single-scattering albedo sigma_s / sigma_t"));
    emission->insertMeta("units", openvdb::StringMetadata("emitted radiance per meter [W/(m^2 sr m)]"));

    const CompiledScene cs = compileScene(scene);
    const size_t slice = size_t(n.x) * size_t(n.y);
    std::vector<shd::MediaSample> media(slice * kSlab);
    auto da = density->getAccessor();
    auto aa = albedo->getAccessor();
    auto ea = emission->getAccessor();
    BakeResult result;
    result.box = box.value();
    result.voxels = n;
    for (int z0 = 0; z0 < n.z; z0 += kSlab) {
        const int zs = std::min(kSlab, n.z - z0);
        parallelFor(zs * n.y, options.threads, [&](int row) {
            const int z = row / n.y, y = row % n.y;
            for (int x = 0; x < n.x; ++x) {
                const glm::vec3 p = glm::vec3(lo + glm::ivec3(x, y, z0 + z)) * h;
                media[size_t(z) * slice + size_t(y) * size_t(n.x) + size_t(x)] = mediaAt(cs, p);
            }
        });
        for (int z = 0; z < zs; ++z)
            for (int y = 0; y < n.y; ++y)
                for (int x = 0; x < n.x; ++x) {
                    const shd::MediaSample& m = media[size_t(z) * slice + size_t(y) * size_t(n.x) + size_t(x)];
                    const float sigmaT = (m.sigmaT.x + m.sigmaT.y + m.sigmaT.z) / 3.0f;
                    const bool emits = m.emission.x > 0.0f || m.emission.y > 0.0f || m.emission.z > 0.0f;
                    if (!(sigmaT > 0.0f) && !emits) continue;
                    const openvdb::Coord c(lo.x + x, lo.y + y, lo.z + z0 + z);
                    da.setValueOn(c, sigmaT);
                    glm::vec3 cd(0.0f);
                    for (int a = 0; a < 3; ++a) cd[a] = m.sigmaT[a] > 0.0f ? std::min(1.0f, m.sigmaS[a] / m.sigmaT[a]) : 0.0f;
                    aa.setValueOn(c, openvdb::Vec3s(cd.x, cd.y, cd.z));
                    if (emits) ea.setValueOn(c, openvdb::Vec3s(m.emission.x, m.emission.y, m.emission.z));
                    ++result.activeVoxels;
                }
        if (options.progress) options.progress(float(z0 + zs) / float(n.z));
    }
    for (openvdb::GridBase::Ptr g : {openvdb::GridBase::Ptr(density), openvdb::GridBase::Ptr(albedo), openvdb::GridBase::Ptr(emission)})
        g->pruneGrid();

    openvdb::MetaMap meta;
    meta.insertMeta("creator", openvdb::StringMetadata(std::string("Brume ") + BRUME_VERSION_STRING));
    meta.insertMeta("brume_version", openvdb::StringMetadata(BRUME_VERSION_STRING));
    meta.insertMeta("units", openvdb::StringMetadata("meters; density = sigma_t [1/m], Cd = albedo, emission = W/(m^2 sr m)"));
    meta.insertMeta("voxel_size_m", openvdb::FloatMetadata(h));
    Result<void> w = writeFileAtomic(path, [&](const std::string& tmpPath) -> Result<void> {
        try {
            openvdb::io::File file(tmpPath);
            file.write({density, albedo, emission}, meta);
            file.close();
        } catch (const std::exception& e) {
            return Error{path + ": cannot write the OpenVDB file (" + std::string(e.what()) + ").", true};
        }
        return {};
    });
    if (!w) return w.error();
    return result;
}

}  // namespace brume
