// Brume's scene model: what a scene file holds, in memory. Defaults come from core/settings.h.
// Right-handed, Y up, meters. io/scene_json.* reads and writes it; core/compile.* turns it into
// the shared VolumeData/LightData arrays that both renderers evaluate.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "density_grid.h"
#include "keyframes.h"
#include "settings.h"

namespace brume {

constexpr glm::vec3 vec3Default(const Setting& s) {
    return {static_cast<float>(s.def[0]), static_cast<float>(s.def[1]), static_cast<float>(s.def[2])};
}

// world = T * R * S, R = Rz * Ry * Rx (rotation about world X first, then Y, then Z).
struct Transform {
    glm::vec3 translation = vec3Default(settings::transform_translation);
    glm::vec3 rotation_deg = vec3Default(settings::transform_rotation);
    glm::vec3 scale = vec3Default(settings::transform_scale);

    glm::mat4 worldFromLocal() const;
    glm::mat4 localFromWorld() const;
    bool operator==(const Transform&) const = default;
};

struct Camera {
    glm::vec3 position = vec3Default(settings::camera_position);
    glm::vec3 target = vec3Default(settings::camera_target);
    glm::vec3 up = vec3Default(settings::camera_up);
    float fov_y_deg = settings::camera_fov_y.f();
    float near = settings::camera_near.f();
    float far = settings::camera_far.f();

    glm::mat4 viewFromWorld() const;
    bool operator==(const Camera&) const = default;
};

enum class Quality { Low, Medium, High, Ultra };

struct RenderBlock {
    int width = settings::render_width.i();
    int height = settings::render_height.i();
    Quality quality = static_cast<Quality>(settings::render_quality.i());
    int frames = settings::render_frames.i();
    bool operator==(const RenderBlock&) const = default;
};

// Each present key overrides the quality preset's value.
struct FroxelOverrides {
    std::optional<int> tile_px;
    std::optional<int> slices;
    std::optional<float> near;
    std::optional<float> far;
    std::optional<float> distribution;
    bool operator==(const FroxelOverrides&) const = default;
};

struct Temporal {
    bool enabled = settings::temporal_enabled.b();
    float history_weight = settings::temporal_history_weight.f();
    bool operator==(const Temporal&) const = default;
};

enum class LightType { Directional, Point, Spot };

struct Light {
    LightType type = LightType::Directional;
    std::string name;
    glm::vec3 direction = vec3Default(settings::light_direction);  // normalized on load
    glm::vec3 position = vec3Default(settings::light_position);
    glm::vec3 color = vec3Default(settings::light_color);
    float intensity = settings::light_intensity_directional.f();
    float range = settings::light_range.f();
    bool shadows = settings::light_shadows_directional.b();
    float fog_scale = settings::light_fog_scale.f();
    float inner_deg = settings::light_inner_deg.f();
    float outer_deg = settings::light_outer_deg.f();
    // Settings that change with the scene time (core/animate.h); the fields above hold the values
    // without them (what the editor edits).
    std::vector<KeyTrack> keys;
    // Editor view state (brume-editor's hide): not in the scene format, never saved; the renderers
    // ignore it, the editor renders a copy without hidden objects (app/editor/view.h).
    bool hidden = false;
    bool operator==(const Light&) const = default;
};

// A light of the given type with that type's defaults.
Light makeLight(LightType type);

struct Medium {
    glm::vec3 scattering = vec3Default(settings::medium_scattering);
    glm::vec3 absorption = vec3Default(settings::medium_absorption);
    glm::vec3 emission = vec3Default(settings::medium_emission);
    float phase_g = settings::medium_phase_g.f();
    bool operator==(const Medium&) const = default;
};

// One layer of a density texture: a noise grid tiled through world space and scrolled over time that
// modulates a volume's density by 1 + strength (value / mean - 1) (docs/vdb.md, "Density textures").
// Sampled in world space, so adjacent volumes with the same texture meet without a seam.
struct TextureLayer {
    std::string file;  // as written in the scene
    std::string grid = "density";
    float tile_size_m = settings::texture_tile_size.f();
    glm::vec3 scroll_mps = vec3Default(settings::texture_scroll);
    float strength = settings::texture_strength.f();
    float exponent = settings::texture_exponent.f();  // contrast: each voxel's value^exponent
    // Loaded by io/vdb_import.h (loadSceneGrids), not serialized: the grid and its mean over the
    // active box (DensityGrid::activeBoxMean) of value^exponent. Null until loaded: an unloaded texture modulates nothing.
    DensityGridPtr density;
    float mean = 0.0f;
    bool operator==(const TextureLayer&) const = default;
};

// A volume's density texture (any volume type), with an optional detail layer: a second grid with
// its own tile, scroll, strength and exponent whose factor is multiplied in (layered noise).
struct DensityTexture : TextureLayer {
    std::optional<TextureLayer> detail;
    bool operator==(const DensityTexture&) const = default;
};

// A detail layer with the detail settings' defaults (core/settings.h texture_detail_*).
TextureLayer makeDetailLayer();

enum class VolumeType { Box, Height, Depth, Vdb, Mesh, Ellipsoid, Cylinder };

// Box, ellipsoid and cylinder: the shapes in a transformed unit cube (compiled to one GPU kind).
constexpr bool isLocalShape(VolumeType t) {
    return t == VolumeType::Box || t == VolumeType::Ellipsoid || t == VolumeType::Cylinder;
}
enum class HeightProfile { Exponential, Linear };

// One struct for every volume type; only the fields of its type are read and written.
struct Volume {
    VolumeType type = VolumeType::Box;
    std::string name;
    Transform transform;                                       // box, ellipsoid, cylinder, vdb, mesh
    float edge_fade = settings::volume_edge_fade.f();          // box, ellipsoid, cylinder
    float height_falloff = settings::volume_height_falloff.f();  // box, ellipsoid, cylinder, vdb, mesh
    float base_height = settings::volume_base_height.f();      // height
    HeightProfile profile = HeightProfile::Exponential;        // height
    float falloff = settings::volume_falloff.f();              // height, exponential
    float transition_height = settings::volume_transition_height.f();  // height, linear
    float visibility_distance = settings::volume_visibility_distance.f();  // depth
    float start_distance = settings::volume_start_distance.f();            // depth
    std::string file;                                          // vdb, mesh: as written in the scene
    float edge_fade_m = settings::volume_edge_fade_m.f();      // mesh
    std::string grid = "density";                              // vdb
    VdbEncoding encoding = VdbEncoding::Float;                 // vdb, the same for all of a scene's
    float density_scale = settings::volume_density_scale.f();  // vdb
    // vdb: the grid read from `file` by io/vdb_import.h (loadSceneGrids); mesh: the fog grid made from
    // the mesh (io/mesh_import.h), sampled like a vdb grid. Not serialized. Null until loaded: an
    // unloaded vdb or mesh volume is empty.
    DensityGridPtr density;
    std::optional<DensityTexture> density_texture;             // any type
    Medium medium;
    // Settings that change with the scene time (core/animate.h); the fields above hold the values
    // without them (what the editor edits).
    std::vector<KeyTrack> keys;
    // Editor view state (brume-editor's hide): not in the scene format, never saved; the renderers
    // ignore it, the editor renders a copy without hidden objects (app/editor/view.h).
    bool hidden = false;
    bool operator==(const Volume&) const = default;
};

enum class GeometryType { Plane, Box, Sphere };

struct Geometry {
    GeometryType type = GeometryType::Plane;
    std::string name;
    float height = settings::geometry_height.f();        // plane
    Transform transform;                                 // box: unit cube [-0.5,0.5]^3
    glm::vec3 center = vec3Default(settings::geometry_center);  // sphere
    float radius = settings::geometry_radius.f();        // sphere
    glm::vec3 albedo = vec3Default(settings::geometry_albedo);
    glm::vec3 emission = vec3Default(settings::geometry_emission);
    // Editor view state (brume-editor's hide): not in the scene format, never saved; the renderers
    // ignore it, the editor renders a copy without hidden objects (app/editor/view.h).
    bool hidden = false;
    bool operator==(const Geometry&) const = default;
};

enum class InfluencerType { Sphere, Capsule };

// A sphere or upright capsule moving along a path that thins every volume's fog and leaves a wake
// that recovers with a half-life (docs/scene-format.md, "Influencers"; core/influence.h).
struct Influencer {
    InfluencerType type = InfluencerType::Sphere;
    std::string name;
    float radius = settings::influencer_radius.f();
    float length = settings::influencer_length.f();  // capsule
    float strength = settings::influencer_strength.f();
    float wake_half_life_s = settings::influencer_half_life.f();
    float wake_step_s = settings::influencer_wake_step.f();
    int wake_samples = settings::influencer_wake_samples.i();
    // Target "position": the centre over time (at least 2 keys in increasing time; the reader checks).
    KeyTrack path;
    // Editor view state, like Volume::hidden: never saved, the editor renders a copy without it.
    bool hidden = false;
    bool operator==(const Influencer&) const = default;
};

struct Scene {
    int version = 1;
    Camera camera;
    RenderBlock render;
    FroxelOverrides froxels;
    Temporal temporal;
    glm::vec3 ambient = vec3Default(settings::ambient);
    std::vector<Light> lights;
    std::vector<Volume> volumes;
    std::vector<Geometry> geometry;
    std::vector<Influencer> influencers;
    // Folder of the scene file, for resolving relative paths (vdb files); not serialized.
    std::string baseDir;
    // Scene time [s] (density textures scroll with it, keyframes are evaluated at it): a render input (brume render --time), not
    // serialized and not compared.
    float time_s = 0.0f;
    bool operator==(const Scene& o) const {
        return version == o.version && camera == o.camera && render == o.render && froxels == o.froxels &&
               temporal == o.temporal && ambient == o.ambient && lights == o.lights && volumes == o.volumes &&
               geometry == o.geometry && influencers == o.influencers;
    }
};

const char* toString(Quality q);
const char* toString(LightType t);
const char* toString(VolumeType t);
const char* toString(HeightProfile p);
const char* toString(GeometryType t);
const char* toString(InfluencerType t);

}  // namespace brume
