// The point and spot lights' glow, the per-pixel part (shared/glow.h; core: compositeRow), added to the
// composited image: one dispatch per glowing light, in light order, over the pixels whose rays can
// meet its ball (lightGlowScreenRect, in the push constants). In the composite, lavapipe paid for the
// quadrature on every pixel of the screen (docs/performance.md, "perfgeo").
#define BRUME_FROXEL_IMAGES
// The light through the texel view lightTexels (resources.glsl lightAt): lavapipe loads a storage
// buffer's LightData lane by lane (docs/performance.md, "texel2").
#define BRUME_LIGHT_TEXELS
#define BRUME_VOLUME_TEXELS  // the volumes of the _media variants' media (media_at.glsl)
#include "resources.glsl"
#ifdef BRUME_INLINE_MEDIA
#ifdef BRUME_VOXELIZE_TEXTURE
#include "density_texture.glsl"
#endif
#include "media_at.glsl"
#endif

layout(local_size_x = SCREEN_GROUP_X, local_size_y = SCREEN_GROUP_Y, local_size_z = 1) in;

layout(push_constant) uniform GlowPush { GlowParams glow; };

Accumulated integratedAt(int x, int y, int s) {
    Accumulated a;
    a.scattering = vec3(0.0f);
    a.transmittance = imageLoad(integratedTransmittance, ivec3(x, y, s)).rgb;
    return a;
}

#include "integrated_lookup.glsl"

// The transmittance of the integrated volume's lookup (shd::integratedLookup; composite.comp).
vec3 integratedTransmittanceAt(vec2 pixel, float viewDepth) {
    IntegratedLookup k = integratedLookup(pixel, viewDepth, frame);
    Accumulated byEntry[2];
    for (int e = 0; e < 2; ++e) byEntry[e] = integratedEntry(k, k.entries[e]);
    return integratedResult(k, byEntry[0], byEntry[1]).transmittance;
}

void main() {
    ivec2 px = glow.rect.xy + ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThan(px, glow.rect.zw))) return;
    float viewDepth = imageLoad(sceneDepth, px).r;
    vec2 pixel = vec2(px) + vec2(0.5f);
    vec3 viewRay = viewRayFromPixel(pixel, frame);
    float rayPerDepth = length(viewRay);
    vec3 dir = normalize(vec3(frame.worldFromView * vec4(viewRay, 0.0f)));
    vec3 origin = frame.cameraPosition.xyz;
    LightData l = lightAt(glow.light.x);
    LightGlowRay r = lightGlowRay(l, frame, origin, dir, viewDepth * rayPerDepth);
    if (r.radius <= 0.0f) return;
    ivec3 m = lightGlowFroxel(r, origin, dir, frame);
#ifdef BRUME_INLINE_MEDIA
    // The _media variants (scenes without vdb volumes): voxelize has not run; the media at froxel m's
    // sample point as voxelize computes them (media_at.glsl), the same values.
    MediaSample media = froxelMediaAt(worldFromFroxelCoord(vec3(m) + frame.jitter.xyz, frame));
    vec4 scatteringG = vec4(media.sigmaS, mediaPhaseG(media));
#else
    vec4 scatteringG = imageLoad(mediaScatteringG, m);
#endif
    // The resolved sigma_t (integrate.comp), in the history's two texels (resources.glsl).
    vec3 sigmaT = historyExtinctionOf(imageLoad(historySourceOut, m), imageLoad(historyExtinctionOut, m)).rgb;
    vec3 toEnter = integratedTransmittanceAt(pixel, r.enter / rayPerDepth);
    vec3 sum = toEnter * scatteringG.rgb * lightGlowPerSigmaS(l, r, origin, dir, sigmaT, scatteringG.a);
    imageStore(outputImage, px, vec4(imageLoad(outputImage, px).rgb + sum, 1.0f));
}
