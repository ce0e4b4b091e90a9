// Mesh volumes on the GPU: the fog grid made from the mesh goes through the vdb path (NanoVDB in the
// voxelize pass, occupancy cells, fog shadows), so the GPU must agree with the CPU froxel renderer as
// for vdb volumes: within 1% relative mean absolute error; the validation layer must stay silent.
#include <gtest/gtest.h>

#include <cstdio>
#include <unistd.h>

#include "core/compile.h"
#include "core/render.h"
#include "gpu/gpu_renderer.h"
#include "gpu_test_support.h"
#include "io/mesh_import.h"
#include "mesh_test_util.h"

using namespace brume;
namespace fs = std::filesystem;

namespace {

constexpr double kTolerance = 0.01;

// An L-shaped prism (concave: the occupancy cells skip its notch), as an OBJ.
std::string lPrismObj() {
    const float xy[6][2] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
    std::string s;
    for (int z = 0; z < 2; ++z)
        for (const auto& p : xy)
            s += "v " + std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(z ? 1.0 : 0.0) + "\n";
    s += "f 1 2 3 4 5 6\nf 7 12 11 10 9 8\n";  // the caps, fanned from (0, 0): the L is star-shaped from there
    for (int i = 0; i < 6; ++i) {
        const int a = i + 1, b = (i + 1) % 6 + 1;
        s += "f " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(b + 6) + " " +
             std::to_string(a + 6) + "\n";
    }
    return s;
}

}  // namespace

class GpuMesh : public test::ValidatedGpuTest {};

TEST_F(GpuMesh, MeshVolumeMatchesTheCpuFroxelRenderer) {
    const fs::path dir = fs::temp_directory_path() / ("brume_gpu_mesh_" + std::to_string(getpid()));
    test::writeText(dir / "l.obj", lPrismObj());
    Result<VdbLoad> load = loadMeshDensity((dir / "l.obj").string(), 0.15f, {});
    fs::remove_all(dir);
    ASSERT_TRUE(load.ok()) << load.error().message;
    Volume v;
    v.type = VolumeType::Mesh;
    v.file = "l.obj";
    v.edge_fade_m = 0.15f;
    v.density = load.value().grid;
    v.transform.translation = {-0.8f, 0.2f, -0.4f};
    v.transform.rotation_deg = {0.0f, 30.0f, 0.0f};
    v.medium.scattering = {3.0f, 3.4f, 3.8f};
    v.medium.absorption = glm::vec3(0.3f);
    v.medium.phase_g = 0.4f;
    EXPECT_NE(v.density->occupancyOffset(), 0u) << "the occupancy cells should cull the hull's empty space";

    Scene s;
    s.camera.position = {0.8f, 2.0f, 3.4f};
    s.camera.target = {0.0f, 0.8f, 0.0f};
    s.camera.far = 40.0f;
    s.froxels.far = 15.0f;
    s.froxels.slices = 48;
    s.ambient = {0.05f, 0.06f, 0.08f};
    Light sun = makeLight(LightType::Directional);
    sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.4f));
    sun.shadows = true;
    s.lights = {sun};
    Geometry ground;
    ground.type = GeometryType::Plane;
    s.geometry = {ground};
    s.volumes = {v};

    RenderRequest request;
    request.width = 160;
    request.height = 90;
    request.threads = 2;
    const FroxelResult cpu = renderFroxelCpu(s, request);
    auto gpu = renderer->render(s, request, true);
    ASSERT_TRUE(gpu.ok()) << gpu.error().message;
    const double mediaErr = relativeMeanAbsError(test::asImage(gpu.value().volumes.mediaExtinction),
                                                 test::asImage(cpu.volumes.mediaExtinction));
    const double imageErr = relativeMeanAbsError(gpu.value().image, cpu.image);
    Scene noFog = s;
    noFog.volumes.clear();
    const double share = relativeMeanAbsError(renderFroxelCpu(noFog, request).image, cpu.image);
    std::printf("[gpu-vs-cpu mesh] sigma_t %.2e image %.2e (the hull's share of the image %.2f)\n", mediaErr, imageErr,
                share);
    EXPECT_TRUE(allFinite(gpu.value().image));
    EXPECT_LT(mediaErr, kTolerance);
    EXPECT_LT(imageErr, kTolerance);
    EXPECT_GT(share, 5.0 * kTolerance) << "the hull barely shows: the comparison could not fail";
}
