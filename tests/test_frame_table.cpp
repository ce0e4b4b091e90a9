// The GPU frame's tables (gpu/frame_table.h, shaders/shared/frame_table.h) against the shaders:
// every shader is compiled with glslang and its reflected descriptor bindings must be the table's
// (same binding, name and descriptor type), and every binding a pass's shader uses must be in that
// pass's reads or writes, from which the executor derives the barriers.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <map>
#include <set>
#include <new>
#include <stdexcept>
#include <string>
#include <thread>

#include "glslang_support.h"
#include "gpu/frame_table.h"
#include "gpu/pipeline.h"

using namespace brume;
using namespace brume::gpu;

namespace {

const std::string kShaders = std::string(BRUME_SOURCE_DIR) + "/shaders";

struct ReflectedBinding {
    int binding;
    std::string name;
    bool image;  // else a block (glslang lists storage blocks among the uniform blocks too: the
                 // table's block names tell uniform from storage)
};

struct ReflectedShader {
    std::string log;
    std::vector<ReflectedBinding> bindings;
};

std::string readShader(const std::string& name) {
    std::ifstream in(kShaders + "/" + name);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

EShLanguage stageOf(const std::string& name) {
    if (name.ends_with(".vert")) return EShLangVertex;
    if (name.ends_with(".frag")) return EShLangFragment;
    return EShLangCompute;
}

ReflectedShader compileShader(const std::string& name) {
    ReflectedShader out;
    glslang::InitializeProcess();
    {
        glslang::TShader shader(stageOf(name));
        glslang::TProgram program;
        out.log = test::compileAndReflect(shader, program, readShader(name),
                                          {kShaders + "/shared", kShaders, BRUME_NANOVDB_INCLUDE},
                                          EShReflectionDefault);
        if (out.log.empty()) {
            for (int i = 0; i < program.getNumUniformVariables(); ++i) {
                const glslang::TObjectReflection& u = program.getUniform(i);
                // Members of blocks carry their block's index; the rest are the storage images.
                if (u.index < 0) out.bindings.push_back({u.getBinding(), u.name, true});
            }
            // Push constant blocks have no binding (the debug view's parameters).
            for (int i = 0; i < program.getNumUniformBlocks(); ++i)
                if (program.getUniformBlock(i).getBinding() >= 0)
                    out.bindings.push_back({program.getUniformBlock(i).getBinding(), program.getUniformBlock(i).name, false});
            for (int i = 0; i < program.getNumBufferBlocks(); ++i)
                if (program.getBufferBlock(i).getBinding() >= 0)
                    out.bindings.push_back({program.getBufferBlock(i).getBinding(), program.getBufferBlock(i).name, false});
        }
    }
    glslang::FinalizeProcess();
    return out;
}

// Compiling with PNanoVDB takes a second: each file once per test run.
const ReflectedShader& reflectShader(const std::string& name) {
    static std::map<std::string, ReflectedShader> cache;
    auto it = cache.find(name);
    if (it == cache.end()) it = cache.emplace(name, compileShader(name)).first;
    return it->second;
}

// The shaders of the froxel frame: those that declare its set through resources.glsl (the editor's
// display pass, gpu/display_pass.cpp, has a set of its own).
std::vector<std::string> shaderFiles() {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(kShaders)) {
        const std::string n = e.path().filename().string();
        if (!(n.ends_with(".comp") || n.ends_with(".vert") || n.ends_with(".frag"))) continue;
        if (readShader(n).find("#include \"resources.glsl\"") != std::string::npos) names.push_back(n);
    }
    std::sort(names.begin(), names.end());
    return names;
}

// The binding(s) behind a pass's resource reference.
int bindingOf(ResRef r) {
    switch (r.kind) {
        case ResRef::Kind::Buffer: return kBuffers[r.index].binding;
        case ResRef::Kind::Image: return kImages[r.index].binding;
        case ResRef::Kind::HistoryIn: return kHistory[r.index].inBinding;
        case ResRef::Kind::HistoryOut: return kHistory[r.index].outBinding;
        case ResRef::Kind::TexelView: return kTexelViews[r.index].binding;
        case ResRef::Kind::None: break;
    }
    return -1;
}

TEST(FrameTable, BindingsAreDenseAndNamedOnce) {
    const auto table = bindingTable();
    std::set<std::string> names;
    for (size_t i = 0; i < table.size(); ++i) {
        EXPECT_EQ(table[i].binding, static_cast<int>(i)) << "binding " << i << " is missing from frame_table.h";
        if (table[i].glslName) {
            EXPECT_TRUE(names.insert(table[i].glslName).second) << table[i].glslName;
        }
    }
}

// A pass's reads or writes beyond ResList::kCapacity would be dropped, and their barriers with them.
TEST(FrameTable, EveryPassListFitsItsCapacity) {
    for (const PassDecl& p : kPasses) {
        EXPECT_FALSE(p.reads.overflow) << p.label << ": more reads than ResList::kCapacity";
        EXPECT_FALSE(p.writes.overflow) << p.label << ": more writes than ResList::kCapacity";
    }
    EXPECT_TRUE(ResList({BufferId::frame, BufferId::frame, BufferId::frame, BufferId::frame, BufferId::frame,
                         BufferId::frame, BufferId::frame, BufferId::frame, BufferId::frame, BufferId::frame,
                         BufferId::frame, BufferId::frame, BufferId::frame, BufferId::frame, BufferId::frame,
                         BufferId::frame, BufferId::frame})
                    .overflow);
}

TEST(FrameTable, EveryShaderUsesTheTablesBindings) {
    const auto table = bindingTable();
    const auto files = shaderFiles();
    ASSERT_GE(files.size(), 10u);
    for (const std::string& file : files) {
        const ReflectedShader& s = reflectShader(file);
        ASSERT_TRUE(s.log.empty()) << file << ": " << s.log;
        for (const ReflectedBinding& b : s.bindings) {
            ASSERT_GE(b.binding, 0) << file << ": " << b.name;
            ASSERT_LT(b.binding, kBindingCount) << file << ": " << b.name;
            const BindingDecl& d = table[static_cast<size_t>(b.binding)];
            EXPECT_EQ(b.name, d.glslName) << file << ": binding " << b.binding;
            EXPECT_EQ(b.image, d.image) << file << ": " << b.name;
        }
    }
}

// A pass that touched a resource its table entry does not list would get no barrier for it.
TEST(FrameTable, EveryPassListsWhatItsShaderUses) {
    // integrate_rest.comp (-DBRUME_TEMPORAL_REST) is reflected as integrate.comp: its table entry lists the
    // history images the define adds.
    const VariantKey variants[] = {{}, {false, true, VdbEncoding::Float}, {true, true, VdbEncoding::Float},
                                   {true, false, VdbEncoding::Fp16}};
    for (const PassDecl& p : kPasses) {
        std::set<std::string> sources;
        if (p.dispatch == Dispatch::Raster) {
            sources = {"geometry.vert", "geometry.frag", "geometry_sphere_depth.frag"};
        } else {
            // Variants built with -D defines (shaders/CMakeLists.txt) share their source's bindings.
            for (const VariantKey& k : variants) {
                std::string n = variantShaderName(p.shader, p.variant, k);
                for (const char* e : {"_fp16", "_fp8"})
                    if (auto at = n.find(e); at != std::string::npos) n.erase(at, std::string(e).size());
                sources.insert(n);
            }
        }
        std::set<int> listed;
        for (ResRef r : p.reads) listed.insert(bindingOf(r));
        for (ResRef r : p.writes) listed.insert(bindingOf(r));
        for (const std::string& file : sources) {
            const ReflectedShader& s = reflectShader(file);
            ASSERT_TRUE(s.log.empty()) << file << ": " << s.log;
            for (const ReflectedBinding& b : s.bindings)
                EXPECT_TRUE(listed.count(b.binding)) << "pass '" << p.label << "' (" << file << ") uses " << b.name
                                                     << " but frame_table.cpp does not list it";
        }
    }
}

// A texel view reads its buffer's memory: the executor's barriers follow memoryOf, so a pass reading
// the view waits for the pass that wrote the buffer. Views are read only, and each view's buffer is
// written by a pass before the first pass that reads the view (else the view reads nothing).
TEST(FrameTable, TexelViewsReadTheirBuffersAfterTheirWriters) {
    EXPECT_EQ(memoryOf(TexelViewId::shadowTexels), ResRef(BufferId::shadowTransmittance));
    EXPECT_EQ(memoryOf(TexelViewId::lightClusterTexels), ResRef(BufferId::lightClusters));
    EXPECT_EQ(memoryOf(TexelViewId::lightTexels), ResRef(BufferId::lights));
    EXPECT_EQ(memoryOf(TexelViewId::distantTexels), ResRef(BufferId::distantTable));
    EXPECT_EQ(memoryOf(TexelViewId::volumeTexels), ResRef(BufferId::volumes));
    EXPECT_EQ(memoryOf(BufferId::lights), ResRef(BufferId::lights));
    for (const TexelViewDecl& v : kTexelViews) {
        const ResRef view(v.id);
        bool written = hostWrites(decl(v.buffer).kind), read = false;
        for (const PassDecl& p : kPasses) {
            EXPECT_FALSE(p.writes.contains(view)) << p.label << " writes the texel view " << v.name;
            EXPECT_FALSE(p.reads.contains(ResRef(v.buffer)) && p.reads.contains(view))
                << p.label << " lists both " << v.name << " and its buffer";
            if (p.reads.contains(view)) {
                EXPECT_TRUE(written) << p.label << " reads " << v.name << " before any pass writes its buffer";
                read = true;
            }
            if (p.writes.contains(ResRef(v.buffer))) written = true;
        }
        EXPECT_TRUE(read) << v.name << " is read by no pass";
    }
}

// An indirect dispatch reads its group count from a list an earlier pass wrote: the list is an
// indirect buffer (its header reset every frame), the pass names it only with Dispatch::Indirect, and
// some pass before it writes that buffer.
TEST(FrameTable, IndirectDispatchesReadAListAnEarlierPassWrote) {
    std::set<BufferId> written;
    int indirect = 0;
    for (const PassDecl& p : kPasses) {
        EXPECT_EQ(p.dispatch == Dispatch::Indirect, p.indirect.has_value()) << p.label;
        if (p.indirect) {
            ++indirect;
            EXPECT_EQ(decl(*p.indirect).kind, BufferKind::STORAGE_INDIRECT) << p.label;
            EXPECT_TRUE(written.count(*p.indirect) > 0) << p.label << " reads " << decl(*p.indirect).name
                                                        << " before any pass writes it";
        }
        for (BufferId b : {BufferId::exactList, BufferId::nearTiles, BufferId::farTiles, BufferId::allFarTiles,
                           BufferId::skyTiles})
            if (p.writes.contains(ResRef(b))) written.insert(b);
    }
    EXPECT_EQ(indirect, 4);  // light exact, composite far, composite all far, composite sky
}

// distant_fog.comp takes each volume's kind from SPEC_VOLUME_LIST: its pipeline must get the scene's
// whole list, where every volume's kind is its own (a culled volume would lose its height or depth fog
// past the froxel far, which no froxel pass's reach covers).
TEST(FrameTable, TheDistantFogPassSeesEveryVolume) {
    int found = 0;
    for (const PassDecl& p : kPasses) {
        if (std::string(p.shader) != "distant_fog") continue;
        ++found;
        EXPECT_TRUE(p.specialized);
        EXPECT_FALSE(p.culledVolumes);
    }
    EXPECT_EQ(found, 1);
}

TEST(FrameTable, VariantNamesFollowTheBuild) {
    EXPECT_EQ(variantShaderName("voxelize", Variant::Voxelize, {}), "voxelize.comp");
    EXPECT_EQ(variantShaderName("voxelize", Variant::Voxelize, {true, true, VdbEncoding::Fp16}),
              "voxelize_vdb_texture_fp16.comp");
    EXPECT_EQ(variantShaderName("voxelize", Variant::Voxelize, {false, true, VdbEncoding::Float}), "voxelize_texture.comp");
    EXPECT_EQ(variantShaderName("shadow_volume", Variant::ShadowVolumeVdb, {true, true, VdbEncoding::Fp8}),
              "shadow_volume_vdb_fp8.comp");
    EXPECT_EQ(variantShaderName("light", Variant::None, {true, true, VdbEncoding::Fp8}), "light.comp");
    // The light passes' lookups are compiled out by specialization constants, not variants.
    EXPECT_EQ(variantShaderName("light", Variant::Shapes, {}), "light.comp");
    // Without vdb volumes the light passes and the glow compute the media themselves (_media).
    EXPECT_EQ(variantShaderName("light", Variant::LightMedia, {}), "light_media.comp");
    EXPECT_EQ(variantShaderName("light", Variant::LightMedia, {false, true, VdbEncoding::Float}),
              "light_media_texture.comp");
    EXPECT_EQ(variantShaderName("light", Variant::LightMedia, {true, true, VdbEncoding::Fp16}), "light.comp");
    EXPECT_EQ(variantShaderName("glow", Variant::GlowMedia, {false, true, VdbEncoding::Float}), "glow_media_texture.comp");
    EXPECT_EQ(variantShaderName("glow", Variant::GlowMedia, {true, false, VdbEncoding::Float}), "glow.comp");
    // The sampled fog shadows of ellipsoids and cylinders (shaders/CMakeLists.txt BRUME_SHAPES_SHADERS).
    VariantKey shaped;
    shaped.shapes = true;
    EXPECT_EQ(variantShaderName("distant_fog", Variant::Shapes, shaped), "distant_fog_shapes.comp");
    EXPECT_EQ(variantShaderName("distant_fog", Variant::Shapes, {}), "distant_fog.comp");
    EXPECT_EQ(variantShaderName("light_exact", Variant::Shapes, shaped), "light_exact_shapes.comp");
    EXPECT_EQ(variantShaderName("light_exact", Variant::LightMedia, shaped), "light_exact_media_shapes.comp");
    VariantKey vdbShaped = shaped;
    vdbShaped.vdb = true;
    vdbShaped.encoding = VdbEncoding::Fp16;
    EXPECT_EQ(variantShaderName("shadow_volume", Variant::ShadowVolumeVdb, vdbShaped), "shadow_volume_vdb_fp16_shapes.comp");
    // The shadow volume's place without vdb volumes never names the vdb variant.
    EXPECT_EQ(variantShaderName("shadow_volume", Variant::Shapes, vdbShaped), "shadow_volume_shapes.comp");
    EXPECT_EQ(variantShaderName("voxelize", Variant::Voxelize, shaped), "voxelize.comp");
    // At rest the integrate pass resolves the history (integrate_rest.comp); the temporal pass has no variant.
    VariantKey rest;
    rest.temporalRest = true;
    EXPECT_EQ(variantShaderName("integrate", Variant::Temporal, rest), "integrate_rest.comp");
    EXPECT_EQ(variantShaderName("integrate", Variant::Temporal, {}), "integrate.comp");
}

}  // namespace

// The geometry pipelines are keyed by the constants their shaders read (gpu/pipeline.h constantsReadBy):
// the froxel passes' constants, which the editor's coarse and full frames set differently, are reset,
// and the ones the geometry shaders read are kept. Each of the four geometry shaders is read.
TEST(FrameTable, GeometryKeysKeepTheConstantsTheGeometryShadersRead) {
    SpecKey key;
    for (size_t i = 0; i < key.values.size(); ++i) key.values[i] = 100 + static_cast<int32_t>(i);
    for (const auto& names : {std::pair{"geometry.frag", "geometry_sphere.frag"},
                              std::pair{"geometry_shapes.frag", "geometry_sphere_shapes.frag"}}) {
        const SpecKey kept = constantsReadBy(key, {names.first, names.second});
        const SpecKey defaults;
        for (SpecId read : {SpecId::SPEC_SURFACE_LIGHTS, SpecId::SPEC_VOLUME_LIST, SpecId::SPEC_SHAPE_LIST,
                            SpecId::SPEC_SUN_SHADOW_MAP, SpecId::SPEC_GREY_FOG_SHADOWS})
            EXPECT_EQ(kept[read], key[read]) << names.first << " constant " << static_cast<int>(read);
        for (SpecId unread : {SpecId::SPEC_SHADOW_REDUCTION, SpecId::SPEC_EMISSION, SpecId::SPEC_INFLUENCERS,
                              SpecId::SPEC_DISTANT_FOG, SpecId::SPEC_DIRECTIONAL_LIGHTS})
            EXPECT_EQ(kept[unread], defaults[unread]) << names.first << " constant " << static_cast<int>(unread);
    }
    // A shader that reads none keeps none.
    EXPECT_EQ(constantsReadBy(key, {"geometry.vert"}), SpecKey{});
}

// PipelineBatch (gpu/pipeline.h) compiles a frame's missing pipelines at once. Two jobs that each wait
// for the other to start finish only if they run at the same time; a sequential batch fails them after
// the wait's bound rather than hanging.
TEST(PipelineBatch, RunsItsJobsOnSeveralCoresAtOnce) {
    if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "one core: the batch runs its jobs in turn";
    std::atomic<int> started{0};
    auto meetTheOther = [&]() -> Result<void> {
        ++started;
        const auto bound = std::chrono::steady_clock::now() + std::chrono::seconds(20);
        while (started.load() < 2)
            if (std::chrono::steady_clock::now() > bound) return Error{"the other job did not start"};
            else std::this_thread::sleep_for(std::chrono::milliseconds(1));
        return {};
    };
    PipelineBatch batch;
    batch.add(meetTheOther, 1);
    batch.add(meetTheOther, 1);
    Result<void> r = batch.run();
    EXPECT_TRUE(r.ok()) << r.error().message;
}

// Every job runs even when some fail; the error is the first failed job's in the order added (not in
// the order run: the costliest first), and a run leaves the batch empty.
TEST(PipelineBatch, RunsEveryJobAndReportsTheFirstFailureInTheOrderAdded) {
    std::atomic<int> ran{0};
    PipelineBatch batch;
    for (int i = 0; i < 6; ++i)
        batch.add(
            [&ran, i]() -> Result<void> {
                ++ran;
                if (i == 2 || i == 4) return Error{"job " + std::to_string(i) + " failed"};
                return {};
            },
            static_cast<size_t>(i));  // job 4 runs before job 2
    EXPECT_EQ(batch.size(), 6u);
    Result<void> r = batch.run();
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message, "job 2 failed");
    EXPECT_EQ(ran.load(), 6);
    EXPECT_EQ(batch.size(), 0u);
    EXPECT_TRUE(batch.run().ok());
    EXPECT_EQ(ran.load(), 6);
}

// A job that throws (out of memory in a helper thread) is that job's error, one sentence, not the end
// of the process; the other jobs still run.
TEST(PipelineBatch, AJobThatThrowsIsItsErrorAndTheOthersRun) {
    std::atomic<int> ran{0};
    PipelineBatch batch;
    batch.add([]() -> Result<void> { throw std::runtime_error("no memory left"); }, 2);
    for (int i = 0; i < 3; ++i)
        batch.add(
            [&ran]() -> Result<void> {
                ++ran;
                return {};
            },
            1);
    Result<void> r = batch.run();
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message, "A shader pipeline could not be created: no memory left.");
    EXPECT_EQ(ran.load(), 3);
    // std::bad_alloc's what() ("std::bad_alloc") is no sentence for a user.
    batch.add([]() -> Result<void> { throw std::bad_alloc(); }, 1);
    Result<void> oom = batch.run();
    ASSERT_FALSE(oom.ok());
    EXPECT_EQ(oom.error().message, "A shader pipeline could not be created: the host is out of memory.");
}
