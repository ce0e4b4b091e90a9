// Mutated scene files, as a new user (or a bad disk) makes them (issue 17): from the committed scene
// seeds, each mutant deletes a key, gives a value the wrong type, puts a huge, tiny or negative
// number in a value, or flips bytes of the text. Deterministic for a seed. Used by the editor's tests:
// the editor must never crash on a file the command line refuses (docs/reliability.md).
#pragma once

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "test_support.h"

namespace brume::test {

// The committed scene seeds: the fuzzing corpus and the example scenes without external files.
inline std::vector<std::filesystem::path> sceneSeeds() {
    std::vector<std::filesystem::path> seeds;
    for (const char* dir : {"/tests/fuzz/corpus/scene_json", "/assets/scenes"}) {
        for (const auto& e : std::filesystem::directory_iterator(std::string(BRUME_SOURCE_DIR) + dir))
            // Scenes naming grid or mesh files are left out: their relative paths would not hold in
            // the mutants' folder, and an unreadable grid is a warning in the editor, an error in
            // `brume validate` (io/scene_json.h openSceneFile; the VDB reader has its own fuzzing).
            if (e.path().extension() == ".json" && readText(e.path()).find("\"file\"") == std::string::npos)
                seeds.push_back(e.path());
    }
    std::sort(seeds.begin(), seeds.end());
    return seeds;
}

namespace detail {

// Every value's JSON pointer in `j` (objects' keys and arrays' items, depth first).
inline void pointers(const nlohmann::json& j, const nlohmann::json::json_pointer& at,
                     std::vector<nlohmann::json::json_pointer>& out) {
    if (j.is_object()) {
        for (auto it = j.begin(); it != j.end(); ++it) {
            out.push_back(at / it.key());
            pointers(it.value(), at / it.key(), out);
        }
    } else if (j.is_array()) {
        for (size_t i = 0; i < j.size(); ++i) {
            out.push_back(at / i);
            pointers(j[i], at / i, out);
        }
    }
}

}  // namespace detail

// `count` mutants written as dir/mutant_N.json; returns their paths.
inline std::vector<std::filesystem::path> writeMutatedScenes(const std::filesystem::path& dir, int count, uint32_t seed) {
    const std::vector<std::filesystem::path> seeds = sceneSeeds();
    std::mt19937 rng(seed);
    auto pick = [&](size_t n) { return static_cast<size_t>(std::uniform_int_distribution<size_t>(0, n - 1)(rng)); };
    const std::vector<nlohmann::json> wrongValues = {
        "text", nlohmann::json::array(), nlohmann::json::object(), true, nullptr, 1e308, -1e308, 1e39, -1.0,
        0.0, 1e-45, 4294967296.0, -2147483649.0, nlohmann::json::array({1e30, -1e30, 1e30}), "nan", "\xff\xfe"};
    std::vector<std::filesystem::path> out;
    for (int n = 0; n < count; ++n) {
        const std::string text = readText(seeds[pick(seeds.size())]);
        std::string mutated = text;
        const int kind = n % 4;
        nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
        std::vector<nlohmann::json::json_pointer> at;
        if (!j.is_discarded()) detail::pointers(j, nlohmann::json::json_pointer(), at);
        if (kind < 3 && !at.empty()) {
            const nlohmann::json::json_pointer p = at[pick(at.size())];
            if (kind == 0) {
                nlohmann::json& parent = j[p.parent_pointer()];
                if (parent.is_object()) parent.erase(p.back());
                else parent.erase(static_cast<size_t>(std::stoul(p.back())));
            } else if (kind == 1) {
                j[p] = wrongValues[pick(wrongValues.size())];
            } else {
                // A number anywhere it can go: huge, tiny, negative, integral overflow.
                const double numbers[] = {1e30, -1e30, 3.4e38, 1e-30, -1.0, 0.0, 1e9, 65536.0, 2147483648.0};
                j[p] = numbers[pick(std::size(numbers))];
            }
            mutated = j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
        } else {
            // Flipped bytes of the text (1 to 8 of them).
            const size_t flips = 1 + pick(8);
            for (size_t k = 0; k < flips && !mutated.empty(); ++k)
                mutated[pick(mutated.size())] ^= static_cast<char>(1 << pick(8));
        }
        const std::filesystem::path path = dir / ("mutant_" + std::to_string(n) + ".json");
        std::ofstream(path, std::ios::binary) << mutated;
        out.push_back(path);
    }
    return out;
}

}  // namespace brume::test
