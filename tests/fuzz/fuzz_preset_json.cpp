// libFuzzer target: the strict preset reader (io/preset.h). Any bytes give a Preset or one sentence
// naming the file (never a crash, a hang or a sanitizer report); an accepted preset survives the
// writer (its text reads back to the same text) and applies to the default scene or says why not.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "io/preset.h"

namespace {

void requireSentence(const std::string& m, const char* file) {
    if (m.rfind(file, 0) != 0 || m.find('\n') != std::string::npos) {
        std::fprintf(stderr, "not one sentence naming the file: %s\n", m.c_str());
        std::abort();
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    const std::string dir = "/nonexistent-brume-fuzz";
    brume::Result<brume::Preset> r = brume::parsePreset(text, "fuzz.json", dir);
    if (!r) {
        requireSentence(r.error().message, "fuzz.json");
        return 0;
    }
    const std::string once = brume::presetToJson(r.value(), dir);
    brume::Result<brume::Preset> back = brume::parsePreset(once, "fuzz.json", dir);
    if (!back || brume::presetToJson(back.value(), dir) != once) {
        std::fprintf(stderr, "the writer's output does not read back to the same preset:\n%s\n", once.c_str());
        std::abort();
    }
    for (brume::PresetApply mode : {brume::PresetApply::Replace, brume::PresetApply::Add}) {
        brume::Result<brume::Scene> s = brume::applyPreset(brume::Scene{}, r.value(), mode, dir, "out.json");
        if (!s) requireSentence(s.error().message, "out.json");
    }
    return 0;
}
