// glslang's C++ API for the tests that reflect GLSL: an includer that resolves #include "x" from a
// list of folders, like glslangValidator -I in the build, and a compile-and-reflect helper.
#pragma once

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace brume::test {

class FolderIncluder : public glslang::TShader::Includer {
public:
    explicit FolderIncluder(std::vector<std::string> folders) : folders_(std::move(folders)) {}
    IncludeResult* includeLocal(const char* name, const char*, size_t) override {
        for (const std::string& folder : folders_) {
            std::ifstream in(folder + "/" + name);
            if (!in) continue;
            std::stringstream ss;
            ss << in.rdbuf();
            auto* text = new std::string(ss.str());
            return new IncludeResult(name, text->data(), text->size(), text);
        }
        return nullptr;
    }
    IncludeResult* includeSystem(const char* name, const char* from, size_t depth) override {
        return includeLocal(name, from, depth);
    }
    void releaseInclude(IncludeResult* r) override {
        if (!r) return;
        delete static_cast<std::string*>(r->userData);
        delete r;
    }

private:
    std::vector<std::string> folders_;
};

// Compiles `source` as a Vulkan GLSL shader of `stage` and builds its reflection into `program`;
// returns the info log ("" on success). `preamble`: extra lines after #version (e.g. "#define X\n").
inline std::string compileAndReflect(glslang::TShader& shader, glslang::TProgram& program, const std::string& source,
                                     const std::vector<std::string>& includeFolders, int reflectionOptions,
                                     const std::string& preamble = "") {
    const char* text = source.c_str();
    shader.setStrings(&text, 1);
    if (!preamble.empty()) shader.setPreamble(preamble.c_str());
    const EShLanguage stage = shader.getStage();
    shader.setEnvInput(glslang::EShSourceGlsl, stage, glslang::EShClientVulkan, 100);
    shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_1);
    shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_3);
    FolderIncluder includer(includeFolders);
    if (!shader.parse(GetDefaultResources(), 450, false, EShMsgDefault, includer)) return shader.getInfoLog();
    program.addShader(&shader);
    if (!program.link(EShMsgDefault)) return program.getInfoLog();
    if (!program.buildReflection(reflectionOptions)) return "reflection failed";
    return "";
}

}  // namespace brume::test
