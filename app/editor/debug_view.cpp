#include "debug_view.h"

#include <charconv>

#include "core/debug_view.h"
#include "core/settings.h"

namespace brume::editor {
namespace {

constexpr const char* kUsage =
    "debug takes: debug final|density|scattering|transmittance [SLICE], debug slice SLICE or debug grid on|off.";

bool sliceNumber(const std::string& s, int& out) {
    const char* end = s.data() + s.size();
    auto r = std::from_chars(s.data(), end, out);
    return r.ec == std::errc() && r.ptr == end && out >= settings::cli_debug_slice.min &&
           out <= settings::cli_debug_slice.max;
}

}  // namespace

Result<void> runDebugAction(DebugViewState& state, const Action& a) {
    const std::vector<std::string>& w = a.args;
    if (w.empty()) return Error{kUsage};
    if (w[0] == "grid") {
        if (w.size() != 2 || (w[1] != "on" && w[1] != "off")) return Error{kUsage};
        state.grid = w[1] == "on";
        return {};
    }
    int slice = state.slice;
    if (w[0] == "slice") {
        if (w.size() != 2) return Error{kUsage};
        if (!sliceNumber(w[1], slice)) return Error{"debug slice: \"" + w[1] + "\" is not a slice in [0, 4095]."};
        state.slice = slice;
        return {};
    }
    int view = 0;
    if (!parseDebugView(w[0], view) || w.size() > 2) return Error{kUsage};
    if (w.size() == 2 && !sliceNumber(w[1], slice))
        return Error{"debug: \"" + w[1] + "\" is not a slice in [0, 4095]."};
    state.view = view;
    state.slice = slice;
    return {};
}

}  // namespace brume::editor
