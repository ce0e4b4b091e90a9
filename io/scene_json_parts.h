// The scene reader's and writer's pieces that other file formats built on scenes share (presets:
// io/preset.h), so that a volume or a light is read by one reader, with the same settings metadata
// and the same error sentences, whatever file it sits in. Implemented in io/scene_json.cpp.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "core/result.h"
#include "core/scene.h"

namespace brume::scene_json {

// Strict JSON parse: a syntax error names the line and column, a duplicate key its JSON path;
// errors read "FILE: WHERE: what is wrong".
Result<nlohmann::json> parseStrictJson(std::string_view text, const std::string& file);

// `value` is the array at JSON path `path` ("lights", "volumes"); every element is read by the
// scene reader (same keys, ranges and messages). readVolumes also checks the one-encoding rule.
Result<std::vector<Light>> readLights(const nlohmann::json& value, const std::string& file, const std::string& path);
Result<std::vector<Volume>> readVolumes(const nlohmann::json& value, const std::string& file, const std::string& path);

// The "ambient" key of `object` (the scene's ambient setting); `fallback` when absent.
Result<glm::vec3> readAmbient(const nlohmann::json& object, const std::string& file, glm::vec3 fallback);

// True when the object's keys are all in `allowed`; else the scene reader's unknown-key sentence.
Result<void> checkKeys(const nlohmann::json& object, const std::string& file, const std::string& path,
                       const std::vector<std::string>& allowed, const std::string& where);

// The scene writer's JSON of each piece (same key order and float digits).
nlohmann::ordered_json lightToJson(const Light& light);
nlohmann::ordered_json volumeToJson(const Volume& volume);
nlohmann::ordered_json vec3ToJson(glm::vec3 v);

// The scene writer's layout (two-space indent, vec3s on one line), with a final newline.
std::string prettyJson(const nlohmann::ordered_json& j);

// The whole file as text; "PATH: cannot read: REASON" otherwise.
Result<std::string> readTextFile(const std::string& path);

}  // namespace brume::scene_json
