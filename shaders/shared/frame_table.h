// The GPU froxel frame's resources, declared once for GLSL and C++ as X-macro tables: the one
// descriptor set (set 0) every pass shares. shaders/resources.glsl expands them into the GLSL
// declarations; gpu/frame_table.h expands them into the renderer's resource table, from which
// gpu/frame_executor.cpp derives creation, debug names, the descriptor layout, pool and writes,
// layout transitions and the readback (docs/gpu.md, "The frame as data"). Not used by the CPU.
//
// Adding a froxel image is one line in BRUME_FRAME_IMAGES with the next free binding (then use it in
// a shader and name it in a pass's reads or writes in gpu/frame_table.cpp); tests/test_frame_table.cpp
// checks that the bindings are 0..N-1 without gaps and every shader's bindings against these tables.
//
// Columns are plain tokens so that both preprocessors can pass them through: GLSL uses the layout
// and block columns, C++ the kind and flag columns (gpu/frame_table.h gives them meaning).
#ifndef BRUME_SHARED_FRAME_TABLE_H
#define BRUME_SHARED_FRAME_TABLE_H

// Buffers: X(id, binding, kind, glsl layout, glsl qualifiers, block name, block body).
//   kind UNIFORM: a uniform buffer the host writes; STORAGE: a storage buffer the host writes;
//   STORAGE_GPU: one the passes write; STORAGE_READBACK: one the passes write and the host reads;
//   STORAGE_INDIRECT: one the passes write that starts with a VkDispatchIndirectCommand, which the
//   frame resets to (0, 1, 1) (the 4th uint to 0) before the first pass.
//   Sizes follow the scene (volumes, lights, grids, shadow maps): GpuRenderer::State::prepare.
#define BRUME_FRAME_BUFFERS(X) \
    X(frame, 0, UNIFORM, std140, uniform, FrameBlock, FrameUniforms frame;) \
    X(volumes, 1, STORAGE, std430, readonly buffer, VolumeBlock, VolumeData volumes[];) \
    X(lights, 2, STORAGE, std430, readonly buffer, LightBlock, LightData lights[];) \
    X(counters, 3, STORAGE_READBACK, std430, buffer, CounterBlock, FroxelCounters counters;) \
    X(previousFrame, 4, UNIFORM, std140, uniform, PreviousFrameBlock, FrameUniforms previousFrame;) \
    X(shadowTransmittance, 5, STORAGE_GPU, std430, buffer, ShadowBlock, vec4 shadowTransmittance[];) \
    X(vdbGrids, 6, STORAGE, std430, readonly buffer, VdbGridBlock, uint vdbGridWords[];) \
    X(lightClusters, 7, STORAGE, std430, readonly buffer, ClusterBlock, int lightClusters[];) \
    X(sunShadowMap, 8, STORAGE, std430, readonly buffer, SunShadowBlock, SunShadowFit sunShadowFit; float sunShadowDepth[];) \
    X(localShadowMaps, 9, STORAGE, std430, readonly buffer, LocalShadowBlock, float localShadowDepth[];) \
    X(exactList, 23, STORAGE_INDIRECT, std430, buffer, ExactListBlock, ExactListHeader exactList; uint exactFroxels[];) \
    X(distantTable, 24, STORAGE_GPU, std430, buffer, DistantTableBlock, vec4 distantTable[];) \
    X(influence, 25, STORAGE, std430, readonly buffer, InfluenceBlock, InfluenceHeader influenceHeader; InfluenceSample influenceSamples[];) \
    X(depthTiles, 31, STORAGE_GPU, std430, buffer, DepthTileBlock, vec2 depthTileRange[];) \
    X(nearTiles, 32, STORAGE_INDIRECT, std430, buffer, NearTileBlock, ExactListHeader nearTileList; uint nearTileIndex[];) \
    X(farTiles, 33, STORAGE_INDIRECT, std430, buffer, FarTileBlock, ExactListHeader farTileList; uint farTileIndex[];) \
    X(allFarTiles, 35, STORAGE_INDIRECT, std430, buffer, AllFarTileBlock, ExactListHeader allFarTileList; uint allFarTileIndex[];) \
    X(columnEnds, 37, STORAGE_GPU, std430, buffer, ColumnEndBlock, ivec4 columnEnd[];) \
    X(surfaceLights, 46, UNIFORM, std140, uniform, SurfaceLightBlock, SurfaceLights surfaceLights;) \
    X(skyTiles, 47, STORAGE_INDIRECT, std430, buffer, SkyTileBlock, ExactListHeader skyTileList; uint skyTileIndex[];)

// What the buffers hold:
//   frame               FrameUniforms of this frame (types.h)
//   volumes, lights     VolumeData[], LightData[] (at least one entry each)
//   counters            FroxelCounters (bindings.h), counted by the light pass, read back by the host
//   previousFrame       FrameUniforms of the previous frame (temporal pass)
//   shadowTransmittance vec4[]: the fog transmittance volume (shadow_volume.h shadowVolumeIndex),
//                       written by the shadow volume pass; its readers go through the texel view
//                       shadowTexels (below). A buffer, not an image: lavapipe's imageLoad is ~3x
//                       dearer, and the geometry pass reads it
//   vdbGrids            uint[]: every vdb volume's NanoVDB grid back to back (VolumeData.kind.y: byte
//                       offset), read with PNanoVDB
//   lightClusters       int[]: light lists per cluster and the light reach record (clusters.h)
//   sunShadowMap        SunShadowFit, then float depth[N * N] (sun_shadow.h), built on the host
//   localShadowMaps     float[]: every point/spot shadow map face (local_shadow.h), built on the host
//   exactList           ExactListHeader, then uint[] (bindings.h): the froxels whose fog transmittance
//                       the light pass left to the exact pass, and that pass's indirect dispatch
//   distantTable        vec4[]: the distant fog per tile corner and depth (distant_table.h), written
//                       by the distant fog pass, read by the composite
//   influence           InfluenceHeader, then InfluenceSample[] (influence.h): the influencers and
//                       their wakes at the scene time (core/influence.h), read by voxelize
//   depthTiles          vec2[]: the deepest (x) and shallowest (y) view depth of each 8x8 pixel tile
//                       (distant_table.h depthTileIndex), written by the depth tiles pass when the
//                       scene has distant fog, read by the distant fog pass (x) and the tile lists pass
//   columnEnds          ivec4[2 x columns]: per froxel column, the integrated entries its pixels' lookups
//                       read (xy, inclusive) and its walk end (z: the froxels it computes are [0, z)),
//                       this frame's (half frame.temporal.w) and the previous frame's (the other half),
//                       written by the column ends pass (shaders/column_entries.glsl)
//   surfaceLights       SurfaceLights (bindings.h): the surface lights in the light reach's order, read by
//                       the geometry pass where SPEC_SURFACE_LIGHTS gives their count and kinds
//   nearTiles, farTiles, allFarTiles
//                       ExactListHeader (the indirect dispatch: one workgroup per tile), then uint[]:
//                       the tiles (depthTileIndex) whose pixels all lie within the froxel far, those
//                       whose pixels all lie past it (allFar: clear of it by DISTANT_ALL_FAR_MARGIN),
//                       and the others; written by the tile lists pass, dispatched over by the
//                       composite (near: no distant fog code), the composite all far (one entry of the
//                       integrated volume, its last) and the composite far (composite_body.glsl)
//   skyTiles            the same for the tiles whose pixels are all sky (distant_table.h isSkyDepth):
//                       the composite sky (the integrated volume's last entry and the table's, alone)

// Uniform texel buffer views of the buffers above, X(id, binding, viewed buffer, texel format): GLSL
// reads them with texelFetch (a samplerBuffer, an isamplerBuffer for the r32i and rgba32i formats:
// the bits as stored, intBitsToFloat gives a float field back); they alias the buffer's memory, so the executor
// orders their reads after the buffer's writes (a pass lists the view in its reads). Why a view:
// lavapipe loads a storage buffer lane by lane (8 guarded scalar loads per component), a texel
// buffer's texelFetch through its sampler's vector gather (docs/performance.md, "blend").
//   shadowTexels        shadowTransmittance as rgba32f texels (fog_shadow.glsl shadowCell): the light
//                       passes' and the surfaces' reads of the fog transmittance volume
//   lightClusterTexels  lightClusters as r32i texels: the light passes' reads of the cluster lists
//   lightTexels         lights as rgba32i texels, LIGHT_DATA_TEXELS per LightData (resources.glsl
//                       lightAt): the light passes' reads of the lights
//   distantTexels       distantTable as rgba32f texels: the composite's 16 reads per pixel
//   volumeTexels        volumes as rgba32i texels, VOLUME_DATA_TEXELS per VolumeData (resources.glsl
//                       volumeAt): voxelize's and the closed forms' reads of the volumes (light
//                       exact, geometry, shadow volume, distant fog)
//   sunShadowTexels     sunShadowMap as rgba32f texels: the fit's SUN_SHADOW_FIT_TEXELS vec4s, then the
//                       depths 4 to a texel (sun_shadow.glsl): the light passes' and the surfaces' reads
//   columnEndTexels     columnEnds as rgba32i texels (column_entries.glsl): the reads of the walk ends by
//                       the shadow volume (up to 64 a run), light, temporal (4 a froxel in motion) and
//                       integrate passes; the column ends pass writes the buffer
//   depthTileTexels     depthTiles as rg32f texels: the column ends pass's (up to 36 a column) and the
//                       distant fog pass's reads of the tiles' depths
//   vdbGridTexels       vdbGrids as r32i texels: every read of a grid or a density texture (PNanoVDB's
//                       tree walks, the occupancy cells; pnanovdb_texels.glsl)
//   localShadowTexels   localShadowMaps as r32f texels: the point/spot shadow maps' 4 depths per lookup
//                       (local_shadow.glsl) by the light passes and the surfaces
//   influenceTexels     influence as rgba32f texels: the header's 3 (INFLUENCE_HEADER_TEXELS), then 2 per
//                       InfluenceSample (influence.glsl): the inline media's and voxelize's reads
//   nearTileTexels, farTileTexels, allFarTileTexels, skyTileTexels
//                       the tile lists as r32i texels: each composite invocation's read of its tile
//                       (TILE_LIST_HEADER_TEXELS, then the tiles), the same for the workgroup's 64
// Which passes read a buffer through its views is a define per shader (resources.glsl); a pass reads
// a buffer through its views or through the buffer, not both (docs/performance.md, "light3").
#define BRUME_FRAME_TEXEL_VIEWS(X) \
    X(shadowTexels, 26, shadowTransmittance, rgba32f) \
    X(lightClusterTexels, 27, lightClusters, r32i) \
    X(lightTexels, 28, lights, rgba32i) \
    X(distantTexels, 29, distantTable, rgba32f) \
    X(volumeTexels, 30, volumes, rgba32i) \
    X(sunShadowTexels, 34, sunShadowMap, rgba32f) \
    X(columnEndTexels, 38, columnEnds, rgba32i) \
    X(depthTileTexels, 39, depthTiles, rg32f) \
    X(nearTileTexels, 40, nearTiles, r32i) \
    X(farTileTexels, 41, farTiles, r32i) \
    X(allFarTileTexels, 42, allFarTiles, r32i) \
    X(vdbGridTexels, 43, vdbGrids, r32i) \
    X(localShadowTexels, 44, localShadowMaps, r32f) \
    X(influenceTexels, 45, influence, rgba32f) \
    X(skyTileTexels, 48, skyTiles, r32i)

// Storage images, compute stages only: X(id, binding, glsl format, glsl type, flags).
//   image3D: one texel per froxel; image2D: one per pixel. Flags (C++ only):
//   FRAME: rewritten every frame (contents discarded at its start);
//   READBACK: copied to the host when render() is asked for the froxel volumes (FroxelVolumes order);
//   TARGET: also a colour attachment of the geometry pass (it clears and writes it);
//   OUTPUT: the composited image, read back every frame;
//   MEDIA: voxelize's output, which only the frames that run voxelize use (gpu/frame_table.h
//   VariantKey::inlineMedia): one texel otherwise, so a scene without vdb volumes does not hold 48 B
//   per froxel it never writes (GpuRenderer::State::ensureFroxelImages).
#define BRUME_FRAME_IMAGES(X) \
    X(mediaScatteringG, 10, rgba32f, image3D, FRAME_READBACK_MEDIA) \
    X(mediaExtinction, 11, rgba32f, image3D, FRAME_READBACK_MEDIA) \
    X(mediaEmission, 12, rgba32f, image3D, FRAME_READBACK_MEDIA) \
    X(sourceImage, 13, rgba32f, image3D, FRAME_READBACK) \
    X(integratedScattering, 14, rgba32f, image3D, FRAME_READBACK) \
    X(integratedTransmittance, 15, rgba16, image3D, FRAME_READBACK) \
    X(sceneColor, 16, rgba32f, image2D, TARGET) \
    X(sceneDepth, 17, r32f, image2D, TARGET) \
    X(outputImage, 18, rgba32f, image2D, FRAME_OUTPUT) \
    X(sourceExtinction, 36, rg32f, image3D, FRAME)

// What the images hold:
//   mediaScatteringG       rgb sigma_s [1/m], a phase g        (voxelize)
//   mediaExtinction        rgb sigma_t [1/m]                   (voxelize; the light pass reads it
//                                                               where it does not compute the media)
//   mediaEmission          rgb emission                         (voxelize)
//   Without vdb volumes the light passes and the glow compute the media themselves and voxelize runs
//   only for the read-back volumes (gpu/frame_table.h VariantKey::inlineMedia).
//   sourceImage            rgb source S, a sigma_t.r            (light; temporal resolves them)
//   sourceExtinction       rg sigma_t.g, sigma_t.b              (light): the froxel's S and sigma_t in
//                          6 words, as the history holds them (resources.glsl sourceTexelA / B), where
//                          they took 8 in sourceImage and mediaExtinction, whose alphas were 0: stores
//                          cost lavapipe per word (docs/performance.md, "pack")
//   integratedScattering   camera -> far side of each slice     (integrate)
//   integratedTransmittance                                     (integrate)
//                          in [0, 1], 16-bit unsigned normalized: rounded by at most 0.5 / 65535 (7.6e-6)
//                          absolute, 0 and 1 exact. Half the bytes and half the lane-by-lane store loops of
//                          rgba32f on lavapipe (docs/performance.md, "froxel"); half floats (2.4e-4
//                          relative) made brume tradeoff's errors worse
//   sceneColor             shaded surfaces / sky radiance       (geometry)
//   sceneDepth             view depth [m], camera far = sky     (geometry)
//   outputImage            the composited image                 (composite, debug view)

// Temporal history: ping-pong pairs of froxel images kept across frames,
// X(id, input name, input binding, output name, output binding, glsl format, glsl type).
// Each frame reads the pair's *_IN side (what the previous frame wrote) and writes its *_OUT side;
// the renderer swaps which image sits behind each binding every frame.
//   historySource          rgb the resolved source S, a sigma_t.r   (temporal in motion, integrate at rest)
//   historyExtinction      rg the resolved sigma_t.g, sigma_t.b
// S's and sigma_t's alpha is 0, so one froxel's 7 numbers take 6 words, not 8: 25% fewer words stored
// and loaded per froxel, in the two passes that are lavapipe's store loops (docs/performance.md,
// "history"). resources.glsl packs and unpacks them; the read-back volumes unpack them on the host.
#define BRUME_FRAME_HISTORY(X) \
    X(historySource, historySourceIn, 19, historySourceOut, 20, rgba32f, image3D) \
    X(historyExtinction, historyExtinctionIn, 21, historyExtinctionOut, 22, rg32f, image3D)

#endif
