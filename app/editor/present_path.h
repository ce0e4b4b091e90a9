// How a window frame puts the renderer's output on screen (app/editor/presenter.cpp): the choice
// alone, without Vulkan, so it is tested without a window (tests/test_editor_actions.cpp).
#pragma once

#include <glm/glm.hpp>

namespace brume::editor {

enum class PresentPath {
    Background,  // nothing rendered yet: the window is the background grey
    Window,      // the display pass over every window pixel (bilinear when the sizes differ), copied in
    Upscale,     // the display pass at the source's size, then a linear blit of its bytes to the view
};

// A frame whose output has the view's size (every frame at rest) takes the Window path, so its bytes
// are the PNG's. A smaller one (a coarse frame while interacting) is tone mapped at its own size and
// scaled up as display values by the device's blit, when the window's format can be blitted with
// linear filtering (`canBlit`); else the display pass scales it per window pixel.
inline PresentPath choosePresentPath(bool haveSource, glm::ivec2 sourceSize, glm::ivec2 viewSize, bool canBlit) {
    if (!haveSource) return PresentPath::Background;
    if (sourceSize == viewSize || !canBlit) return PresentPath::Window;
    return PresentPath::Upscale;
}

}  // namespace brume::editor
