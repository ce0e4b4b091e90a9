#include "compile.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "animate.h"
#include "shaders/shared/distant_table.h"
#include "shadows.h"

namespace brume {

using shd::BRUME_HUGE;

static void unbounded(shd::VolumeData& d) {
    d.worldMin = glm::vec4(-BRUME_HUGE, -BRUME_HUGE, -BRUME_HUGE, 0.0f);
    d.worldMax = glm::vec4(BRUME_HUGE, BRUME_HUGE, BRUME_HUGE, 0.0f);
}

void unitCubeWorldBounds(const glm::mat4& worldFromLocal, glm::vec3& lo, glm::vec3& hi) {
    lo = glm::vec3(BRUME_HUGE);
    hi = glm::vec3(-BRUME_HUGE);
    for (int i = 0; i < 8; ++i) {
        glm::vec3 c((i & 1) ? 0.5f : -0.5f, (i & 2) ? 0.5f : -0.5f, (i & 4) ? 0.5f : -0.5f);
        glm::vec3 w = glm::vec3(worldFromLocal * glm::vec4(c, 1.0f));
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
    }
}

static void boundsOfUnitCube(shd::VolumeData& d, const glm::mat4& worldFromLocal) {
    glm::vec3 lo, hi;
    unitCubeWorldBounds(worldFromLocal, lo, hi);
    d.worldMin = glm::vec4(lo, 0.0f);
    d.worldMax = glm::vec4(hi, 0.0f);
}

// The tight world bounds of a box-kind shape: along world axis i the shape reaches
// 0.5 x (the length of row i of the linear map) for an ellipsoid, 0.5 x (|(row i).xz| + |row_i.y|)
// for a cylinder (local Y its axis), the unit cube's corners for a box. worldMin.y is its bottom.
static void boundsOfShape(shd::VolumeData& d, const glm::mat4& worldFromLocal, int shape) {
    if (shape == shd::SHAPE_BOX) return boundsOfUnitCube(d, worldFromLocal);
    const glm::vec3 centre(worldFromLocal[3]);
    glm::vec3 half;
    for (int i = 0; i < 3; ++i) {
        const glm::vec3 row(worldFromLocal[0][i], worldFromLocal[1][i], worldFromLocal[2][i]);
        half[i] = shape == shd::SHAPE_ELLIPSOID ? 0.5f * glm::length(row)
                                                 : 0.5f * (glm::length(glm::vec2(row.x, row.z)) + std::abs(row.y));
    }
    d.worldMin = glm::vec4(centre - half, 0.0f);
    d.worldMax = glm::vec4(centre + half, 0.0f);
}

static int shapeOf(VolumeType t) {
    return t == VolumeType::Ellipsoid ? shd::SHAPE_ELLIPSOID : t == VolumeType::Cylinder ? shd::SHAPE_CYLINDER : shd::SHAPE_BOX;
}

// index space -> grid space (the file's voxel transform) -> the volume's transform -> world.
static void compileVdb(const Volume& v, shd::VolumeData& d) {
    d.kind.x = shd::VOLUME_VDB;
    d.params.x = v.density_scale;
    if (!v.density || v.density->empty()) {
        // Nothing to sample: bounds that contain no point.
        d.worldMin = glm::vec4(BRUME_HUGE, BRUME_HUGE, BRUME_HUGE, 0.0f);
        d.worldMax = glm::vec4(-BRUME_HUGE, -BRUME_HUGE, -BRUME_HUGE, 0.0f);
        return;
    }
    d.kind.z = 1;
    d.kind.w = static_cast<int>(v.density->occupancyOffset());
    const glm::mat4 worldFromIndex = v.transform.worldFromLocal() * v.density->gridFromIndex();
    d.localFromWorld = glm::inverse(worldFromIndex);
    const glm::vec3 lo = v.density->indexMin(), hi = v.density->indexMax();
    glm::vec3 wlo(BRUME_HUGE), whi(-BRUME_HUGE);
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 c((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
        const glm::vec3 w = glm::vec3(worldFromIndex * glm::vec4(c, 1.0f));
        wlo = glm::min(wlo, w);
        whi = glm::max(whi, w);
    }
    d.worldMin = glm::vec4(wlo, 0.0f);
    d.worldMax = glm::vec4(whi, 0.0f);
    // The shortest world length of a voxel edge: the reference's step limit inside the grid.
    d.params.y = std::min({glm::length(glm::vec3(worldFromIndex[0])), glm::length(glm::vec3(worldFromIndex[1])),
                           glm::length(glm::vec3(worldFromIndex[2]))});
    // height_falloff, as a box's: 1 at the bottom of the grid's world bounds.
    d.params.z = std::max(v.height_falloff, 0.0f);
    d.params.w = d.worldMin.y;
}

// A layer's tile and scroll as written; the grid's active box and mean from the loaded grid. False
// (nothing written) for a layer that is not loaded, empty, or has no positive mean (factor 1).
static bool compileLayer(const TextureLayer& t, glm::vec4& params, glm::vec4& scroll, glm::ivec4& boxMin, glm::ivec4& boxSize) {
    if (!t.density || t.density->empty() || !(t.mean > 0.0f) || !(t.tile_size_m > 0.0f)) return false;
    const glm::ivec3 lo = glm::ivec3(t.density->indexMin()) + 1;  // indexMin/Max are grown by one voxel
    const glm::ivec3 hi = glm::ivec3(t.density->indexMax()) - 1;
    params = glm::vec4(1.0f / t.tile_size_m, t.strength, 1.0f / t.mean, std::max(t.exponent, 0.0f));
    scroll = glm::vec4(t.scroll_mps, 0.0f);
    boxMin = glm::ivec4(lo, 0);
    boxSize = glm::ivec4(hi - lo + 1, 1);
    return true;
}

// The texture, then its detail layer (only with a texture: the detail multiplies the texture's factor).
static void compileTexture(const Volume& v, shd::VolumeData& d) {
    if (!v.density_texture) return;
    const DensityTexture& t = *v.density_texture;
    if (!compileLayer(t, d.textureParams, d.textureScroll, d.textureMin, d.textureSize)) return;
    if (t.detail) compileLayer(*t.detail, d.detailParams, d.detailScroll, d.detailMin, d.detailSize);
}

shd::VolumeData compileVolume(const Volume& v) {
    shd::VolumeData d{};
    d.localFromWorld = glm::mat4(1.0f);
    d.sigmaS_g = glm::vec4(v.medium.scattering, v.medium.phase_g);
    d.sigmaA = glm::vec4(v.medium.absorption, 0.0f);
    d.emission = glm::vec4(v.medium.emission, 0.0f);
    unbounded(d);
    switch (v.type) {
        case VolumeType::Box:
        case VolumeType::Ellipsoid:
        case VolumeType::Cylinder:
            d.kind.x = shd::VOLUME_BOX;
            d.kind.y = shapeOf(v.type);
            d.localFromWorld = v.transform.localFromWorld();
            d.params.x = v.edge_fade;
            boundsOfShape(d, v.transform.worldFromLocal(), d.kind.y);
            d.params.z = std::max(v.height_falloff, 0.0f);
            d.params.w = d.worldMin.y;  // the lowest point, where the height factor is 1
            break;
        case VolumeType::Height:
            // The shared densities divide by transition_height and visibility_distance: scenes from
            // files are range-checked, scenes built in code are held to the same minimum here.
            d.params.x = v.base_height;
            if (v.profile == HeightProfile::Exponential) {
                d.kind.x = shd::VOLUME_HEIGHT_EXPONENTIAL;
                d.params.y = std::max(v.falloff, 0.0f);
                // Above base + 40/falloff the density is below e^-40 (4e-18): nothing visible.
                if (v.falloff > 0.0f) d.worldMax.y = v.base_height + 40.0f / v.falloff;
            } else {
                d.kind.x = shd::VOLUME_HEIGHT_LINEAR;
                d.params.y = std::max(v.transition_height, static_cast<float>(settings::volume_transition_height.min));
                d.worldMax.y = v.base_height + d.params.y;
            }
            break;
        case VolumeType::Depth:
            d.kind.x = shd::VOLUME_DEPTH;
            d.params.x = std::max(v.visibility_distance, static_cast<float>(settings::volume_visibility_distance.min));
            d.params.y = v.start_distance;
            break;
        case VolumeType::Vdb: compileVdb(v, d); break;
        case VolumeType::Mesh:  // a fog grid made from the mesh at load: sampled as a vdb volume, density x 1
            compileVdb(v, d);
            d.params.x = 1.0f;
            break;
    }
    compileTexture(v, d);
    return d;
}

shd::LightData compileLight(const Light& l) {
    shd::LightData d{};
    const float len = glm::length(l.direction);
    const glm::vec3 dir = len > 0.0f ? l.direction / len : glm::vec3(0, -1, 0);
    d.positionRange = glm::vec4(l.position, l.range);
    d.direction = glm::vec4(dir, 0.0f);
    d.intensity = l.color * l.intensity;
    d.fogScale = l.fog_scale;
    d.spot = glm::vec4(std::cos(glm::radians(l.outer_deg)), std::cos(glm::radians(l.inner_deg)), 0.0f, 0.0f);
    switch (l.type) {
        case LightType::Directional: d.kind.x = shd::LIGHT_DIRECTIONAL; break;
        case LightType::Point: d.kind.x = shd::LIGHT_POINT; break;
        case LightType::Spot: d.kind.x = shd::LIGHT_SPOT; break;
    }
    d.kind.y = l.shadows ? 1 : 0;
    return d;
}

CompiledScene compileScene(const Scene& scene) {
    // Keyed settings take their values at the scene time here, so every renderer sees them.
    if (hasKeys(scene)) return compileScene(bakeKeys(scene, scene.time_s));
    CompiledScene cs;
    cs.ambient = scene.ambient;
    cs.cameraPosition = scene.camera.position;
    cs.time = scene.time_s;
    cs.influence = compileInfluence(scene.influencers, scene.time_s);
    size_t gridOffset = 0;
    for (const Volume& v : scene.volumes) {
        shd::VolumeData d = compileVolume(v);
        const bool sampled = shd::vdbHasGrid(d);
        if (sampled) {
            d.kind.y = static_cast<int>(gridOffset);
            gridOffset += v.density->size();
        }
        cs.volumes.push_back(d);
        cs.grids.push_back(sampled ? v.density : nullptr);
    }
    // Textures go after every density grid, in volume order (gpu/vdb_grids.cpp uploads them so).
    for (size_t i = 0; i < scene.volumes.size(); ++i) {
        const bool textured = shd::hasDensityTexture(cs.volumes[i]);
        if (textured) {
            cs.volumes[i].textureMin.w = static_cast<int>(gridOffset);
            gridOffset += scene.volumes[i].density_texture->density->size();
        }
        cs.textures.push_back(textured ? scene.volumes[i].density_texture->density : nullptr);
    }
    for (size_t i = 0; i < scene.volumes.size(); ++i) {
        const bool detailed = shd::hasDetailTexture(cs.volumes[i]);
        if (detailed) {
            cs.volumes[i].detailMin.w = static_cast<int>(gridOffset);
            gridOffset += scene.volumes[i].density_texture->detail->density->size();
        }
        cs.details.push_back(detailed ? scene.volumes[i].density_texture->detail->density : nullptr);
    }
    int localShadowSlots = 0;
    for (const Light& l : scene.lights) {
        shd::LightData d = compileLight(l);
        // Each point or spot light with shadows owns the next slot of the local shadow map array
        // (shared/local_shadow.h), whatever the quality, so slots follow the scene alone.
        if (d.kind.x != shd::LIGHT_DIRECTIONAL && shd::lightCastsShadows(d)) d.kind.z = ++localShadowSlots;
        cs.lights.push_back(d);
    }
    return cs;
}

float plainVolumeDensity(const CompiledScene& cs, size_t i, glm::vec3 p) {
    const shd::VolumeData& v = cs.volumes[i];
    if (v.kind.x != shd::VOLUME_VDB) return shd::analyticDensity(v, p, cs.cameraPosition);
    if (!cs.grids[i]) return 0.0f;
    const glm::vec3 indexPos = shd::vdbIndexPos(v, p);
    // Occupancy culling (kind.w: the cells' offset, 0 = off): the GPU's vdbDensity skips the same walks.
    if (shd::vdbOccupancyOffset(v) != 0 && !cs.grids[i]->occupied(indexPos)) return 0.0f;
    return v.params.x * cs.grids[i]->sampleIndex(indexPos) * shd::localHeightFactor(v, p.y);
}

float densityTextureFactor(const CompiledScene& cs, size_t i, glm::vec3 p) {
    if (i >= cs.textures.size() || !cs.textures[i]) return 1.0f;
    const shd::VolumeData& v = cs.volumes[i];
    const shd::TextureCell c = shd::textureCell(v, p, cs.time);
    float factor = shd::textureDensityFactor(v, cs.textures[i]->sampleCorners(c.lo, c.hi, c.frac, v.textureParams.w));
    if (i < cs.details.size() && cs.details[i]) {
        const shd::TextureCell dc = shd::detailCell(v, p, cs.time);
        factor *= shd::detailDensityFactor(v, cs.details[i]->sampleCorners(dc.lo, dc.hi, dc.frac, v.detailParams.w));
    }
    return factor;
}

float volumeDensity(const CompiledScene& cs, size_t i, glm::vec3 p) {
    const float density = plainVolumeDensity(cs, i, p);
    return density > 0.0f ? density * densityTextureFactor(cs, i, p) : density;
}

shd::MediaSample mediaAt(const CompiledScene& cs, glm::vec3 p) {
    shd::MediaSample m = shd::emptyMedia();
    for (size_t i = 0; i < cs.volumes.size(); ++i) {
        if (!shd::insideBounds(cs.volumes[i], p)) continue;
        m = shd::addMedium(m, cs.volumes[i], volumeDensity(cs, i, p));
    }
    // Only where there is fog and some influencer or wake reaches (its box): the factor's cost
    // follows the froxels they touch.
    if (m.gWeight > 0.0f || m.sigmaT != glm::vec3(0.0f) || m.emission != glm::vec3(0.0f))
        if (shd::insideInfluenceBounds(cs.influence.header, p)) m = shd::influenceScaleMedia(m, influenceFactor(cs.influence, p));
    return m;
}

shd::Accumulated accumulateDistantPiece(const CompiledScene& cs, shd::Accumulated a, glm::vec3 dir, float s0, float s1) {
    const glm::vec3 middle = cs.cameraPosition + dir * std::sqrt(s0 * s1);
    // Ambient and emission first, then each directional light with its transmittance evaluated
    // once per piece (the GPU's distant_fog.comp in the same order).
    shd::DistantSegment seg = shd::emptyDistantSegment();
    for (const shd::VolumeData& v : cs.volumes) {
        const float len = shd::distantDensityLength(v, cs.cameraPosition, dir, s0, s1);
        seg = shd::addDistantVolume(seg, v, len, cs.ambient);
    }
    for (const shd::LightData& l : cs.lights) {
        if (l.kind.x != shd::LIGHT_DIRECTIONAL) continue;
        const glm::vec3 t = lightFogTransmittance(cs, l, middle, -glm::vec3(l.direction), shd::BRUME_HUGE, 0);
        for (const shd::VolumeData& v : cs.volumes) {
            const float len = shd::distantDensityLength(v, cs.cameraPosition, dir, s0, s1);
            seg = shd::addDistantLight(seg, v, len, shd::distantLightPerSigmaS(l, dir, v.sigmaS_g.w) * t);
        }
    }
    return shd::accumulateDistant(a, seg);
}

shd::Accumulated accumulateDistantFog(const CompiledScene& cs, shd::Accumulated a, glm::vec3 dir, float s0, float s1) {
    if (!(s1 > s0)) return a;
    const int pieces = shd::distantShadowPieceCount(s0, s1);
    for (int piece = 0; piece < pieces; ++piece) {
        const glm::vec2 b = shd::distantShadowPiece(s0, s1, piece, pieces);
        a = accumulateDistantPiece(cs, a, dir, b.x, b.y);
    }
    return a;
}

int distantFogEntries(const CompiledScene& cs, const shd::FrameUniforms& frame) {
    bool distant = false;
    for (const shd::VolumeData& v : cs.volumes) distant = distant || shd::distantFogKind(v.kind.x);
    return distant ? shd::distantTableEntries(frame) : 0;
}

shd::FrameUniforms makeFrameUniforms(const Scene& scene, const CompiledScene& cs, int width, int height,
                                     const FroxelSettings& fs, glm::vec3 jitter) {
    shd::FrameUniforms f{};
    const Camera& c = scene.camera;
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    const float tanY = std::tan(glm::radians(c.fov_y_deg) * 0.5f);
    f.viewFromWorld = c.viewFromWorld();
    f.worldFromView = glm::inverse(f.viewFromWorld);
    // Vulkan clip space: depth in [0,1], y down in framebuffer coordinates.
    glm::mat4 proj = glm::perspectiveRH_ZO(glm::radians(c.fov_y_deg), aspect, c.near, c.far);
    proj[1][1] *= -1.0f;
    f.clipFromView = proj;
    f.clipFromWorld = proj * f.viewFromWorld;
    f.cameraPosition = glm::vec4(c.position, 0.0f);
    f.ambient = glm::vec4(scene.ambient, cs.time);
    f.projection = glm::vec4(tanY * aspect, tanY, c.near, c.far);
    f.froxelRange = glm::vec4(fs.near, fs.far, fs.distribution, 0.0f);
    const glm::ivec3 dims = froxelGridDims(width, height, fs);
    f.froxelDims = glm::ivec4(dims, fs.tile_px);
    f.counts = glm::ivec4(width, height, static_cast<int>(cs.volumes.size()), static_cast<int>(cs.lights.size()));
    f.jitter = glm::vec4(jitter, 0.0f);
    return f;
}

}  // namespace brume
