// Lavapipe hands each of its threads one contiguous block of a dispatch's workgroups, in x, then y,
// then z order, and no thread steals another's (docs/performance.md, "Lavapipe's cost model"). Where
// the cost of a workgroup follows its place (a frame skipping hidden froxels: the deep runs of the
// light pass and the ground's columns cost little, the sky's columns much), the first half of the
// order would cost more than the second, and one core would idle. balancedGlobalID interleaves the
// halves: the workgroup at place w of the order runs the grid's workgroup 2w in the first half and
// 2(w - half) + 1 in the second, so each half of the order covers every second workgroup of the grid.
// A bijection of the workgroups: every invocation still runs once.
uvec3 balancedWorkGroupID() {
    uvec3 n = gl_NumWorkGroups;
    uint w = gl_WorkGroupID.x + n.x * (gl_WorkGroupID.y + n.y * gl_WorkGroupID.z);
    uint firstHalf = (n.x * n.y * n.z + 1u) / 2u;
    uint t = w < firstHalf ? 2u * w : 2u * (w - firstHalf) + 1u;
    return uvec3(t % n.x, (t / n.x) % n.y, t / (n.x * n.y));
}

uvec3 balancedGlobalID() { return balancedWorkGroupID() * gl_WorkGroupSize + gl_LocalInvocationID; }
