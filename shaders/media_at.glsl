// The media of every volume at a froxel's sample point (core: voxelizeRow's mediaAt), shared by the
// voxelize pass and, for scenes without vdb volumes, the passes that compute the media where they use
// them instead of loading voxelize's images (light_body.glsl, glow.comp with BRUME_INLINE_MEDIA;
// docs/performance.md, "fuse"). Include after resources.glsl (with BRUME_VOLUME_TEXELS), and after
// vdb_sample.glsl (BRUME_VOXELIZE_VDB) or density_texture.glsl (BRUME_VOXELIZE_TEXTURE) when defined.
#include "influence.glsl"

// Volume i (of kind k: a constant in pipelines specialized with the scene's volume list) at p. The
// volumes come through the texel view volumeTexels (resources.glsl volumeAt: a vector gather on
// lavapipe, where volumes[i] loads lane by lane).
void addVolume(inout MediaSample m, int i, int k, vec3 p) {
    VolumeData v = volumeAt(i);
    if (!insideBounds(v, p)) return;
#ifdef BRUME_VOXELIZE_VDB
    float density = BRUME_VOLUME_KIND_USED(VOLUME_VDB) && k == VOLUME_VDB
                        ? vdbDensity(v, p)
                        : analyticDensityOfKind(k, v, p, frame.cameraPosition.xyz);
#else
    float density = analyticDensityOfKind(k, v, p, frame.cameraPosition.xyz);
#endif
#ifdef BRUME_VOXELIZE_TEXTURE
    if (density > 0.0f) density *= densityTextureFactor(v, p);
#endif
    m = addMedium(m, v, density);
}

MediaSample mediaAt(vec3 p) {
    MediaSample m = emptyMedia();
    if (SPEC_VOLUME_COUNT >= 0) {
        // Unrolled by hand with each volume's kind a constant (fog_shadow.glsl does the same): only that
        // kind's density is built for it; a loop would run every kind's code for every volume.
#define BRUME_LISTED_VOLUME(i) \
    if (BRUME_SPEC_VOLUME_LISTED(i)) \
        addVolume(m, i, BRUME_SPEC_LISTED_KIND(SPEC_VOLUME_LIST, i), p);
        BRUME_EACH_LISTED_VOLUME(BRUME_LISTED_VOLUME)
#undef BRUME_LISTED_VOLUME
    } else {
        for (int i = 0; i < frame.counts.z; ++i) addVolume(m, i, volumeAt(i).kind.x, p);
    }
    return m;
}

// The media at froxel sample point p, the influencers' thinning included: what voxelize stores.
MediaSample froxelMediaAt(vec3 p) {
    MediaSample m = mediaAt(p);
    if (SPEC_INFLUENCERS != 0) m = influencedMedia(m, p);
    return m;
}
