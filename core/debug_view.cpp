#include "debug_view.h"

#include <array>
#include <cstdio>

namespace brume {

namespace {

const std::vector<glm::vec4>& debugVolume(const FroxelVolumes& v, int view) {
    if (view == shd::DEBUG_VIEW_DENSITY) return v.mediaExtinction;
    if (view == shd::DEBUG_VIEW_SCATTERING) return v.source;
    return v.integratedTransmittance;
}

constexpr std::array<const char*, 4> kNames{"final", "density", "scattering", "transmittance"};

}  // namespace

Image debugViewImage(const FroxelVolumes& v, int view, int slice) {
    const shd::FrameUniforms& f = v.frame;
    Image img(f.counts.x, f.counts.y);
    const std::vector<glm::vec4>& volume = debugVolume(v, view);
    const int s = shd::debugSliceClamped(slice, v.dims.z);
    for (int y = 0; y < img.height; ++y) {
        for (int x = 0; x < img.width; ++x) {
            const glm::ivec2 c = shd::debugFroxelColumn(glm::ivec2(x, y), f.froxelDims);
            const size_t i = (static_cast<size_t>(s) * static_cast<size_t>(v.dims.y) + static_cast<size_t>(c.y)) *
                                 static_cast<size_t>(v.dims.x) +
                             static_cast<size_t>(c.x);
            img.at(x, y) = shd::debugViewColor(volume[i], view);
        }
    }
    return img;
}

bool parseDebugView(const std::string& text, int& view) {
    for (size_t i = 0; i < kNames.size(); ++i) {
        if (text == kNames[i]) {
            view = static_cast<int>(i);
            return true;
        }
    }
    return false;
}

const char* debugViewName(int view) {
    return view >= 0 && view < static_cast<int>(kNames.size()) ? kNames[static_cast<size_t>(view)] : "?";
}

glm::vec2 debugSliceDepths(const shd::FrameUniforms& frame, int slice) {
    const int n = frame.froxelDims.z;
    const int s = shd::debugSliceClamped(slice, n);
    const glm::vec3 r(frame.froxelRange);
    const float z0 = s == 0 ? 0.0f : shd::viewDepthFromSliceT(static_cast<float>(s) / static_cast<float>(n), r.x, r.y, r.z);
    const float z1 = shd::viewDepthFromSliceT(static_cast<float>(s + 1) / static_cast<float>(n), r.x, r.y, r.z);
    return {z0, z1};
}

std::string debugViewLegend(const shd::FrameUniforms& frame, int view, int slice) {
    if (view == shd::DEBUG_VIEW_FINAL) return "final image";
    const int s = shd::debugSliceClamped(slice, frame.froxelDims.z);
    const glm::vec2 z = debugSliceDepths(frame, s);
    const glm::vec2 range = shd::debugViewRange(view);
    char buf[256];
    if (view == shd::DEBUG_VIEW_TRANSMITTANCE)
        std::snprintf(buf, sizeof buf, "transmittance, slice %d of %d (%.2f-%.2f m): grey, black 0 .. white 1", s,
                      frame.froxelDims.z, static_cast<double>(z.x), static_cast<double>(z.y));
    else
        std::snprintf(buf, sizeof buf, "%s, slice %d of %d (%.2f-%.2f m): log ramp black 0, blue %g .. white %g %s",
                      debugViewName(view), s, frame.froxelDims.z, static_cast<double>(z.x), static_cast<double>(z.y),
                      static_cast<double>(range.x), static_cast<double>(range.y),
                      view == shd::DEBUG_VIEW_DENSITY ? "1/m (sigma_t)" : "radiance/m (S)");
    return buf;
}

std::string debugViewLegend(const Scene& scene, const RenderRequest& request) {
    const CompiledScene cs = compileScene(scene);
    const FroxelSettings fs = resolveFroxelSettings(scene, request.quality);
    const shd::FrameUniforms f = makeFrameUniforms(scene, cs, request.width, request.height, fs);
    return debugViewLegend(f, request.debugView, request.debugSlice);
}

}  // namespace brume
