// Every resource of the froxel renderer's single descriptor set, expanded from the tables of
// shared/frame_table.h (the C++ side expands the same tables in gpu/frame_table.h). Passes use a
// subset; spirv-opt drops the rest. imageLoad needs the format qualifiers, and only compute stages
// see the images (devices may allow as few as 4 storage images per graphics stage).
#include "brume.h"
#include "bindings.h"
#include "frame_table.h"

#define BRUME_GLSL_BUFFER(id, binding_, kind, layout_, qualifiers, block, body) \
    layout(layout_, set = 0, binding = binding_) qualifiers block { body };
BRUME_FRAME_BUFFERS(BRUME_GLSL_BUFFER)
// The format is the view's (C++), not the shader's: texelFetch returns vec4 whatever it is.
#define BRUME_GLSL_TEXEL_VIEW(id, binding_, buffer, format) layout(set = 0, binding = binding_) uniform samplerBuffer id;
BRUME_FRAME_TEXEL_VIEWS(BRUME_GLSL_TEXEL_VIEW)

#ifdef BRUME_FROXEL_IMAGES
#define BRUME_GLSL_IMAGE(id, binding_, format, type, flags) \
    layout(set = 0, binding = binding_, format) uniform type id;
BRUME_FRAME_IMAGES(BRUME_GLSL_IMAGE)
#define BRUME_GLSL_HISTORY(id, inName, inBinding, outName, outBinding, format, type) \
    layout(set = 0, binding = inBinding, format) uniform type inName; \
    layout(set = 0, binding = outBinding, format) uniform type outName;
BRUME_FRAME_HISTORY(BRUME_GLSL_HISTORY)
#endif
