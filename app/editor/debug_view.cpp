#include "debug_view.h"

#include <algorithm>
#include <charconv>

#include "core/debug_view.h"
#include "core/settings.h"

namespace brume::editor {
namespace {

constexpr const char* kUsage =
    "debug takes: debug final|density|scattering|transmittance [SLICE], debug error, debug slice SLICE, debug depth "
    "METRES or debug grid on|off.";

bool sliceNumber(const std::string& s, int& out) {
    const char* end = s.data() + s.size();
    auto r = std::from_chars(s.data(), end, out);
    return r.ec == std::errc() && r.ptr == end && out >= settings::cli_debug_slice.min &&
           out <= settings::cli_debug_slice.max;
}

}  // namespace

// The slice whose depth range holds view depth z [m] (slice 0 also holds [0, near]).
int sliceAtDepth(const FroxelSettings& fs, float z) {
    const float t = shd::sliceTFromViewDepth(z, fs.near, fs.far, fs.distribution);
    return std::min(static_cast<int>(t * static_cast<float>(fs.slices)), fs.slices - 1);
}

Result<void> runDebugAction(DebugViewState& state, const Action& a, const FroxelSettings& froxels) {
    const std::vector<std::string>& w = a.args;
    if (w.empty()) return Error{kUsage};
    if (w[0] == "grid") {
        if (w.size() != 2 || (w[1] != "on" && w[1] != "off")) return Error{kUsage};
        state.grid = w[1] == "on";
        return {};
    }
    if (w[0] == "error") {
        if (w.size() != 1) return Error{kUsage};
        state.view = shd::DEBUG_VIEW_FINAL;
        state.errorMap = true;
        return {};
    }
    int slice = state.slice;
    if (w[0] == "depth") {
        double z = 0.0;
        const char* end = w.size() == 2 ? w[1].data() + w[1].size() : nullptr;
        if (w.size() != 2 || std::from_chars(w[1].data(), end, z).ptr != end || !(z >= 0.0 && z < 1e9))
            return Error{"debug depth takes a view depth in metres (0 or more)."};
        state.slice = sliceAtDepth(froxels, static_cast<float>(z));
        return {};
    }
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
    state.errorMap = false;
    return {};
}

}  // namespace brume::editor
