// The influencers' thinning of the media at p (shared/influence.h; core: mediaAt in core/compile.cpp,
// which evaluates the same factor in the same order). Called by voxelize only when the pipeline's
// SPEC_INFLUENCERS is on, and only where there is fog inside the samples' box.
// The buffer is read through its texel view influenceTexels (shared/frame_table.h): lavapipe loads a
// storage buffer lane by lane, and every froxel reads every sample.
InfluenceHeader influenceHeaderTexels() {
    vec4 count = texelFetch(influenceTexels, 0);
    return InfluenceHeader(floatBitsToInt(count), texelFetch(influenceTexels, 1), texelFetch(influenceTexels, 2));
}

InfluenceSample influenceSampleTexels(int i) {
    int t = INFLUENCE_HEADER_TEXELS + 2 * i;
    return InfluenceSample(texelFetch(influenceTexels, t), texelFetch(influenceTexels, t + 1));
}

float influenceFactorAt(InfluenceHeader h, vec3 p) {
    float r = 0.0f;
    for (int i = 0; i < h.count.x; ++i) r = max(r, influenceSampleReduction(influenceSampleTexels(i), p));
    return 1.0f - r;
}

MediaSample influencedMedia(MediaSample m, vec3 p) {
    bool any = m.gWeight > 0.0f || m.sigmaT != vec3(0.0f) || m.emission != vec3(0.0f);
    InfluenceHeader h = influenceHeaderTexels();
    if (any && insideInfluenceBounds(h, p)) m = influenceScaleMedia(m, influenceFactorAt(h, p));
    return m;
}
