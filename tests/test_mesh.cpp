// Mesh fog hulls (io/mesh_import.h): a closed mesh becomes a fog grid whose density is the closed
// form smoothstep(0, edge_fade_m, depth below the surface); a cube hull renders like the equal box
// volume (whose edge fade is the same function of the depth below its faces) in the CPU froxel
// renderer and the reference; meshes with holes and bad files are refused in one sentence (exit 2).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sys/wait.h>

#include "core/compile.h"
#include "core/render.h"
#include "io/mesh_import.h"
#include "io/scene_json.h"
#include "mesh_test_util.h"
#include "sanitizer_build.h"
#include "test_support.h"

using namespace brume;
namespace fs = std::filesystem;

namespace {

class Mesh : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("brume_mesh_" + std::to_string(getpid()) + "_" + info->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string write(const std::string& name, const std::string& text) const {
        test::writeText(dir_ / name, text);
        return (dir_ / name).string();
    }
    static std::string loadError(const std::string& path, float fade = 0.1f) {
        Result<VdbLoad> r = loadMeshDensity(path, fade, {});
        EXPECT_FALSE(r.ok());
        return r.ok() ? "" : r.error().message;
    }

    fs::path dir_;
};

// The cube [-1, 1]^3 as a mesh volume and as the equal box (scale 2; edge_fade = fade / half-size), both
// under the same rotated, non-uniformly scaled transform.
struct CubePair {
    Volume mesh, box;
};
CubePair cubePair(const std::string& obj, float fade) {
    Transform t;
    t.translation = {0.2f, 1.1f, -0.3f};
    t.rotation_deg = {0.0f, 25.0f, 10.0f};
    t.scale = {1.3f, 0.9f, 1.0f};
    Medium m;
    m.scattering = {1.8f, 2.0f, 2.2f};
    m.absorption = glm::vec3(0.15f);
    m.emission = {0.02f, 0.01f, 0.0f};
    m.phase_g = 0.3f;
    CubePair p;
    p.mesh.type = VolumeType::Mesh;
    p.mesh.file = obj;
    p.mesh.edge_fade_m = fade;
    p.mesh.transform = t;
    p.mesh.medium = m;
    Result<VdbLoad> r = loadMeshDensity(obj, fade, {});
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
    if (r.ok()) p.mesh.density = r.value().grid;
    p.box.type = VolumeType::Box;
    p.box.transform = t;
    p.box.transform.scale *= 2.0f;
    p.box.edge_fade = fade / 1.0f;
    p.box.medium = m;
    return p;
}

Scene sceneWith(const Volume& v) {
    Scene s;
    s.camera.position = {1.2f, 2.2f, 3.9f};
    s.camera.target = {0.2f, 1.0f, -0.3f};
    s.camera.far = 40.0f;
    s.froxels.far = 20.0f;
    s.ambient = {0.15f, 0.17f, 0.2f};
    Light sun = makeLight(LightType::Directional);
    sun.direction = glm::normalize(glm::vec3(0.4f, -1.0f, -0.3f));
    sun.shadows = true;
    s.lights = {sun};
    Geometry ground;
    ground.type = GeometryType::Plane;
    ground.height = -0.2f;
    s.geometry = {ground};
    s.volumes = {v};
    return s;
}

}  // namespace

// ---- reading and checking ----

TEST_F(Mesh, ObjQuadsAreTriangulatedAndSplitVerticesWelded) {
    // The cube with each face's four vertices written again (as exporters split vertices at seams),
    // with texture and normal indices, relative indices and comments.
    const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    std::string obj = "# split cube\nvt 0 0\nvn 0 0 1\n";
    for (const auto& f : faces) {
        for (int c : f)
            obj += "v " + std::to_string((c & 1) ? 1 : -1) + " " + std::to_string((c & 2) ? 1 : -1) + " " +
                   std::to_string((c & 4) ? 1 : -1) + "\n";
        obj += "f -4/1/1 -3/1/1 -2//1 -1\n";
    }
    Result<TriangleMesh> m = readObjMesh(write("split.obj", obj));
    ASSERT_TRUE(m.ok()) << m.error().message;
    EXPECT_EQ(m.value().points.size(), 8u);
    EXPECT_EQ(m.value().triangles.size(), 12u);
    EXPECT_EQ(openEdgeCount(m.value()), 0u);
}

TEST_F(Mesh, HolesAreCountedAndTheMeshIsRefused) {
    Result<TriangleMesh> m = readObjMesh(write("open.obj", test::cubeObj(1.0f, 2)));
    ASSERT_TRUE(m.ok());
    EXPECT_EQ(openEdgeCount(m.value()), 4u);  // the square hole's rim
    const std::string path = (dir_ / "open.obj").string();
    const std::string e = loadError(path);
    EXPECT_NE(e.find(path), std::string::npos) << e;
    EXPECT_NE(e.find("not closed"), std::string::npos) << e;
    EXPECT_NE(e.find("4 edges"), std::string::npos) << e;
}

// Two cubes sharing one edge: that edge borders 4 triangles (non-manifold) but the surface is closed.
TEST_F(Mesh, NonManifoldButClosedIsAccepted) {
    std::string obj = test::cubeObj(0.5f);
    for (int i = 0; i < 8; ++i)
        obj += "v " + std::to_string((i & 1) ? 1.5 : 0.5) + " " + std::to_string((i & 2) ? 1.5 : 0.5) + " " +
               std::to_string((i & 4) ? 0.5 : -0.5) + "\n";
    obj += "f 9 11 12 10\nf 13 14 16 15\nf 9 10 14 13\nf 11 15 16 12\nf 9 13 15 11\nf 10 12 16 14\n";
    Result<TriangleMesh> m = readObjMesh(write("two.obj", obj));
    ASSERT_TRUE(m.ok());
    EXPECT_EQ(m.value().points.size(), 14u);  // the shared edge's two points welded
    EXPECT_EQ(openEdgeCount(m.value()), 0u);
    Result<VdbLoad> l = loadMeshDensity((dir_ / "two.obj").string(), 0.05f, {});
    ASSERT_TRUE(l.ok()) << l.error().message;
}

TEST_F(Mesh, BadFilesGiveOneSentenceNamingTheFile) {
    struct Case {
        const char* name;
        std::string text;
        const char* says;
    };
    std::string huge = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf";  // one polygon of cap + 1 triangles
    for (size_t i = 0; i < kMeshMaxTriangles + 3; ++i) huge += (i % 3 == 0) ? " 1" : (i % 3 == 1) ? " 2" : " 3";
    const Case cases[] = {
        {"empty.obj", "", "no triangles"},
        {"points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "no triangles"},
        {"nan.obj", test::cubeObj() + "v nan 0 0\n", "non-finite"},
        {"inf.obj", "v 0 0 inf\n" + test::cubeObj(), "non-finite"},
        {"range.obj", test::cubeObj() + "f 1 2 99\n", "vertex 99"},
        {"words.obj", "v 0 0 zero\n", "three numbers"},
        {"binary.obj", std::string("\x7f" "ELF\x02\x01\x01\0\nf \x01 \x02 \x03\n", 17), "not a vertex index"},
        {"degenerate.obj", "v 0 0 0\nv 1 0 0\nf 1 2 2\n", "degenerate"},
        {"huge.obj", huge, "2000000 triangles"},
    };
    for (const Case& c : cases) {
        const std::string path = write(c.name, c.text);
        const std::string e = loadError(path);
        EXPECT_EQ(e.rfind(path + ": ", 0), 0u) << c.name << ": " << e;
        EXPECT_NE(e.find(c.says), std::string::npos) << c.name << ": " << e;
        EXPECT_EQ(e.find('\n'), std::string::npos) << c.name << ": " << e;
    }
    const std::string missing = (dir_ / "missing.obj").string();
    EXPECT_NE(loadError(missing).find(missing + ": cannot read the file"), std::string::npos);
    EXPECT_NE(loadError(dir_.string()).find("cannot read"), std::string::npos);  // a folder
}

// ---- PLY ----

// The cube [-1, 1]^3 as PLY: ASCII with quads, a normal per vertex and an extra element; or binary
// little-endian with triangles, int32 indices after a uchar count and a double property between.
std::string plyCube(bool binary, const std::string& vertexLine = "") {
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    std::string s = "ply\nformat " + std::string(binary ? "binary_little_endian" : "ascii") + " 1.0\ncomment cube\n";
    s += binary ? "element vertex 8\nproperty float x\nproperty double w\nproperty float y\nproperty float z\n"
                : "element vertex 8\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\n";
    s += binary ? "element face 12\nproperty list uchar int vertex_indices\n"
                : "element face 6\nproperty list uchar int vertex_index\nelement edge 1\nproperty int vertex1\nproperty int vertex2\n";
    s += "end_header\n";
    auto put = [&s](const void* p, size_t n) { s.append(static_cast<const char*>(p), n); };
    for (int i = 0; i < 8; ++i) {
        const float x = (i & 1) ? 1.0f : -1.0f, y = (i & 2) ? 1.0f : -1.0f, z = (i & 4) ? 1.0f : -1.0f;
        if (!binary) {
            s += (i == 0 && !vertexLine.empty()) ? vertexLine : std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z) + " 0\n";
            continue;
        }
        const double w = 7.0;
        const float nan = std::nanf("");
        put(i == 0 && !vertexLine.empty() ? &nan : &x, 4), put(&w, 8), put(&y, 4), put(&z, 4);
    }
    for (const auto& q : quads) {
        if (!binary) {
            s += "4 " + std::to_string(q[0]) + " " + std::to_string(q[1]) + " " + std::to_string(q[2]) + " " + std::to_string(q[3]) + "\n";
            continue;
        }
        for (const int t : {0, 2}) {
            const unsigned char n = 3;
            const int32_t idx[3] = {q[0], q[t == 0 ? 1 : 2], q[t == 0 ? 2 : 3]};
            put(&n, 1), put(idx, 12);
        }
    }
    if (!binary) s += "0 1\n";
    return s;
}

TEST_F(Mesh, PlyAsciiQuadsAndBinaryTrianglesReadAsTheCube) {
    for (const bool binary : {false, true}) {
        Result<TriangleMesh> m = readMesh(write(binary ? "cube.PLY" : "cube.ply", plyCube(binary)));
        ASSERT_TRUE(m.ok()) << m.error().message;
        EXPECT_EQ(m.value().points.size(), 8u) << binary;
        EXPECT_EQ(m.value().triangles.size(), 12u) << binary;
        EXPECT_EQ(openEdgeCount(m.value()), 0u) << binary;
        for (const glm::vec3& p : m.value().points) EXPECT_EQ(glm::abs(p), glm::vec3(1.0f)) << binary;
    }
    // Through the reader process, the binary cube's grid is the OBJ cube's.
    Result<VdbLoad> ply = loadMeshDensity(write("b.ply", plyCube(true)), 0.2f, {});
    Result<VdbLoad> obj = loadMeshDensity(write("c.obj", test::cubeObj()), 0.2f, {});
    ASSERT_TRUE(ply.ok() && obj.ok()) << (ply.ok() ? "" : ply.error().message);
    for (const glm::vec3 p : {glm::vec3(0.0f), glm::vec3(0.93f, 0.1f, -0.5f), glm::vec3(-0.97f, 0.97f, 0.2f)}) {
        const glm::vec3 index = glm::vec3(glm::inverse(obj.value().grid->gridFromIndex()) * glm::vec4(p, 1.0f));
        EXPECT_EQ(ply.value().grid->sampleIndex(index), obj.value().grid->sampleIndex(index)) << p.x;
    }
}

TEST_F(Mesh, BadPlyFilesGiveTheObjSentences) {
    const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
    const struct {
        const char* name;
        std::string text;
        const char* says;
    } cases[] = {
        {"nofaces.ply", header + "end_header\n0 0 0\n1 0 0\n0 1 0\n", "no triangles"},
        {"nan.ply", plyCube(false, "nan 0 0 0\n"), "non-finite"},
        {"nanbin.ply", plyCube(true, "nan"), "non-finite"},
        {"huge.ply", header + "element face 2000001\nproperty list uchar int vertex_indices\nend_header\n", "2000000 triangles"},
        {"range.ply", header + "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", "vertex 8"},
        {"short.ply", header + "end_header\n0 0 0\n", "cut short"},
        {"big.ply", "ply\nformat binary_big_endian 1.0\nend_header\n", "not supported"},
        {"text.ply", "solid cube\n", "not a PLY file"},
    };
    for (const auto& c : cases) {
        const std::string path = write(c.name, c.text);
        const std::string e = loadError(path);
        EXPECT_EQ(e.rfind(path + ": ", 0), 0u) << c.name << ": " << e;
        EXPECT_NE(e.find(c.says), std::string::npos) << c.name << ": " << e;
        EXPECT_EQ(e.find('\n'), std::string::npos) << c.name << ": " << e;
    }
    const std::string missing = (dir_ / "missing.ply").string();
    EXPECT_NE(loadError(missing).find(missing + ": cannot read the file"), std::string::npos);
}

// ---- the density ----

// At points throughout and around the hull, the sampled density against the closed form: the box's,
// which for a cube is smoothstep(0, fade, depth below the nearest face).
TEST_F(Mesh, CubeDensityMatchesTheBoxClosedForm) {
    const float fade = 0.2f;
    const CubePair p = cubePair(write("cube.obj", test::cubeObj()), fade);
    ASSERT_TRUE(p.mesh.density);
    Scene s;
    s.volumes = {p.mesh, p.box};
    const CompiledScene cs = compileScene(s);
    const glm::mat4 worldFromLocal = p.mesh.transform.worldFromLocal();
    double maxErr = 0.0, sumErr = 0.0, sumBox = 0.0;
    int n = 0;
    for (float x = -1.23f; x <= 1.25f; x += 0.071f)
        for (float y = -1.19f; y <= 1.25f; y += 0.083f)
            for (float z = -1.21f; z <= 1.25f; z += 0.067f) {
                const glm::vec3 world = glm::vec3(worldFromLocal * glm::vec4(x, y, z, 1.0f));
                const float mesh = shd::insideBounds(cs.volumes[0], world) ? volumeDensity(cs, 0, world) : 0.0f;
                const float box = shd::insideBounds(cs.volumes[1], world) ? volumeDensity(cs, 1, world) : 0.0f;
                maxErr = std::max(maxErr, double(std::abs(mesh - box)));
                sumErr += std::abs(mesh - box);
                sumBox += box;
                ++n;
            }
    std::printf("cube hull density vs box: max abs error %.3f, mean abs error / mean %.2e over %d points (voxel %.4f m)\n",
                maxErr, sumErr / sumBox, n, meshVoxelSize(2.0f, fade));
    // The largest errors lie on the cube's inner diagonal planes, where the depth below the nearest
    // face has a kink that trilinear interpolation rounds off (slope 1.5 / fade x a quarter voxel).
    EXPECT_LT(maxErr, 0.15);
    EXPECT_LT(sumErr / sumBox, 0.015);
}

TEST_F(Mesh, VoxelSizeFollowsTheFadeWithinTheCaps) {
    EXPECT_FLOAT_EQ(meshVoxelSize(2.0f, 0.2f), 0.05f);             // fade / 4
    EXPECT_FLOAT_EQ(meshVoxelSize(2.0f, 0.0f), 2.0f / 128.0f);     // finest allowed
    EXPECT_FLOAT_EQ(meshVoxelSize(2.0f, 100.0f), 2.0f / 32.0f);    // coarsest allowed
    // The hard edge's one-voxel ramp has the hard step's integral across the surface.
    double integral = 0.0;
    for (double d = -3.0; d < 3.0; d += 1e-4) integral += meshFogDensity(static_cast<float>(d + 0.5e-4), 0.0f, 0.5f) * 1e-4;
    EXPECT_NEAR(integral, 3.0, 1e-3);
}

// height_falloff inside a hull (issue 15: "inside any local volume"): the density is the hull's times
// exp(-k (y - bottom)) at every sampled point, bottom the lowest world point of the grid's bounds,
// which lies at most two world voxels below the rotated cube's lowest corner.
TEST_F(Mesh, HeightFalloffMultipliesTheHullFromTheBottomOfItsBounds) {
    const float k = 0.8f, fade = 0.2f;
    const CubePair p = cubePair(write("cube.obj", test::cubeObj()), fade);
    ASSERT_TRUE(p.mesh.density);
    Volume falling = p.mesh;
    falling.height_falloff = k;
    Scene s;
    s.volumes = {falling, p.mesh};
    const CompiledScene cs = compileScene(s);
    const glm::mat4 worldFromLocal = p.mesh.transform.worldFromLocal();
    float lowest = 1e30f;
    for (int i = 0; i < 8; ++i)
        lowest = std::min(lowest, (worldFromLocal * glm::vec4((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1, 1)).y);
    const float bottom = cs.volumes[0].worldMin.y;
    const float worldVoxel = meshVoxelSize(2.0f, fade) * 1.3f;  // the largest scale
    std::printf("hull bottom %.4f, lowest corner %.4f (world voxel <= %.4f)\n", bottom, lowest, worldVoxel);
    EXPECT_LE(bottom, lowest);
    EXPECT_GE(bottom, lowest - 2.0f * worldVoxel);
    int inside = 0;
    for (float x = -1.1f; x <= 1.1f; x += 0.13f)
        for (float y = -1.1f; y <= 1.1f; y += 0.11f)
            for (float z = -1.1f; z <= 1.1f; z += 0.17f) {
                const glm::vec3 w = glm::vec3(worldFromLocal * glm::vec4(x, y, z, 1.0f));
                const double flat = volumeDensity(cs, 1, w);
                const double expected = flat * std::exp(-double(k) * (double(w.y) - double(bottom)));
                EXPECT_NEAR(volumeDensity(cs, 0, w), expected, 1e-5 + 1e-5 * expected) << x << " " << y << " " << z;
                inside += flat > 0.5 ? 1 : 0;
            }
    EXPECT_GT(inside, 500);
    // A hull's falloff is keyable and round-trips through the scene format.
    Result<Scene> parsed = parseScene(R"({"brume_scene": 1, "volumes": [{"type": "mesh", "file": "h.obj", "height_falloff": 0.8,
        "keys": {"height_falloff": [{"time": 0, "value": 0.5}, {"time": 1, "value": 1}]}},
        {"type": "vdb", "file": "g.vdb", "height_falloff": 2}]})", "s.json");
    ASSERT_TRUE(parsed.ok()) << parsed.error().message;
    EXPECT_EQ(parsed.value().volumes[0].height_falloff, 0.8f);
    EXPECT_EQ(parsed.value().volumes[1].height_falloff, 2.0f);
    Result<Scene> again = parseScene(sceneToJson(parsed.value()), "s.json");
    ASSERT_TRUE(again.ok()) << again.error().message;
    EXPECT_EQ(again.value(), parsed.value());
    Result<Scene> negative = parseScene(R"({"brume_scene": 1, "volumes": [{"type": "vdb", "file": "g.vdb", "height_falloff": -1}]})", "s.json");
    ASSERT_FALSE(negative.ok());
    EXPECT_NE(negative.error().message.find("volumes[0].height_falloff"), std::string::npos) << negative.error().message;
}

// The hull with height_falloff, lit by a sun, in the CPU froxel renderer against the reference (both
// march the same falling density, the froxel renderer into its vdb shadow layer), as close as the
// hull without falloff (the 3% bound of the shapes' scene, tests/test_shapes.cpp), and the falloff
// changes the image (so the test can fail).
TEST_F(Mesh, HeightFalloffInsideTheHullFroxelMatchesTheReference) {
    const CubePair p = cubePair(write("cube.obj", test::cubeObj()), 0.2f);
    ASSERT_TRUE(p.mesh.density);
    RenderRequest request;
    request.width = 96;
    request.height = 54;
    request.threads = 2;
    request.quality = Quality::High;
    Volume falling = p.mesh;
    falling.height_falloff = 2.0f;
    const Scene flat = sceneWith(p.mesh), fall = sceneWith(falling);
    const Image refFall = renderReference(fall, request);
    const double err = relativeMeanAbsError(renderFroxelCpu(fall, request).image, refFall);
    const double errFlat = relativeMeanAbsError(renderFroxelCpu(flat, request).image, renderReference(flat, request));
    const double share = relativeMeanAbsError(renderReference(flat, request), refFall);
    std::printf("hull with height_falloff: froxel (high) vs reference %.4f (without falloff %.4f); the falloff's share %.3f\n",
                err, errFlat, share);
    EXPECT_LT(err, 0.03);
    EXPECT_GT(share, 0.05);
}

// ---- rendering: the cube hull against the equal box ----

// The froxel renderer marches vdb grids (so the hull) into its fog shadow volume, where a box's fog
// shadows are closed forms: lit by the sun, the two agree as well as that march allows, which is within
// 1% at quality ultra with the full-resolution transmittance volume (1.2% at high, 0.9% with it:
// docs/vdb.md, "Mesh fog hulls"); lit by the sky alone they agree to the grid's sampling.
// Nearly all of the test's time is the reference's image of the hull: its fog shadows march the grid
// (up to 128^3 voxels, edge_fade_m 0) at a quarter voxel per step from every step of every camera
// ray. Under AddressSanitizer (scripts/test --sanitize: clang -O1, every check on, glm and NanoVDB's
// accessors out of line) that costs ~17x a normal build's CPU time: the test took 122 CPU s, 219 s of
// wall time at load 6, where a normal build takes 7 CPU s (docs/reliability.md "san"). There the
// reference pair renders at 48x27: the same scene, the same bounds, a quarter of the camera rays
// (each still marched and shadowed in full); the froxel comparisons keep 96x54.
TEST_F(Mesh, CubeHullRendersLikeTheEqualBoxInTheFroxelRendererAndTheReference) {
    for (const float fade : {0.2f, 0.0f}) {
        const CubePair p = cubePair(write("cube.obj", test::cubeObj()), fade);
        ASSERT_TRUE(p.mesh.density);
        RenderRequest request;
        request.width = 96;
        request.height = 54;
        request.threads = 2;
        RenderRequest fine = request;
        fine.quality = Quality::Ultra;
        fine.shadowReduction = 1;
        const Scene withMesh = sceneWith(p.mesh), withBox = sceneWith(p.box);
        Scene skyMesh = withMesh, skyBox = withBox;
        skyMesh.lights.clear();
        skyBox.lights.clear();
        Scene noFog = withBox;
        noFog.volumes.clear();
        const double cpuErr =
            relativeMeanAbsError(renderFroxelCpu(withMesh, fine).image, renderFroxelCpu(withBox, fine).image);
        const double cpuSkyErr =
            relativeMeanAbsError(renderFroxelCpu(skyMesh, request).image, renderFroxelCpu(skyBox, request).image);
        RenderRequest reference = request;
        if (test::kAsanBuild) {
            reference.width = request.width / 2;
            reference.height = request.height / 2;
        }
        const Image refBox = renderReference(withBox, reference);
        const double refErr = relativeMeanAbsError(renderReference(withMesh, reference), refBox);
        const double fogShare = relativeMeanAbsError(renderReference(noFog, reference), refBox);
        std::printf("cube hull vs box, edge_fade_m %.1f: CPU froxel (ultra, full shadow volume) %.2e, sky only (high) "
                    "%.2e, reference (%dx%d) %.2e (the fog's share of the image %.2f)\n",
                    fade, cpuErr, cpuSkyErr, reference.width, reference.height, refErr, fogShare);
        EXPECT_LT(cpuErr, 0.01) << "fade " << fade;
        EXPECT_LT(cpuSkyErr, 0.01) << "fade " << fade;
        EXPECT_LT(refErr, 0.01) << "fade " << fade;
        EXPECT_GT(fogShare, 0.1) << "the fog barely shows: the comparison could not fail";
    }
}

// The same pair at quality high with the sun's fog shadows (issue 15: "a cube mesh renders within 1%
// of the equal box volume"). It does not hold with the default shadow volume (2.3% at edge_fade_m
// 0.2, 3.1% hard-edged), and the cause is where the vdb shadow layer is read, not the march: a box's
// shadow falls back to its exact closed form wherever the 8 cells around a froxel or surface point
// disagree (a shadow edge), the grid's layer is always their trilinear blend. In the fog that blend
// spans the reduced volume's r = 2 froxels: without the ground the hull is 1.3% (1.5%) from the box at
// r = 2 and 0.04% (0.17%) at r = 1. On the ground the blend spans a froxel at any r, which leaves 1%
// at r = 1. docs/vdb.md, "Mesh fog hulls"; the fix (an exact vdb march where the cells disagree, in
// the light pass's exact fallback and the surfaces, CPU and GPU) is not made.
TEST_F(Mesh, CubeHullAtHighWithTheSunMatchesTheBoxInTheFogWithAFullShadowVolume) {
    for (const float fade : {0.2f, 0.0f}) {
        const CubePair p = cubePair(write("cube.obj", test::cubeObj()), fade);
        ASSERT_TRUE(p.mesh.density);
        RenderRequest high;
        high.width = 96;
        high.height = 54;
        high.threads = 2;
        high.quality = Quality::High;
        RenderRequest full = high;
        full.shadowReduction = 1;
        Scene mesh = sceneWith(p.mesh), box = sceneWith(p.box);
        const double withGround = relativeMeanAbsError(renderFroxelCpu(mesh, high).image, renderFroxelCpu(box, high).image);
        mesh.geometry.clear();
        box.geometry.clear();
        const double fog = relativeMeanAbsError(renderFroxelCpu(mesh, high).image, renderFroxelCpu(box, high).image);
        const double fogFull = relativeMeanAbsError(renderFroxelCpu(mesh, full).image, renderFroxelCpu(box, full).image);
        std::printf("cube hull vs box at high with the sun, edge_fade_m %.1f: %.4f; fog alone %.4f, with a full-resolution "
                    "shadow volume %.4f\n", fade, withGround, fog, fogFull);
        EXPECT_LT(fogFull, 0.01) << "fade " << fade;
        EXPECT_LT(fog, 0.02) << "fade " << fade;         // the reduced volume's blend (1.3-1.5% measured)
        EXPECT_LT(withGround, 0.04) << "fade " << fade;  // and the ground's (2.3-3.1% measured)
    }
}

// ---- scene files and the command line ----

TEST_F(Mesh, SceneFileRoundTripsAndLoadsTheGrid) {
    write("hull.obj", test::cubeObj());
    const std::string scene = write("scene.json", R"({"brume_scene": 1, "volumes": [
        {"type": "mesh", "file": "hull.obj", "edge_fade_m": 0.25, "transform": {"translation": [0, 1, 0]},
         "medium": {"scattering": [0.5, 0.5, 0.5]}}]})");
    Result<Scene> s = loadSceneFile(scene);
    ASSERT_TRUE(s.ok()) << s.error().message;
    ASSERT_EQ(s.value().volumes.size(), 1u);
    EXPECT_EQ(s.value().volumes[0].type, VolumeType::Mesh);
    EXPECT_FLOAT_EQ(s.value().volumes[0].edge_fade_m, 0.25f);
    std::vector<std::string> warnings;
    ASSERT_TRUE(loadSceneGrids(s.value(), scene, uint64_t(1) << 30, warnings).ok());
    ASSERT_TRUE(s.value().volumes[0].density);
    const CompiledScene cs = compileScene(s.value());
    EXPECT_NEAR(volumeDensity(cs, 0, {0.0f, 1.0f, 0.0f}), 1.0f, 1e-6);
    EXPECT_EQ(volumeDensity(cs, 0, {0.0f, 2.2f, 0.0f}), 0.0f);
    Result<Scene> again = parseScene(sceneToJson(s.value()), scene);
    ASSERT_TRUE(again.ok()) << again.error().message;
    s.value().volumes[0].density = nullptr;  // the grid is made at load, never written
    EXPECT_EQ(again.value(), s.value());
}

// Hostile input through `brume render`: one line on stderr naming the scene's volume and the mesh
// file, exit code 2, for each bad mesh (docs/reliability.md).
TEST_F(Mesh, BadMeshesExitTwoFromTheCommandLine) {
    write("open.obj", test::cubeObj(1.0f, 0));
    write("nan.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    write("none.obj", "# nothing\n");
    for (const char* file : {"open.obj", "nan.obj", "none.obj", "missing.obj"}) {
        const std::string scene = write("scene.json", std::string(R"({"brume_scene": 1, "volumes": [{"type": "mesh", "file": ")") +
                                                          file + R"("}]})");
        const std::string cmd = test::quoted(BRUME_EXE) + " render " + test::quoted(scene) + " -o " +
                                test::quoted((dir_ / "out.png").string()) + " --cpu --width 32 --height 18 2>" +
                                test::quoted((dir_ / "err").string()) + " >/dev/null";
        const int status = std::system(cmd.c_str());
        const std::string err = test::readText(dir_ / "err");
        EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 2) << file << ": " << err;
        EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << file << ": " << err;
        EXPECT_NE(err.find("volumes[0].file: "), std::string::npos) << err;
        EXPECT_NE(err.find(file), std::string::npos) << err;
        EXPECT_FALSE(fs::exists(dir_ / "out.png")) << file;
    }
}

// `brume bake` bakes a hull like any volume: sigma_t inside, nothing outside.
TEST_F(Mesh, BakeWritesTheHullsSigmaT) {
    write("hull.obj", test::cubeObj());
    const std::string scene = write("scene.json", R"({"brume_scene": 1, "volumes": [{"type": "mesh", "file": "hull.obj",
        "edge_fade_m": 0.2, "medium": {"scattering": [0.5, 0.5, 0.5], "absorption": [0.25, 0.25, 0.25]}}]})");
    const std::string out = (dir_ / "baked.vdb").string();
    const std::string cmd = test::quoted(BRUME_EXE) + " bake " + test::quoted(scene) + " -o " + test::quoted(out) +
                            " --voxel-size 0.1 >/dev/null 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0);
    Result<VdbLoad> baked = loadVdbDensity(out, {});
    ASSERT_TRUE(baked.ok()) << baked.error().message;
    const DensityGrid& g = *baked.value().grid;
    const glm::mat4 indexFromWorld = glm::inverse(g.gridFromIndex());
    auto at = [&](glm::vec3 p) { return g.sampleIndex(glm::vec3(indexFromWorld * glm::vec4(p, 1.0f))); };
    EXPECT_NEAR(at({0.0f, 0.0f, 0.0f}), 0.75f, 1e-4);
    EXPECT_NEAR(at({0.5f, -0.6f, 0.3f}), 0.75f, 1e-4);
    EXPECT_EQ(at({1.5f, 0.0f, 0.0f}), 0.0f);
}

