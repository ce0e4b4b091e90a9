// SPIR-V of shaders/*.comp|vert|frag, compiled and optimized at build time and embedded by
// shaders/embed_spirv.cmake (brume_spirv), so binaries need no shader files at run time.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

namespace brume::gpu {

// name: the source file name, e.g. "voxelize.comp"; empty when there is no such shader.
std::span<const std::uint32_t> embeddedSpirv(std::string_view name);

}  // namespace brume::gpu
