// Every user-facing setting of the scene format, written once: JSON path, unit, default, range and
// help text. The scene parser validates against it, Scene's default member values come from it, the
// editor builds its widgets from it and `brume settings --markdown` prints the docs' table from it.
#pragma once

#include <array>
#include <span>
#include <string_view>

namespace brume {

enum class SettingKind { Number, Integer, Vec3, Bool, Choice, String };

struct Setting {
    std::string_view path;     // JSON path; "[]" is any element, "[type=x]" only elements of that type
    SettingKind kind;
    std::string_view unit;     // "" when unitless
    double min;                // inclusive range (each component of a Vec3)
    double max;
    std::array<double, 3> def; // default (components beyond the kind's count are ignored)
    std::string_view choices;  // Choice: alternatives separated by '|', first is not special
    std::string_view help;

    constexpr double value() const { return def[0]; }
    constexpr float f() const { return static_cast<float>(def[0]); }
    constexpr int i() const { return static_cast<int>(def[0]); }
    constexpr bool b() const { return def[0] != 0.0; }
};

namespace settings {

using K = SettingKind;
inline constexpr double kBig = 1.0e6;     // positions and distances
inline constexpr double kCoef = 1.0e9;    // medium coefficients [1/m]

// clang-format off
inline constexpr Setting camera_position  {"camera.position", K::Vec3, "m", -kBig, kBig, {0, 1.5, 6}, "", "Camera position in world space."};
inline constexpr Setting camera_target    {"camera.target", K::Vec3, "m", -kBig, kBig, {0, 0, 0}, "", "Point the camera looks at; must differ from the position."};
inline constexpr Setting camera_up        {"camera.up", K::Vec3, "", -1, 1, {0, 1, 0}, "", "Up direction; must not be parallel to the view direction."};
inline constexpr Setting camera_fov_y     {"camera.fov_y_deg", K::Number, "deg", 1, 179, {60}, "", "Vertical field of view."};
inline constexpr Setting camera_near      {"camera.near", K::Number, "m", 1e-4, 1e4, {0.1}, "", "Near clip distance (view depth)."};
inline constexpr Setting camera_far       {"camera.far", K::Number, "m", 1e-3, 1e7, {100}, "", "Far clip distance (view depth); fog and geometry end here, beyond is the ambient sky. Must exceed near."};

inline constexpr Setting render_width     {"render.width", K::Integer, "px", 1, 16384, {640}, "", "Image width."};
inline constexpr Setting render_height    {"render.height", K::Integer, "px", 1, 16384, {360}, "", "Image height."};
inline constexpr Setting render_quality   {"render.quality", K::Choice, "", 0, 0, {2}, "low|medium|high|ultra", "Froxel quality preset (see docs/quality.md)."};
inline constexpr Setting render_frames    {"render.frames", K::Integer, "", 1, 1024, {1}, "", "Frames brume render accumulates (temporal) when --frames is not given; the editor's Quality panel sets it with the preset."};

inline constexpr Setting froxels_tile_px  {"froxels.tile_px", K::Integer, "px", 1, 64, {8}, "", "Screen tile covered by one froxel column (overrides the preset)."};
inline constexpr Setting froxels_slices   {"froxels.slices", K::Integer, "", 1, 1024, {64}, "", "Number of depth slices (overrides the preset)."};
inline constexpr Setting froxels_near     {"froxels.near", K::Number, "m", 1e-4, 1e6, {0.1}, "", "View depth where slice 0 begins (overrides the preset; default: camera near)."};
inline constexpr Setting froxels_far      {"froxels.far", K::Number, "m", 1e-3, 1e7, {64}, "", "View depth where the last slice ends (overrides the preset; clamped to camera far)."};
inline constexpr Setting froxels_distribution {"froxels.distribution", K::Number, "", 0.1, 8, {2}, "", "Slice distribution exponent k: z(t) = near + (far - near) t^k; 1 = even, larger = more slices near the camera."};

inline constexpr Setting temporal_enabled {"temporal.enabled", K::Bool, "", 0, 1, {1}, "", "Blend each frame with the reprojected previous one."};
inline constexpr Setting temporal_history_weight {"temporal.history_weight", K::Number, "", 0, 0.99, {0.9}, "", "Weight of the history in the blend."};

inline constexpr Setting ambient          {"ambient", K::Vec3, "W/(m^2 sr)", 0, kBig, {0, 0, 0}, "", "Constant radiance arriving from every direction (sky); lights fog and surfaces unshadowed."};

inline constexpr Setting light_type       {"lights[].type", K::Choice, "", 0, 0, {0}, "directional|point|spot", "Kind of light; required."};
inline constexpr Setting light_name       {"lights[].name", K::String, "", 0, 0, {0}, "", "Name shown in the editor."};
inline constexpr Setting light_direction  {"lights[].direction", K::Vec3, "", -1, 1, {0.3, -1, 0.2}, "", "Direction the light travels (directional, spot); normalized on load, must not be zero."};
inline constexpr Setting light_position   {"lights[].position", K::Vec3, "m", -kBig, kBig, {0, 2, 0}, "", "Light position (point, spot)."};
inline constexpr Setting light_color      {"lights[].color", K::Vec3, "", 0, kBig, {1, 1, 1}, "", "Color multiplier of the intensity."};
inline constexpr Setting light_intensity_directional {"lights[type=directional].intensity", K::Number, "W/m^2", 0, kBig, {3}, "", "Irradiance on a surface facing the light."};
inline constexpr Setting light_intensity_local {"lights[type=point|spot].intensity", K::Number, "W/sr", 0, kBig, {20}, "", "Radiant intensity on the axis; falls off with the inverse square of distance."};
inline constexpr Setting light_range      {"lights[].range", K::Number, "m", 0, kBig, {0}, "", "Distance where a smooth window (1 - (d/range)^4)^2 reaches zero; 0 = no window (point, spot)."};
inline constexpr Setting light_shadows_directional {"lights[type=directional].shadows", K::Bool, "", 0, 1, {1}, "", "Casts shadows."};
inline constexpr Setting light_shadows_local {"lights[type=point|spot].shadows", K::Bool, "", 0, 1, {0}, "", "Casts shadows."};
inline constexpr Setting light_fog_scale  {"lights[].fog_scale", K::Number, "", 0, 100, {1}, "", "Multiplies the light's effect on fog only; 0 = does not light fog."};
inline constexpr Setting light_inner_deg  {"lights[type=spot].inner_deg", K::Number, "deg", 0, 179, {20}, "", "Half-angle of full intensity; must not exceed outer_deg."};
inline constexpr Setting light_outer_deg  {"lights[type=spot].outer_deg", K::Number, "deg", 0, 179, {30}, "", "Half-angle where the cone reaches zero (smoothstep on the cosine in between)."};

inline constexpr Setting volume_type      {"volumes[].type", K::Choice, "", 0, 0, {0}, "box|height|depth|vdb|mesh|ellipsoid|cylinder", "Kind of fog volume; required."};
inline constexpr Setting volume_name      {"volumes[].name", K::String, "", 0, 0, {0}, "", "Name shown in the editor."};
inline constexpr Setting volume_edge_fade {"volumes[type=box|ellipsoid|cylinder].edge_fade", K::Number, "", 0, 1, {0.1}, "", "Fraction of the half-size over which density fades to 0 at the faces (ellipsoid, cylinder: the surface); 0 = hard edge."};
inline constexpr Setting volume_height_falloff {"volumes[type=box|ellipsoid|cylinder|vdb|mesh].height_falloff", K::Number, "1/m", 0, 1000, {0}, "", "Density x exp(-height_falloff * (y - bottom)), bottom = the volume's lowest world point (vdb, mesh: the bottom of the grid's bounds); 0 = uniform."};
inline constexpr Setting volume_base_height {"volumes[type=height].base_height", K::Number, "m", -kBig, kBig, {0}, "", "Height below which density is 1."};
inline constexpr Setting volume_profile   {"volumes[type=height].profile", K::Choice, "", 0, 0, {0}, "exponential|linear", "Density profile above base_height."};
inline constexpr Setting volume_falloff   {"volumes[type=height].falloff", K::Number, "1/m", 0, 1000, {0.5}, "", "Exponential profile: density exp(-falloff * (y - base_height))."};
inline constexpr Setting volume_transition_height {"volumes[type=height].transition_height", K::Number, "m", 1e-3, kBig, {2}, "", "Linear profile: height above base_height where density reaches 0."};
inline constexpr Setting volume_visibility_distance {"volumes[type=depth].visibility_distance", K::Number, "m", 1e-3, 1e7, {50}, "", "Distance over which density rises to 95% (1 - exp(-3))."};
inline constexpr Setting volume_start_distance {"volumes[type=depth].start_distance", K::Number, "m", 0, 1e7, {0}, "", "Distance from the camera where depth fog begins."};
inline constexpr Setting volume_file      {"volumes[type=vdb].file", K::String, "", 0, 0, {0}, "", "OpenVDB file, relative to the scene file's folder. Required."};
inline constexpr Setting volume_grid      {"volumes[type=vdb].grid", K::String, "", 0, 0, {0}, "", "Grid name in the file (default: density)."};
inline constexpr Setting volume_encoding  {"volumes[type=vdb].encoding", K::Choice, "", 0, 0, {0}, "float|fp16|fp8", "How the grid's values are stored once loaded (CPU and GPU): float (32 bits a voxel), fp16 or fp8 (16 or 8 bits, quantized per 8^3 leaf between its min and max: about 55% and 32% of float's memory; image error against float 6e-7 and 7e-5 on gaffer_smoke). All vdb volumes of a scene use the same encoding (docs/vdb.md)."};
inline constexpr Setting volume_density_scale {"volumes[type=vdb].density_scale", K::Number, "", 0, kBig, {1}, "", "Multiplies the grid's values."};

inline constexpr Setting volume_mesh_file {"volumes[type=mesh].file", K::String, "", 0, 0, {0}, "", "Closed triangle mesh (Wavefront OBJ), relative to the scene file's folder, turned into a fog grid inside its surface at load (a fog hull; docs/vdb.md, \"Mesh fog hulls\"). Required. A mesh with holes (an edge of an odd number of triangles), no triangles, a non-finite vertex or more than 2,000,000 triangles is refused."};
inline constexpr Setting volume_edge_fade_m {"volumes[type=mesh].edge_fade_m", K::Number, "m", 0, kBig, {0.1}, "", "Depth inside the mesh's surface over which density rises from 0 to 1 (smoothstep of the distance to the surface, in the mesh's own units, before the transform's scale); 0 = hard edge (a one-voxel ramp centred on the surface). Sets the voxel size: edge_fade_m / 4, between 1/128 and 1/32 of the mesh's longest side."};
inline constexpr Setting texture_file     {"volumes[].density_texture.file", K::String, "", 0, 0, {0}, "", "OpenVDB file of a noise grid tiled through world space that modulates the volume's density, relative to the scene file's folder. Required in density_texture (docs/vdb.md)."};
inline constexpr Setting texture_grid     {"volumes[].density_texture.grid", K::String, "", 0, 0, {0}, "", "Grid name in the texture file (default: density; the same choice rules as a vdb volume's grid)."};
inline constexpr Setting texture_tile_size {"volumes[].density_texture.tile_size_m", K::Number, "m", 1e-3, kBig, {10}, "", "Edge of the cube in world space that one copy of the grid's active box fills; the grid repeats every tile_size_m along X, Y and Z."};
inline constexpr Setting texture_scroll   {"volumes[].density_texture.scroll_mps", K::Vec3, "m/s", -kBig, kBig, {0, 0, 0}, "", "Wind: the texture moves by scroll_mps x time (brume render --time, --fps)."};
inline constexpr Setting texture_strength {"volumes[].density_texture.strength", K::Number, "", 0, 100, {1}, "", "density x max(0, 1 + strength (texture / mean - 1)), mean = the grid's mean over its active box: 0 = the plain volume, 1 = density x texture / mean (same mean density), > 1 = more contrast."};
inline constexpr Setting texture_exponent {"volumes[].density_texture.exponent", K::Number, "", 0, 100, {1}, "", "Contrast: each voxel's value is raised to this power before the strength rule (and the mean is that of value^exponent, so strength 0 is still the plain volume); 1 = the grid as it is, > 1 sharper wisps."};
inline constexpr Setting detail_file      {"volumes[].density_texture.detail.file", K::String, "", 0, 0, {0}, "", "Detail layer (optional object in density_texture): OpenVDB file of a second noise grid whose factor multiplies the texture's, relative to the scene file's folder. Required in detail."};
inline constexpr Setting detail_grid      {"volumes[].density_texture.detail.grid", K::String, "", 0, 0, {0}, "", "Grid name in the detail file (default: density)."};
inline constexpr Setting detail_tile_size {"volumes[].density_texture.detail.tile_size_m", K::Number, "m", 1e-3, kBig, {2.5}, "", "Edge of the world cube one copy of the detail grid fills (usually smaller than the texture's tile: finer noise)."};
inline constexpr Setting detail_scroll    {"volumes[].density_texture.detail.scroll_mps", K::Vec3, "m/s", -kBig, kBig, {0, 0, 0}, "", "Wind of the detail layer: it moves by scroll_mps x time, independently of the texture."};
inline constexpr Setting detail_strength  {"volumes[].density_texture.detail.strength", K::Number, "", 0, 100, {1}, "", "The detail's factor max(0, 1 + strength (detail / mean - 1)) multiplies the texture's; 0 = no detail (the texture alone), 1 = same mean density."};
inline constexpr Setting detail_exponent  {"volumes[].density_texture.detail.exponent", K::Number, "", 0, 100, {1}, "", "Contrast of the detail layer: each voxel's value^exponent before its strength rule (its mean is that of value^exponent)."};
inline constexpr Setting transform_translation {"*.transform.translation", K::Vec3, "m", -kBig, kBig, {0, 0, 0}, "", "Translation."};
inline constexpr Setting transform_rotation {"*.transform.rotation_deg", K::Vec3, "deg", -36000, 36000, {0, 0, 0}, "", "Rotation about world X, then Y, then Z."};
inline constexpr Setting transform_scale  {"*.transform.scale", K::Vec3, "", 1e-4, kBig, {1, 1, 1}, "", "Scale along the local axes (box volumes and geometry: the unit cube's edge lengths; ellipsoid: its diameters; cylinder: diameters along X and Z, height along Y)."};

inline constexpr Setting medium_scattering {"volumes[].medium.scattering", K::Vec3, "1/m", 0, kCoef, {0.1, 0.1, 0.1}, "", "Scattering coefficient sigma_s at density 1."};
inline constexpr Setting medium_absorption {"volumes[].medium.absorption", K::Vec3, "1/m", 0, kCoef, {0.01, 0.01, 0.01}, "", "Absorption coefficient sigma_a at density 1."};
inline constexpr Setting medium_emission  {"volumes[].medium.emission", K::Vec3, "W/(m^2 sr m)", 0, kBig, {0, 0, 0}, "", "Radiance emitted per meter of path at density 1."};
inline constexpr Setting medium_phase_g   {"volumes[].medium.phase_g", K::Number, "", -1, 1, {0.2}, "", "Henyey-Greenstein anisotropy: > 0 forward, < 0 backward; evaluated with |g| <= 0.999."};

inline constexpr Setting keys_interpolation {"*.keys.*.interpolation", K::Choice, "", 0, 0, {0}, "linear|smooth", "How a keyed setting moves between its keys: straight lines, or smooth (a Catmull-Rom curve through the keys, clamped to the setting's range). A key list written as a plain array is linear (docs/scene-format.md, Keyframes)."};
inline constexpr Setting keys_time        {"*.keys.*[].time", K::Number, "s", -kBig, kBig, {0}, "", "Scene time of a key; the keys of a list in strictly increasing time. Before the first key and after the last the setting holds that key's value."};
inline constexpr Setting keys_value       {"*.keys.*[].value", K::Number, "", -kCoef, kCoef, {0}, "", "The keyed setting's value at that time: a number or an array of 3 like the setting itself, with its unit and within its range."};

inline constexpr Setting influencer_type  {"influencers[].type", K::Choice, "", 0, 0, {0}, "sphere|capsule", "Shape that thins the fog it passes through (docs/scene-format.md, Influencers); required. A capsule stands upright: its axis runs along world Y, centred on the path position."};
inline constexpr Setting influencer_name  {"influencers[].name", K::String, "", 0, 0, {0}, "", "Name shown in the editor."};
inline constexpr Setting influencer_radius {"influencers[].radius", K::Number, "m", 1e-3, kBig, {1}, "", "Radius of the sphere, or of the capsule around its axis; the thinning falls off smoothly from the centre (axis) to 0 at this distance: 1 - smoothstep(0, 1, distance / radius)."};
inline constexpr Setting influencer_length {"influencers[type=capsule].length", K::Number, "m", 0, kBig, {2}, "", "Length of the capsule's upright axis (its height is length + 2 radius)."};
inline constexpr Setting influencer_strength {"influencers[].strength", K::Number, "", 0, 1, {1}, "", "Every volume's density is multiplied by 1 - strength x falloff: 1 empties the fog at the centre, 0 leaves it."};
inline constexpr Setting influencer_half_life {"influencers[].wake_half_life_s", K::Number, "s", 0, 1e4, {1}, "", "Where the influencer has passed, its thinning decays by half every wake_half_life_s (the fog flows back); 0 = no wake."};
inline constexpr Setting influencer_wake_step {"influencers[].wake_step_s", K::Number, "s", 1e-3, 100, {0.05}, "", "The wake is the influencer's shape at the scene times that are multiples of this step (not the frame times, so any frame renders alone); a larger step when wake_samples would not cover the live wake (until strength x 2^(-age / half-life) < 0.001)."};
inline constexpr Setting influencer_wake_samples {"influencers[].wake_samples", K::Integer, "", 0, 1024, {64}, "", "Most past positions the wake holds; the step grows to wake half-life x log2(strength / 0.001) / wake_samples when that exceeds wake_step_s. Cost: each froxel in the wake's box evaluates them all."};
inline constexpr Setting influencer_path_interpolation {"influencers[].path_interpolation", K::Choice, "", 0, 0, {0}, "linear|smooth", "How the influencer moves between its path points: straight lines, or smooth (Catmull-Rom through the points, like keys)."};
inline constexpr Setting influencer_path_time {"influencers[].path[].time", K::Number, "s", -kBig, kBig, {0}, "", "Scene time of a path point; at least 2 points, in strictly increasing time. Before the first and after the last the influencer holds that point's position."};
inline constexpr Setting influencer_path_position {"influencers[].path[].position", K::Vec3, "m", -kBig, kBig, {0, 0, 0}, "", "Centre of the sphere (capsule) at that time."};

inline constexpr Setting geometry_type    {"geometry[].type", K::Choice, "", 0, 0, {0}, "plane|box|sphere", "Kind of surface; required."};
inline constexpr Setting geometry_name    {"geometry[].name", K::String, "", 0, 0, {0}, "", "Name shown in the editor."};
inline constexpr Setting geometry_height  {"geometry[type=plane].height", K::Number, "m", -kBig, kBig, {0}, "", "Height of the horizontal plane (normal +Y)."};
inline constexpr Setting geometry_center  {"geometry[type=sphere].center", K::Vec3, "m", -kBig, kBig, {0, 1, 0}, "", "Sphere centre."};
inline constexpr Setting geometry_radius  {"geometry[type=sphere].radius", K::Number, "m", 1e-4, kBig, {1}, "", "Sphere radius."};
inline constexpr Setting geometry_albedo  {"geometry[].albedo", K::Vec3, "", 0, 1, {0.5, 0.5, 0.5}, "", "Lambertian reflectance."};
inline constexpr Setting geometry_emission {"geometry[].emission", K::Vec3, "W/(m^2 sr)", 0, kBig, {0, 0, 0}, "", "Radiance the surface emits (light panels, backdrops); it lights nothing else."};
// clang-format on

inline constexpr std::array kAll = {
    &camera_position, &camera_target, &camera_up, &camera_fov_y, &camera_near, &camera_far,
    &render_width, &render_height, &render_quality, &render_frames,
    &froxels_tile_px, &froxels_slices, &froxels_near, &froxels_far, &froxels_distribution,
    &temporal_enabled, &temporal_history_weight, &ambient,
    &light_type, &light_name, &light_direction, &light_position, &light_color,
    &light_intensity_directional, &light_intensity_local, &light_range, &light_shadows_directional,
    &light_shadows_local, &light_fog_scale, &light_inner_deg, &light_outer_deg,
    &volume_type, &volume_name, &volume_edge_fade, &volume_height_falloff, &volume_base_height, &volume_profile, &volume_falloff,
    &volume_transition_height, &volume_visibility_distance, &volume_start_distance, &volume_file,
    &volume_grid, &volume_encoding, &volume_density_scale, &volume_mesh_file, &volume_edge_fade_m, &texture_file, &texture_grid, &texture_tile_size, &texture_scroll,
    &texture_strength, &texture_exponent, &detail_file, &detail_grid, &detail_tile_size, &detail_scroll,
    &detail_strength, &detail_exponent, &transform_translation, &transform_rotation, &transform_scale,
    &medium_scattering, &medium_absorption, &medium_emission, &medium_phase_g,
    &keys_interpolation, &keys_time, &keys_value,
    &influencer_type, &influencer_name, &influencer_radius, &influencer_length, &influencer_strength,
    &influencer_half_life, &influencer_wake_step, &influencer_wake_samples, &influencer_path_interpolation,
    &influencer_path_time, &influencer_path_position,
    &geometry_type, &geometry_name, &geometry_height, &geometry_center, &geometry_radius, &geometry_albedo,
    &geometry_emission,
};

// Options of `brume render` that are not scene keys (so not in kAll, which is the scene format).
// clang-format off
inline constexpr Setting cli_exposure     {"--exposure", K::Number, "", 1e-6, 1e6, {1}, "", "Multiplies radiance before the PNG tone curve; EXR is written linear and unscaled."};
inline constexpr Setting cli_frames       {"--frames", K::Integer, "", 1, 1024, {1}, "", "Frames rendered with temporal accumulation; the last is written (froxel renderers; the reference ignores it)."};
inline constexpr Setting cli_debug_view   {"--debug-view", K::Choice, "", 0, 0, {0}, "final|density|scattering|transmittance", "Froxel renderers: write one depth slice of a froxel volume instead of the image: density (sigma_t, log ramp 0.001..100 1/m), scattering (S, log ramp 1e-4..100 radiance/m) or transmittance (grey 0..1); PNG without exposure or tone curve (docs/cli.md)."};
inline constexpr Setting cli_debug_slice  {"--debug-slice", K::Integer, "", 0, 4095, {0}, "", "Froxel depth slice the debug view shows (0 = nearest the camera); clamped to the grid's last slice."};
inline constexpr Setting cli_orbit        {"--orbit", K::Number, "deg", -180, 180, {0}, "", "Camera path for --frames: frame n turns the camera by n times this about its target (axis: camera.up); 0 = static."};
inline constexpr Setting cli_time         {"--time", K::Number, "s", -kBig, kBig, {0}, "", "Scene time of the image written: density textures have scrolled by scroll_mps x time."};
inline constexpr Setting cli_fps          {"--fps", K::Number, "1/s", 1e-3, 1000, {24}, "", "Frame rate of --frames: frame n of N is at time - (N - 1 - n) / fps, so the last (written) frame is at --time."};
// brume-editor options.
inline constexpr Setting editor_interactive_scale {"--interactive-scale", K::Number, "", 0.1, 1, {0.5}, "", "Viewport resolution while the user drags or moves the camera, as a fraction of the window's (rendered at the low preset, then upscaled); 1 renders every frame at full resolution and the chosen preset."};
inline constexpr Setting editor_frame_budget_ms {"--frame-budget-ms", K::Number, "ms", 0, 1000, {50}, "", "Frame time the viewport aims at while the user interacts: each coarse frame's resolution (at most --interactive-scale of the window's, at least 0.1) follows the measured time of the previous one; 0 keeps it at --interactive-scale."};
inline constexpr Setting editor_autosave_seconds {"--autosave-seconds", K::Number, "s", 0.1, 3600, {5}, "", "Longest time unsaved changes wait before the editor writes them to its recovery file."};
inline constexpr Setting cli_vdb_memory   {"--vdb-memory-mb", K::Integer, "MiB", 1, 1048576, {4096}, "", "Largest OpenVDB grid accepted, in memory and as NanoVDB (GPU); bigger grids are refused."};
// brume noise options.
inline constexpr Setting noise_size       {"--size", K::Integer, "voxels", 8, 256, {64}, "", "Voxels per side of the noise tile (the grid is size^3, every voxel active)."};
inline constexpr Setting noise_octaves    {"--octaves", K::Integer, "", 1, 8, {4}, "", "fBm octaves: octave o has 2^o times the first octave's cells and half the previous octave's amplitude."};
inline constexpr Setting noise_frequency  {"--frequency", K::Integer, "cells/tile", 1, 64, {4}, "", "Noise lattice cells per tile side in the first octave (an integer, so the tile is periodic)."};
inline constexpr Setting noise_seed       {"--seed", K::Integer, "", 0, 999999, {1}, "", "Random seed: the same seed gives the same noise, another seed other noise."};
inline constexpr Setting noise_grid       {"--grid", K::String, "", 0, 0, {0}, "", "Name of the grid written (the density_texture's grid key)."};
// Preset files (io/preset.h, docs/presets.md): their keys besides the scene's ambient, lights and volumes.
inline constexpr Setting preset_name      {"name", K::String, "", 0, 0, {0}, "", "Name of the look shown in preset lists and the editor; required, not empty."};
inline constexpr Setting preset_description {"description", K::String, "", 0, 0, {0}, "", "One or two sentences on the look (default: empty)."};
inline constexpr Setting preset_tags      {"tags", K::String, "", 0, 0, {0}, "", "Array of short words to filter by (default: none)."};
// brume preset options.
inline constexpr Setting cli_thumbnail_width  {"--thumbnail-width", K::Integer, "px", 16, 1024, {160}, "", "Width of the thumbnail PNG written beside the preset."};
inline constexpr Setting cli_thumbnail_height {"--thumbnail-height", K::Integer, "px", 9, 1024, {90}, "", "Height of the thumbnail PNG written beside the preset."};
// brume bake options.
inline constexpr Setting cli_voxel_size   {"--voxel-size", K::Number, "m", 1e-4, 1e4, {0.1}, "", "Edge of a baked voxel; voxel (i, j, k) is centred at (i, j, k) x voxel size in world space. Required."};
inline constexpr Setting cli_bounds       {"--bounds", K::Number, "m", -kBig, kBig, {0}, "", "World box XMIN YMIN ZMIN XMAX YMAX ZMAX the bake is clipped to; required when a height or depth fog (unbounded) is baked."};
inline constexpr Setting cli_threads      {"--threads", K::Integer, "", 0, 1024, {0}, "", "CPU worker threads; 0 = every core."};
// clang-format on

}  // namespace settings
}  // namespace brume
