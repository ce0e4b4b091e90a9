// The sphere proxies' per-pixel ray cast (gpu/geometry_mesh.h): the CPU's ray query through this
// pixel's centre (core/froxel_renderer.cpp compositeRow, core/geometry.cpp GeometrySet::intersect),
// so the sphere's silhouette, position and normal are the CPU's, not a tessellation's.
// Included by geometry_sphere_depth.frag (the depth pre-pass) and geometry.frag built with
// BRUME_SPHERE (shading, depth test EQUAL): both must write the same depth, so every value on its way
// is `precise` (no contraction or reassociation that could differ between the two programs).
#ifndef BRUME_SPHERE_RAY_GLSL
#define BRUME_SPHERE_RAY_GLSL

struct SphereRayHit {
    bool hit;
    vec3 position;   // world [m]
    vec3 normal;     // world, unit, facing the camera
    float viewDepth; // [m]
    float depth;     // the depth attachment's value, in [0, 1]
};

SphereRayHit sphereRayHit(vec3 center, float radius) {
    SphereRayHit h;
    // viewRay has z = -1, so distance along it / its length is the view depth (as compositeRow).
    precise vec3 viewRay = viewRayFromPixel(gl_FragCoord.xy, frame);
    precise float rayPerDepth = length(viewRay);
    precise vec3 dir = normalize(vec3(frame.worldFromView * vec4(viewRay, 0.0f)));
    precise vec3 origin = frame.cameraPosition.xyz;
    // Origin moved to the centre; the half-b form avoids cancellation (as the CPU).
    precise vec3 oc = origin - center;
    precise float b = dot(oc, dir);
    precise vec3 perp = oc - b * dir;
    precise float disc = radius * radius - dot(perp, perp);
    precise float s = sqrt(max(disc, 0.0f));
    precise float t0 = -b - s;
    precise float t = t0 > 0.0f ? t0 : -b + s;
    h.hit = disc >= 0.0f && t > 0.0f && t < frame.projection.w * rayPerDepth;
    precise vec3 position = origin + t * dir;
    h.position = position;
    vec3 n = normalize(position - center);
    h.normal = dot(n, dir) > 0.0f ? -n : n;
    h.viewDepth = t / rayPerDepth;
    precise vec4 clip = frame.clipFromWorld * vec4(position, 1.0f);
    precise float depth = clamp(clip.z / clip.w, 0.0f, 1.0f);
    h.depth = depth;
    return h;
}

#endif
