// libFuzzer target: the strict scene reader (io/scene_json.h). Any bytes give a Scene or one
// sentence naming the file (never a crash, a hang or a sanitizer report), and an accepted scene
// survives the writer: parseScene(sceneToJson(s)) == s.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "io/scene_json.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    brume::Result<brume::Scene> r = brume::parseScene(text, "fuzz.json");
    if (!r) {
        const std::string& m = r.error().message;
        if (m.rfind("fuzz.json", 0) != 0 || m.find('\n') != std::string::npos) {
            std::fprintf(stderr, "not one sentence naming the file: %s\n", m.c_str());
            std::abort();
        }
        return 0;
    }
    const std::string again = brume::sceneToJson(r.value());
    brume::Result<brume::Scene> back = brume::parseScene(again, "fuzz.json");
    if (!back || !(back.value() == r.value())) {
        std::fprintf(stderr, "the writer's output does not read back to the same scene:\n%s\n", again.c_str());
        std::abort();
    }
    return 0;
}
