// Specialization constants: what a compiled scene lets a pass's pipeline leave out, declared once for
// GLSL (layout(constant_id = N) const int) and C++ (gpu/pipeline.h SpecKey, VkSpecializationInfo).
// Lavapipe runs both sides of every branch (docs/performance.md): code behind a condition that is
// never true in this scene still costs its full price, unless the condition is a constant when the
// pipeline is built, which removes the code. Each default means "not specialized": a pipeline built
// without the constants (the CPU, a pass the table does not specialize) behaves as before.
// X(name, constant_id, default); every constant is a 32-bit int.
#ifndef BRUME_SHARED_SPECIALIZATION_H
#define BRUME_SHARED_SPECIALIZATION_H

#define BRUME_SPEC_CONSTANTS(X)                                                                              \
    X(SPEC_VOLUME_KINDS, 0, -1)        /* bit (1 << VOLUME_*) per volume kind in the scene; -1: all */    \
    X(SPEC_DIRECTIONAL_LIGHTS, 1, -1)  /* directional surface lights (light reach); -1: read the list */  \
    X(SPEC_LOCAL_FOG_SHADOWS, 2, 1)    /* 0: frame.localFogShadows is 0 */                                 \
    X(SPEC_SUN_SHADOW_MAP, 3, 1)       /* 0: no sun shadow map (frame.sunShadowLight is 0) */              \
    X(SPEC_LOCAL_SHADOW_MAPS, 4, 1)    /* 0: no point/spot light has a shadow map */                       \
    X(SPEC_VDB_SHADOWS, 5, 1)          /* 0: frame.vdbShadowSamples is 0 */                                \
    X(SPEC_DISTANT_FOG, 6, 1)          /* 0: no height or depth fog (nothing past the froxel far) */       \
    X(SPEC_VOLUME_COUNT, 7, -1)        /* volumes, when SPEC_VOLUME_LIST holds each one's kind; -1: not */ \
    X(SPEC_VOLUME_LIST, 8, 0)          /* VOLUME_* of volume i in bits 3i..3i+2 (SPEC_MAX_LISTED_VOLUMES) */ \
    X(SPEC_INFLUENCERS, 9, 1)          /* 0: no influencer sample (voxelize leaves the factor out) */      \
    X(SPEC_SHADOW_REDUCTION, 10, 0)    /* frame.shadowReduction (the light pass's cell levels); 0: read it */ \
    X(SPEC_EMISSION, 11, 1)            /* 0: no volume emits: no mediaEmission store or load */ \
    X(SPEC_GREY_FOG_SHADOWS, 12, 0)    /* 1: every volume's sigma_s + sigma_a is grey: one exp per light */ \
    X(SPEC_SPOT_LIGHTS, 13, 1)         /* 0: no spot light: evalLightNear's cone is left out */ \
    X(SPEC_SHAPE_LIST, 14, -1)         /* box-kind shape and falloff of volume i in bits 3i..3i+2; -1: read them */ \
    X(SPEC_SURFACE_LIGHTS, 15, -1)     /* geometry: surface light count | slot kinds (below); -1: read the reach list */

// Scenes with at most this many volumes get each volume's kind as a constant (SPEC_VOLUME_LIST):
// volume i's VOLUME_* (0..4) in 3 bits, packed and unpacked by these two macros on both sides.
#define SPEC_MAX_LISTED_VOLUMES 10
#define BRUME_SPEC_VOLUME_LIST_ENTRY(i, kind) ((kind) << (3 * (i)))
#define BRUME_SPEC_LISTED_KIND(list, i) (((list) >> (3 * (i))) & 7)
// With the list, each box-kind volume's shape (SHAPE_*, bits 3i..3i+1) and whether it has a height
// falloff (bit 3i + 2) as a constant too (SPEC_SHAPE_LIST): the fog shadow's closed form then builds
// that shape's intervals and distances only, and the box's closed form or the sampled integral, not
// both (shared/shadows.h shadowDensityLengthListed). 0 for the other kinds.
#define BRUME_SPEC_SHAPE_ENTRY(i, shape, falloff) (((shape) | ((falloff) ? 4 : 0)) << (3 * (i)))
// M(0) ... M(SPEC_MAX_LISTED_VOLUMES - 1): the shaders' loops over the listed volumes, unrolled so that
// each volume's index, and so its kind, is a constant (fog_shadow.glsl, voxelize_body.glsl,
// distant_fog.comp; each body tests BRUME_SPEC_VOLUME_LISTED(i)).
// SPEC_SURFACE_LIGHTS, the geometry pass's surface lights (bindings.h SurfaceLights) when there are at
// most SURFACE_LIGHT_SLOTS: their count in bits 0..3, slot s's LIGHT_* in bits 4 + 2s..5 + 2s.
#define BRUME_SPEC_SURFACE_LIGHT_ENTRY(s, kind) ((kind) << (4 + 2 * (s)))
#define BRUME_SPEC_SURFACE_LIGHT_COUNT(spec) ((spec) & 15)
#define BRUME_SPEC_SURFACE_LIGHT_KIND(spec, s) (((spec) >> (4 + 2 * (s))) & 3)
#define BRUME_EACH_LISTED_VOLUME(M) M(0) M(1) M(2) M(3) M(4) M(5) M(6) M(7) M(8) M(9)
// In the froxel passes' list only (gpu: RendererState::froxelSpec): volume i is out of their reach this
// frame (core/media_region.h froxelVolumesInReach), its terms are exactly 0 and are left out.
#define SPEC_CULLED_VOLUME 7

#ifdef __cplusplus
// The CPU evaluates every kind.
#define BRUME_VOLUME_KIND_USED(k) true
#define BRUME_SPOT_LIGHTS_USED true
#else
#define BRUME_GLSL_SPEC_CONSTANT(name, id, value) layout(constant_id = id) const int name = value;
BRUME_SPEC_CONSTANTS(BRUME_GLSL_SPEC_CONSTANT)
#undef BRUME_GLSL_SPEC_CONSTANT
// Whether volume kind k can occur in this pipeline's scene (a constant once specialized).
#define BRUME_VOLUME_KIND_USED(k) ((SPEC_VOLUME_KINDS & (1 << (k))) != 0)
// Whether a spot light can occur in this pipeline's scene (a constant once specialized).
#define BRUME_SPOT_LIGHTS_USED (SPEC_SPOT_LIGHTS != 0)
// Whether slot i of BRUME_EACH_LISTED_VOLUME holds a volume this pipeline evaluates: listed, and not
// culled (a constant once specialized; the bodies of the unrolled loops test it).
#define BRUME_SPEC_VOLUME_LISTED(i) \
    ((i) < SPEC_VOLUME_COUNT && BRUME_SPEC_LISTED_KIND(SPEC_VOLUME_LIST, i) != SPEC_CULLED_VOLUME)
// Slot i's SPEC_SHAPE_LIST entry (shape | 4 with a falloff), or -1 where the pipeline reads them.
#define BRUME_SPEC_LISTED_SHAPE(i) (SPEC_SHAPE_LIST < 0 ? -1 : ((SPEC_SHAPE_LIST >> (3 * (i))) & 7))
#endif

#endif
