// Point and spot light shadow maps on the host (shaders/shared/local_shadow.h): built by ray
// casting the preview geometry from each mapped light through its faces' texel centres, sampled
// with the shared PCF. The CPU froxel renderer samples them directly; the GPU renderer uploads the
// same array, so both see the same bits.
#pragma once

#include <vector>

#include "compile.h"
#include "geometry.h"
#include "quality.h"

namespace brume {

// Texels per side of each face at this quality (docs/shadows.md, "Point and spot shadow maps").
int localShadowMapResolution(Quality q);

// Every mapped light's faces: slot s (LightData.kind.z - 1) starts at s * LOCAL_SHADOW_FACES * N^2;
// a spot's single face uses the first N^2 of its slot. Empty when no light is mapped.
struct LocalShadowMaps {
    int resolution = 0;
    std::vector<float> depth;
};

// Number of slots compileScene handed out (the highest LightData.kind.z).
int localShadowSlots(const CompiledScene& cs);

// Ray casts the faces of one mapped light into its slot of maps.depth (sized by the caller).
void buildLocalShadowMap(const shd::LightData& light, const GeometrySet& geometry, LocalShadowMaps& maps,
                         int threads);

LocalShadowMaps buildLocalShadowMaps(const CompiledScene& cs, const GeometrySet& geometry, int resolution,
                                     int threads);

// The last maps built, each light's rebuilt only when the geometry, the resolution or what of that
// light the map depends on (kind, position, direction, cone) changes: intensity, colour, range and
// fog edits in the editor do not pay for the ray cast.
class LocalShadowCache {
public:
    const LocalShadowMaps& get(const CompiledScene& cs, const std::vector<Geometry>& geometry, int resolution,
                               int threads);
    int builds() const { return builds_; }  // light maps ray cast so far

private:
    LocalShadowMaps maps_;
    std::vector<shd::LightData> lights_;  // the mapped lights of the last build, by slot
    std::vector<Geometry> geometry_;
    int builds_ = 0;
};

// Visibility of light l at p through its map: 1 for unmapped lights.
float localShadowVisibility(const LocalShadowMaps& maps, const shd::LightData& l, glm::vec3 p);

}  // namespace brume
