// libFuzzer target: the editor's action-script parser (app/editor/document.h). Each input line is
// parsed; an accepted action formats back to a line that parses to the same action, and document
// actions (other than those that touch files) apply or fail with a sentence, leaving a scene the
// strict reader still accepts. That is checked once per input (writing and reading the scene is
// most of a run's time); when it fails, the input is replayed checking after every action, so
// that the report names the line that broke the scene.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "app/editor/document.h"
#include "io/scene_json.h"

namespace {

bool touchesFiles(const brume::editor::Action& a) {
    return a.verb == "save" || (a.verb == "add" && !a.args.empty() && a.args.size() >= 2 && a.args[1] == "vdb");
}

bool readsBack(const brume::editor::Document& doc) {
    return brume::parseScene(brume::sceneToJson(doc.scene()), "fuzz.json").ok();
}

// The first of these actions after which the scene no longer reads back: replayed on a new document.
[[noreturn]] void reportBrokenScene(const std::vector<std::pair<std::string, brume::editor::Action>>& applied) {
    brume::editor::Document doc;
    for (const auto& [line, a] : applied) {
        (void)doc.apply(a);
        if (!readsBack(doc)) {
            std::fprintf(stderr, "after [%s] the scene no longer reads back\n", line.c_str());
            std::abort();
        }
    }
    std::fprintf(stderr, "the scene no longer reads back after %zu actions (not when replayed one by one)\n",
                 applied.size());
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace brume::editor;
    std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
    Document doc;
    std::string line;
    std::vector<std::pair<std::string, Action>> applied;
    while (std::getline(in, line)) {
        brume::Result<Action> r = parseAction(line);
        if (!r) continue;
        const Action& a = r.value();
        brume::Result<Action> back = parseAction(formatAction(a));
        if (!back || back.value().verb != a.verb || back.value().args != a.args) {
            std::fprintf(stderr, "formatAction does not read back: [%s] -> [%s]\n", line.c_str(), formatAction(a).c_str());
            std::abort();
        }
        if (a.verb.empty() || !Document::isDocumentVerb(a.verb) || touchesFiles(a) || applied.size() >= 64) continue;
        (void)doc.apply(a);
        applied.emplace_back(line, a);
    }
    if (!applied.empty() && !readsBack(doc)) reportBrokenScene(applied);
    return 0;
}
