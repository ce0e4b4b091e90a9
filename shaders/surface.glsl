#include "surface_corners.h"

// A surface pixel as the geometry pass left it in the G-buffer (geometry.frag): its point, normal and
// the shadow rays' origin, as core/geometry.cpp shadeSurface derives them from a ray hit.
struct SurfacePoint {
    float viewDepth;
    vec3 worldPos;
    vec3 normal;  // faces the camera
    vec3 origin;  // worldPos off the surface (surfaceRayOffset)
};

SurfacePoint surfacePointAt(ivec2 px) {
    vec4 dn = imageLoad(sceneDepth, px);
    SurfacePoint s;
    s.viewDepth = dn.x;
    s.normal = dn.yzw;
    // The pixel centre's ray (z = -1 in view space) to the view depth.
    vec3 viewRay = viewRayFromPixel(vec2(px) + vec2(0.5f), frame);
    s.worldPos = frame.cameraPosition.xyz + vec3(frame.worldFromView * vec4(viewRay * s.viewDepth, 0.0f));
    vec3 m = abs(s.worldPos);
    s.origin = s.worldPos + s.normal * (1.0e-4f + 2.0e-6f * max(m.x, max(m.y, m.z)));
    return s;
}
