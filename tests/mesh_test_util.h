// Meshes for the mesh-volume tests, written as OBJ text.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

namespace brume::test {

// The cube [-h, h]^3 as six quads (fan-triangulated by the reader), faces wound outward; `dropFace`
// (0-5) leaves one face out: a mesh with a square hole.
inline std::string cubeObj(float h = 1.0f, int dropFace = -1) {
    std::string s = "# cube\no cube\n";
    for (int i = 0; i < 8; ++i)
        s += "v " + std::to_string((i & 1) ? h : -h) + " " + std::to_string((i & 2) ? h : -h) + " " +
             std::to_string((i & 4) ? h : -h) + "\n";
    const char* faces[6] = {"f 1 3 4 2", "f 5 6 8 7", "f 1 2 6 5", "f 3 7 8 4", "f 1 5 7 3", "f 2 4 8 6"};
    for (int f = 0; f < 6; ++f)
        if (f != dropFace) s += std::string(faces[f]) + "\n";
    return s;
}

inline void writeText(const std::filesystem::path& p, const std::string& text) {
    std::filesystem::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
}

}  // namespace brume::test
