// Entry s of the integrated volume blended bilinearly between lookup k's four columns (shd::
// integratedLookup, step 1), read through the includer's integratedAt(x, y, s): the composite's reads
// both images, the glow's the transmittance alone. Include after defining integratedAt.
Accumulated integratedEntry(IntegratedLookup k, int s) {
    Accumulated row0 = mixAccumulated(integratedAt(k.columns.x, k.columns.y, s), integratedAt(k.columns.z, k.columns.y, s),
                                      k.weights.x);
    Accumulated row1 = mixAccumulated(integratedAt(k.columns.x, k.columns.w, s), integratedAt(k.columns.z, k.columns.w, s),
                                      k.weights.x);
    return mixAccumulated(row0, row1, k.weights.y);
}

// Lookup k's result from its two entries' blends (integratedEntry at k.entries.x and .y): between them
// in depth, then against the empty result near the camera (shd::integratedLookup, steps 2 and 3).
Accumulated integratedResult(IntegratedLookup k, Accumulated first, Accumulated second) {
    Accumulated entries = mixAccumulated(first, second, k.weights.z);
    return mixAccumulated(emptyAccumulated(), entries, k.entryWeight);
}
