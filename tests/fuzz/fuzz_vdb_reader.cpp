// libFuzzer target: VDB reading through its real entry points (io/vdb_import.h: inspectVdb and
// loadVdbDensity), which spawn the isolated reader brume-vdb-read on the file. Whatever the bytes,
// Brume gets a grid or one sentence naming the file; the reader may die (OpenVDB crashes on some
// corrupt files: that is why it runs apart), Brume may not. Slow per run (a process per read).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <unistd.h>

#include "io/vdb_import.h"

namespace {

void expectSentence(const brume::Error& e, const std::string& file) {
    if (e.message.rfind(file, 0) != 0 || e.message.find('\n') != std::string::npos) {
        std::fprintf(stderr, "not one sentence naming the file: %s\n", e.message.c_str());
        std::abort();
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const std::string file = "/tmp/brume-fuzz-" + std::to_string(getpid()) + ".vdb";
    FILE* f = std::fopen(file.c_str(), "wb");
    if (!f) return 0;
    std::fwrite(data, 1, size, f);
    std::fclose(f);
    brume::VdbImportOptions options;
    options.memoryLimitBytes = uint64_t(64) << 20;
    options.timeoutSeconds = 20.0;
    auto info = brume::inspectVdb(file, options);
    if (!info) expectSentence(info.error(), file);
    auto load = brume::loadVdbDensity(file, options);
    if (!load) expectSentence(load.error(), file);
    else if (!load.value().grid) std::abort();
    return 0;
}
