// Helpers shared by the test binaries.
#pragma once

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <system_error>

#include <unistd.h>

#include "core/scene.h"

namespace brume::test {

// Whether this build has the GPU renderer (CMake option BRUME_BUILD_GPU; the sanitized build has
// not). Tests of the command line's options render with the build's default renderer: the GPU's,
// or --cpu without it; tests of the GPU renderer itself skip, saying why. Defined for the test
// programs (tests/CMakeLists.txt brume_test), not for the benchmarks that share this header.
#ifdef BRUME_TEST_GPU_BUILT
inline constexpr bool kGpuBuilt = BRUME_TEST_GPU_BUILT != 0;
inline const char* defaultRendererFlag() { return kGpuBuilt ? "" : " --cpu"; }
#define BRUME_REQUIRE_GPU_BUILD()                                                                  \
    do {                                                                                           \
        if (!::brume::test::kGpuBuilt) GTEST_SKIP() << "built without the GPU renderer (BRUME_BUILD_GPU=OFF)"; \
    } while (0)
#endif

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

// A whole file as text ("" when it cannot be read).
inline std::string readText(const std::filesystem::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

// s as one POSIX shell word, for the command lines the CLI tests run through std::system / popen.
inline std::string quoted(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

inline size_t fileCount(const std::filesystem::path& dir) {
    return static_cast<size_t>(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()));
}

// A box fog volume of the given centre and size [m] (no rotation) and coefficients [1/m].
inline Volume boxFog(glm::vec3 center, glm::vec3 size, float edgeFade, glm::vec3 sigmaS, glm::vec3 sigmaA) {
    Volume v;
    v.type = VolumeType::Box;
    v.transform.translation = center;
    v.transform.scale = size;
    v.edge_fade = edgeFade;
    v.medium.scattering = sigmaS;
    v.medium.absorption = sigmaA;
    return v;
}
inline Volume boxFog(glm::vec3 center, glm::vec3 size, float edgeFade, float sigmaS, float sigmaA) {
    return boxFog(center, size, edgeFade, glm::vec3(sigmaS), glm::vec3(sigmaA));
}

// The horizontal plane y = 0.
inline Geometry groundPlane(glm::vec3 albedo) {
    Geometry g;
    g.type = GeometryType::Plane;
    g.albedo = albedo;
    return g;
}

// The view several froxel tests share: 1.8 m up, 7 m back, looking at (0, 1, 0), a dim blue sky.
inline Scene sceneWithTestView() {
    Scene s;
    s.camera.position = {0.0f, 1.8f, 7.0f};
    s.camera.target = {0.0f, 1.0f, 0.0f};
    s.camera.fov_y_deg = 55.0f;
    s.camera.far = 60.0f;
    s.ambient = {0.02f, 0.025f, 0.03f};
    return s;
}

// A point light at p with the given range [m] and intensity.
inline Light pointLight(glm::vec3 p, float range, float intensity) {
    Light l = makeLight(LightType::Point);
    l.position = p;
    l.range = range;
    l.intensity = intensity;
    return l;
}

// The light-culling tests' view: 1.5 m up at z = 6 looking at (0, 0.5, 0), camera far 40 m, froxels
// of 8 px and 48 slices up to froxelFar [m], in exponential height fog based at 0.5 m.
inline Scene heightFogView(float froxelFar, float falloff, glm::vec3 scattering) {
    Scene s;
    s.camera.position = {0.0f, 1.5f, 6.0f};
    s.camera.target = {0.0f, 0.5f, 0.0f};
    s.camera.far = 40.0f;
    s.froxels.tile_px = 8;
    s.froxels.slices = 48;
    s.froxels.far = froxelFar;
    Volume fog;
    fog.type = VolumeType::Height;
    fog.profile = HeightProfile::Exponential;
    fog.base_height = 0.5f;
    fog.falloff = falloff;
    fog.medium.scattering = scattering;
    s.volumes = {fog};
    return s;
}

}  // namespace brume::test
