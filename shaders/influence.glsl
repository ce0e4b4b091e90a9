// The influencers' thinning of the media at p (shared/influence.h; core: mediaAt in core/compile.cpp,
// which evaluates the same factor in the same order). Called by voxelize only when the pipeline's
// SPEC_INFLUENCERS is on, and only where there is fog inside the samples' box.
float influenceFactorAt(vec3 p) {
    float r = 0.0f;
    for (int i = 0; i < influenceHeader.count.x; ++i) r = max(r, influenceSampleReduction(influenceSamples[i], p));
    return 1.0f - r;
}

MediaSample influencedMedia(MediaSample m, vec3 p) {
    bool any = m.gWeight > 0.0f || m.sigmaT != vec3(0.0f) || m.emission != vec3(0.0f);
    if (any && insideInfluenceBounds(influenceHeader, p)) m = influenceScaleMedia(m, influenceFactorAt(p));
    return m;
}
