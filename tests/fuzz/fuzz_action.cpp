// libFuzzer target: the editor's action-script parser (app/editor/document.h). Each input line is
// parsed; an accepted action formats back to a line that parses to the same action, and document
// actions (other than those that touch files) apply or fail with a sentence, leaving a scene the
// strict reader still accepts.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

#include "app/editor/document.h"
#include "io/scene_json.h"

namespace {

bool touchesFiles(const brume::editor::Action& a) {
    return a.verb == "save" || (a.verb == "add" && !a.args.empty() && a.args.size() >= 2 && a.args[1] == "vdb");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace brume::editor;
    std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
    Document doc;
    std::string line;
    int applied = 0;
    while (std::getline(in, line)) {
        brume::Result<Action> r = parseAction(line);
        if (!r) continue;
        const Action& a = r.value();
        brume::Result<Action> back = parseAction(formatAction(a));
        if (!back || back.value().verb != a.verb || back.value().args != a.args) {
            std::fprintf(stderr, "formatAction does not read back: [%s] -> [%s]\n", line.c_str(), formatAction(a).c_str());
            std::abort();
        }
        if (a.verb.empty() || !Document::isDocumentVerb(a.verb) || touchesFiles(a) || ++applied > 64) continue;
        (void)doc.apply(a);
        if (!brume::parseScene(brume::sceneToJson(doc.scene()), "fuzz.json")) {
            std::fprintf(stderr, "after [%s] the scene no longer reads back\n", line.c_str());
            std::abort();
        }
    }
    return 0;
}
