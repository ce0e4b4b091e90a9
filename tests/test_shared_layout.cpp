// The structs in shaders/shared/ cross the CPU/GPU boundary as raw bytes: their C++ (glm) layout
// must equal the GLSL std140 (uniform) and std430 (storage) layouts. glslang compiles a shader
// that declares every struct in both layouts and its reflection reports each member's offset,
// which must equal offsetof on the C++ side; block sizes (and so array strides) must equal sizeof.
#include <gtest/gtest.h>

#include <cstddef>
#include <map>
#include <string>

#include "glslang_support.h"

#include "shaders/shared/bindings.h"
#include "shaders/shared/frame_table.h"
#include "shaders/shared/brume.h"

using namespace brume;

namespace {

constexpr const char* kShader = R"(#version 450
#extension GL_GOOGLE_include_directive : require
#include "brume.h"
#include "bindings.h"
layout(std140, binding = 0) uniform F140 { FrameUniforms f140; };
layout(std140, binding = 1) uniform V140 { VolumeData v140; };
layout(std140, binding = 2) uniform L140 { LightData l140; };
layout(std430, binding = 3) buffer F430 { FrameUniforms f430; };
layout(std430, binding = 4) buffer V430 { VolumeData v430[2]; };
layout(std430, binding = 5) buffer L430 { LightData l430[2]; };
layout(std430, binding = 6) buffer C430 { FroxelCounters c430; };
layout(std430, binding = 7) buffer S430 { SunShadowFit s430; float sDepth[]; };
layout(local_size_x = 1) in;
// Every block must be live to be reflected; EShReflectionAllBlockVariables then lists all members.
void main() {
    c430.litFroxels = uint(f140.counts.x + v140.kind.x + l140.kind.x + f430.counts.x + v430[0].kind.x + l430[0].kind.x +
                          int(s430.dir.x + sDepth[0]));
}
)";

struct Reflected {
    std::map<std::string, int> offsets;  // member name -> byte offset
    std::map<std::string, int> blockSizes;
    std::string log;
};

Reflected reflect() {
    Reflected out;
    glslang::InitializeProcess();
    {
        glslang::TShader shader(EShLangCompute);
        glslang::TProgram program;
        out.log = test::compileAndReflect(shader, program, kShader, {std::string(BRUME_SOURCE_DIR) + "/shaders/shared"},
                                          EShReflectionAllBlockVariables);
        if (out.log.empty()) {
            for (int i = 0; i < program.getNumUniformVariables(); ++i)
                out.offsets[program.getUniform(i).name] = program.getUniform(i).offset;
            for (int i = 0; i < program.getNumBufferVariables(); ++i) {
                out.offsets[program.getBufferVariable(i).name] = program.getBufferVariable(i).offset;
            }
            for (int i = 0; i < program.getNumUniformBlocks(); ++i)
                out.blockSizes[program.getUniformBlock(i).name] = program.getUniformBlock(i).size;
            for (int i = 0; i < program.getNumBufferBlocks(); ++i)
                out.blockSizes[program.getBufferBlock(i).name] = program.getBufferBlock(i).size;
        }
    }
    glslang::FinalizeProcess();
    return out;
}

const Reflected& reflected() {
    static const Reflected r = reflect();
    return r;
}

// Offset of `member` inside `prefix` ("f140." or "v430[0]."), or -1 (with the names seen).
int offsetOf(const std::string& prefix, const std::string& member) {
    const auto& m = reflected().offsets;
    const auto it = m.find(prefix + member);
    return it == m.end() ? -1 : it->second;
}

std::string seenNames() {
    std::string s;
    for (const auto& [name, offset] : reflected().offsets) s += name + "@" + std::to_string(offset) + " ";
    return s;
}

#define EXPECT_MEMBER(prefix, Struct, member) \
    EXPECT_EQ(offsetOf(prefix, #member), static_cast<int>(offsetof(shd::Struct, member))) << prefix << #member << "; seen: " << seenNames()

void expectFrameUniforms(const std::string& p) {
    EXPECT_MEMBER(p, FrameUniforms, viewFromWorld);
    EXPECT_MEMBER(p, FrameUniforms, worldFromView);
    EXPECT_MEMBER(p, FrameUniforms, clipFromView);
    EXPECT_MEMBER(p, FrameUniforms, clipFromWorld);
    EXPECT_MEMBER(p, FrameUniforms, cameraPosition);
    EXPECT_MEMBER(p, FrameUniforms, ambient);
    EXPECT_MEMBER(p, FrameUniforms, projection);
    EXPECT_MEMBER(p, FrameUniforms, froxelRange);
    EXPECT_MEMBER(p, FrameUniforms, froxelDims);
    EXPECT_MEMBER(p, FrameUniforms, counts);
    EXPECT_MEMBER(p, FrameUniforms, jitter);
    EXPECT_MEMBER(p, FrameUniforms, localFogShadows);
    EXPECT_MEMBER(p, FrameUniforms, shadowReduction);
    EXPECT_MEMBER(p, FrameUniforms, sunShadowLight);
    EXPECT_MEMBER(p, FrameUniforms, localShadowTexels);
    EXPECT_MEMBER(p, FrameUniforms, vdbShadowSamples);
    EXPECT_MEMBER(p, FrameUniforms, temporal);
}

void expectVolumeData(const std::string& p) {
    EXPECT_MEMBER(p, VolumeData, localFromWorld);
    EXPECT_MEMBER(p, VolumeData, sigmaS_g);
    EXPECT_MEMBER(p, VolumeData, sigmaA);
    EXPECT_MEMBER(p, VolumeData, emission);
    EXPECT_MEMBER(p, VolumeData, params);
    EXPECT_MEMBER(p, VolumeData, kind);
    EXPECT_MEMBER(p, VolumeData, worldMin);
    EXPECT_MEMBER(p, VolumeData, worldMax);
    EXPECT_MEMBER(p, VolumeData, textureParams);
    EXPECT_MEMBER(p, VolumeData, textureScroll);
    EXPECT_MEMBER(p, VolumeData, textureMin);
    EXPECT_MEMBER(p, VolumeData, textureSize);
    EXPECT_MEMBER(p, VolumeData, detailParams);
    EXPECT_MEMBER(p, VolumeData, detailScroll);
    EXPECT_MEMBER(p, VolumeData, detailMin);
    EXPECT_MEMBER(p, VolumeData, detailSize);
}

void expectLightData(const std::string& p) {
    EXPECT_MEMBER(p, LightData, positionRange);
    EXPECT_MEMBER(p, LightData, direction);
    EXPECT_MEMBER(p, LightData, intensity);
    EXPECT_MEMBER(p, LightData, fogScale);
    EXPECT_MEMBER(p, LightData, spot);
    EXPECT_MEMBER(p, LightData, kind);
}

TEST(SharedLayout, GlslCompilesWithTheSharedHeaders) { EXPECT_TRUE(reflected().log.empty()) << reflected().log; }

TEST(SharedLayout, FrameUniformsStd140AndStd430MatchCpp) {
    expectFrameUniforms("f140.");
    expectFrameUniforms("f430.");
    EXPECT_EQ(reflected().blockSizes.at("F140"), static_cast<int>(sizeof(shd::FrameUniforms)));
    EXPECT_EQ(reflected().blockSizes.at("F430"), static_cast<int>(sizeof(shd::FrameUniforms)));
}

TEST(SharedLayout, VolumeDataStd140AndStd430MatchCpp) {
    expectVolumeData("v140.");
    expectVolumeData("v430[0].");
    EXPECT_EQ(reflected().blockSizes.at("V140"), static_cast<int>(sizeof(shd::VolumeData)));
    // Two elements: the block size is twice the array stride.
    EXPECT_EQ(reflected().blockSizes.at("V430"), static_cast<int>(2 * sizeof(shd::VolumeData)));
}

TEST(SharedLayout, LightDataStd140AndStd430MatchCpp) {
    expectLightData("l140.");
    expectLightData("l430[0].");
    EXPECT_EQ(reflected().blockSizes.at("L140"), static_cast<int>(sizeof(shd::LightData)));
    EXPECT_EQ(reflected().blockSizes.at("L430"), static_cast<int>(2 * sizeof(shd::LightData)));
}

// The light passes read lights[] as rgba32i texels (resources.glsl lightAt): LIGHT_DATA_TEXELS per
// light, each member inside the texel lightAt takes it from, at the component it takes.
TEST(SharedLayout, LightDataTexelsMatchLightAt) {
    EXPECT_EQ(sizeof(shd::LightData), 16u * static_cast<size_t>(shd::LIGHT_DATA_TEXELS));
    EXPECT_EQ(offsetof(shd::LightData, positionRange), 0u);
    EXPECT_EQ(offsetof(shd::LightData, direction), 16u);
    EXPECT_EQ(offsetof(shd::LightData, intensity), 32u);
    EXPECT_EQ(offsetof(shd::LightData, fogScale), 44u);
    EXPECT_EQ(offsetof(shd::LightData, spot), 48u);
    EXPECT_EQ(offsetof(shd::LightData, kind), 64u);
}

// Passes that define BRUME_VOLUME_TEXELS read volumes[] as rgba32i texels (resources.glsl volumeAt):
// VOLUME_DATA_TEXELS per volume, each member at the texel volumeAt takes it from (the matrix's columns
// in texels 0..3, each a whole texel).
TEST(SharedLayout, VolumeDataTexelsMatchVolumeAt) {
    EXPECT_EQ(sizeof(shd::VolumeData), 16u * static_cast<size_t>(shd::VOLUME_DATA_TEXELS));
    EXPECT_EQ(offsetof(shd::VolumeData, localFromWorld), 0u);
    EXPECT_EQ(sizeof(shd::VolumeData::localFromWorld), 64u);
    EXPECT_EQ(offsetof(shd::VolumeData, sigmaS_g), 4u * 16u);
    EXPECT_EQ(offsetof(shd::VolumeData, sigmaA), 5u * 16u);
    EXPECT_EQ(offsetof(shd::VolumeData, emission), 6u * 16u);
    EXPECT_EQ(offsetof(shd::VolumeData, params), 7u * 16u);
    EXPECT_EQ(offsetof(shd::VolumeData, kind), 8u * 16u);
    EXPECT_EQ(offsetof(shd::VolumeData, worldMin), 9u * 16u);
    EXPECT_EQ(offsetof(shd::VolumeData, worldMax), 10u * 16u);
    EXPECT_EQ(offsetof(shd::VolumeData, textureParams), 11u * 16u);
    EXPECT_EQ(offsetof(shd::VolumeData, textureScroll), 12u * 16u);
    EXPECT_EQ(offsetof(shd::VolumeData, textureMin), 13u * 16u);
    EXPECT_EQ(offsetof(shd::VolumeData, textureSize), 14u * 16u);
    EXPECT_EQ(offsetof(shd::VolumeData, detailParams), 15u * 16u);
    EXPECT_EQ(offsetof(shd::VolumeData, detailScroll), 16u * 16u);
    EXPECT_EQ(offsetof(shd::VolumeData, detailMin), 17u * 16u);
    EXPECT_EQ(offsetof(shd::VolumeData, detailSize), 18u * 16u);
}

TEST(SharedLayout, FroxelCountersStd430MatchCpp) {
    EXPECT_MEMBER("c430.", FroxelCounters, litFroxels);
    EXPECT_EQ(reflected().blockSizes.at("C430"), static_cast<int>(sizeof(shd::FroxelCounters)));
}

// The sun shadow map's header, then its depths right after it (resources.glsl SunShadowBlock,
// the host's upload in gpu_renderer.cpp).
TEST(SharedLayout, SunShadowFitStd430MatchesCpp) {
    EXPECT_MEMBER("s430.", SunShadowFit, centerRadius);
    EXPECT_MEMBER("s430.", SunShadowFit, right);
    EXPECT_MEMBER("s430.", SunShadowFit, up);
    EXPECT_MEMBER("s430.", SunShadowFit, dir);
    const auto& offsets = reflected().offsets;
    auto depth = offsets.find("sDepth");
    if (depth == offsets.end()) depth = offsets.find("sDepth[0]");
    ASSERT_NE(depth, offsets.end()) << seenNames();
    EXPECT_EQ(depth->second, static_cast<int>(sizeof(shd::SunShadowFit)));
}

// The sizes the header comments promise (and that the GPU buffers are sized with).
TEST(SharedLayout, SizesAreTheDocumentedOnes) {
    EXPECT_EQ(sizeof(shd::VolumeData), 304u);
    EXPECT_EQ(sizeof(shd::LightData), 80u);
    EXPECT_EQ(sizeof(shd::FrameUniforms), 416u);
}

}  // namespace
