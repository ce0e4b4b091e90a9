#include "blender_export.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>

#include <glm/gtc/matrix_transform.hpp>

#include "core/compile.h"
#include <nlohmann/json.hpp>

#include "io/fog_bake.h"

namespace brume {
namespace {

using ojson = nlohmann::ordered_json;
namespace fs = std::filesystem;

// Blender is Z up: Brume's (x, y, z) is Blender's (x, -z, y).
const glm::mat4 kBlenderFromBrume(glm::vec4(1, 0, 0, 0), glm::vec4(0, 0, 1, 0), glm::vec4(0, -1, 0, 0), glm::vec4(0, 0, 0, 1));

glm::vec3 toBlender(glm::vec3 p) { return {p.x, -p.z, p.y}; }

ojson vec(glm::vec3 v) { return ojson::array({v.x, v.y, v.z}); }

// Rows of a 4x4 matrix (mathutils.Matrix takes rows).
ojson rows(const glm::mat4& m) {
    ojson r = ojson::array();
    for (int row = 0; row < 4; ++row) r.push_back(ojson::array({m[0][row], m[1][row], m[2][row], m[3][row]}));
    return r;
}

// A Blender-space frame at `origin` (Brume space) whose -Z is `forward` and +Y as close to `up` as can be.
glm::mat4 lookFrame(glm::vec3 origin, glm::vec3 forward, glm::vec3 up) {
    const glm::vec3 z = -glm::normalize(toBlender(forward));
    glm::vec3 u = toBlender(up);
    if (glm::length(glm::cross(u, z)) < 1.0e-4f) u = std::abs(z.z) < 0.9f ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
    const glm::vec3 x = glm::normalize(glm::cross(u, z));
    const glm::vec3 y = glm::cross(z, x);
    return glm::mat4(glm::vec4(x, 0), glm::vec4(y, 0), glm::vec4(z, 0), glm::vec4(toBlender(origin), 1));
}

std::string label(const char* list, size_t i, const std::string& name) {
    return std::string(list) + "[" + std::to_string(i) + "]" + (name.empty() ? "" : " \"" + name + "\"");
}

// Principled Volume: sigma_s = density color, sigma_a = density (1 - color) (1 - sqrt(absorption_color)),
// so with density = the largest sigma_t channel both match Brume's per channel.
ojson principled(const Medium& m) {
    const glm::vec3 sigmaT = m.scattering + m.absorption;
    const float d = std::max({sigmaT.x, sigmaT.y, sigmaT.z});
    glm::vec3 color(0.0f), absorptionColor(0.0f);
    for (int c = 0; c < 3; ++c) {
        if (d <= 0.0f) break;
        color[c] = m.scattering[c] / d;
        const float rest = d - m.scattering[c];  // >= sigma_a[c]
        const float t = rest > 0.0f ? 1.0f - m.absorption[c] / rest : 0.0f;
        absorptionColor[c] = std::clamp(t, 0.0f, 1.0f) * std::clamp(t, 0.0f, 1.0f);
    }
    const float e = std::max({m.emission.x, m.emission.y, m.emission.z});
    ojson j;
    j["density"] = d;
    j["color"] = vec(color);
    j["absorption_color"] = vec(absorptionColor);
    j["anisotropy"] = m.phase_g;
    j["emission_strength"] = e;
    j["emission_color"] = vec(e > 0.0f ? m.emission / e : glm::vec3(0.0f));
    return j;
}

std::string absolutePath(const std::string& baseDir, const std::string& file) {
    const fs::path p(file);
    if (p.is_absolute() || baseDir.empty()) return p.lexically_normal().string();
    return (fs::path(baseDir) / p).lexically_normal().string();
}

// Comment lines must stay one line whatever a name holds.
std::string oneLine(std::string s) {
    for (char& c : s)
        if (c == '\n' || c == '\r') c = ' ';
    return s;
}

extern const char* const kScript;

}  // namespace

Result<std::map<size_t, std::string>> bakeTexturedVolumes(const Scene& scene, const std::string& scriptPath,
                                                         const std::string& sceneName) {
    std::map<size_t, std::string> files;
    std::error_code ec;
    const fs::path script = fs::absolute(scriptPath, ec).lexically_normal();
    for (size_t i = 0; i < scene.volumes.size(); ++i) {
        const Volume& v = scene.volumes[i];
        const glm::vec3 sigmaT = v.medium.scattering + v.medium.absorption;
        if (!v.density_texture || !v.density_texture->density || sigmaT.x + sigmaT.y + sigmaT.z <= 0.0f) continue;
        if (v.type != VolumeType::Box && v.type != VolumeType::Vdb) continue;
        Scene one = scene;
        one.volumes = {v};
        BakeOptions options;
        options.voxelSize = v.density_texture->tile_size_m / 64.0f;
        if (v.density_texture->detail)  // the finer of the two layers sets the voxel
            options.voxelSize = std::min(options.voxelSize, v.density_texture->detail->tile_size_m / 64.0f);
        Result<WorldBox> box = bakeBox(one, options, sceneName);
        if (!box) return box.error();
        const glm::vec3 size = box.value().max - box.value().min;
        const double voxels = double(size.x) * double(size.y) * double(size.z) / std::pow(double(options.voxelSize), 3.0);
        if (voxels > double(1 << 24)) options.voxelSize *= static_cast<float>(std::cbrt(voxels / double(1 << 24)));
        const std::string path =
            (script.parent_path() / (script.stem().string() + "_volume" + std::to_string(i) + ".vdb")).string();
        Result<BakeResult> r = bakeFogVdb(one, options, sceneName, path);
        if (!r) return r.error();
        files[i] = path;
    }
    return files;
}

BlenderExport exportBlender(const FogSource& source, const std::map<size_t, std::string>& baked) {
    const Scene& s = source.scene;
    BlenderExport out;
    ojson data;
    data["name"] = source.name;
    data["width"] = s.render.width;
    data["height"] = s.render.height;
    data["ambient"] = vec(s.ambient);
    // Unbounded fog (height, depth) fills a cube this far around the camera: Brume's ends at camera.far.
    const float extent = source.isPreset ? 200.0f : s.camera.far;
    data["extent_center"] = vec(toBlender(source.isPreset ? glm::vec3(0.0f) : s.camera.position));
    data["extent"] = extent;
    if (!source.isPreset) {
        const Camera& c = s.camera;
        data["camera"] = {{"matrix", rows(lookFrame(c.position, c.target - c.position, c.up))},
                          {"fov_y_deg", c.fov_y_deg}, {"near", c.near}, {"far", c.far}};
    } else {
        data["camera"] = nullptr;
    }
    if (glm::length(s.ambient) > 0.0f)
        out.losses.push_back("ambient: Brume's ambient lights fog and surfaces unshadowed; Blender's world light is "
                             "shadowed by geometry and attenuated by fog (approximate).");

    ojson volumes = ojson::array();
    for (size_t i = 0; i < s.volumes.size(); ++i) {
        const Volume& v = s.volumes[i];
        ojson j = principled(v.medium);
        j["name"] = v.name.empty() ? "Volume" + std::to_string(i) : v.name;
        switch (v.type) {
            case VolumeType::Box:
            case VolumeType::Ellipsoid:
            case VolumeType::Cylinder:
                j["kind"] = "box";
                j["shape"] = toString(v.type);
                j["matrix"] = rows(kBlenderFromBrume * v.transform.worldFromLocal());
                j["edge_fade"] = v.edge_fade;
                j["height_falloff"] = v.height_falloff;
                j["bottom"] = compileVolume(v).worldMin.y;  // Brume's lowest world y: Blender's world z
                break;
            case VolumeType::Height:
                j["kind"] = v.profile == HeightProfile::Exponential ? "height_exponential" : "height_linear";
                j["base_height"] = v.base_height;
                j["falloff"] = v.falloff;
                j["transition_height"] = v.transition_height;
                out.losses.push_back(label("volumes", i, v.name) + ": height fog is unbounded; in Blender it fills a cube of " +
                                     std::to_string(int(2 * extent)) + " m around the camera.");
                break;
            case VolumeType::Depth:
                j["kind"] = "depth";
                j["visibility_distance"] = v.visibility_distance;
                j["start_distance"] = v.start_distance;
                j["camera_position"] = vec(toBlender(s.camera.position));
                out.losses.push_back(label("volumes", i, v.name) + ": depth fog is unbounded and follows the camera; in "
                                     "Blender it is fixed to the exported camera position, in a cube of " +
                                     std::to_string(int(2 * extent)) + " m.");
                break;
            case VolumeType::Vdb:
                j["kind"] = "vdb";
                j["matrix"] = rows(kBlenderFromBrume * v.transform.worldFromLocal());
                j["file"] = absolutePath(s.baseDir, v.file);
                j["grid"] = v.grid;
                j["density_scale"] = v.density_scale;
                if (v.grid.find('#') != std::string::npos)
                    out.losses.push_back(label("volumes", i, v.name) + ": grid \"" + v.grid +
                                         "\" picks one of several same-named grids; Blender reads the first.");
                if (v.height_falloff > 0.0f && baked.find(i) == baked.end())
                    out.losses.push_back(label("volumes", i, v.name) + ": height_falloff " + std::to_string(v.height_falloff) +
                                         " 1/m is not exported (the grid renders without it).");
                break;
            case VolumeType::Mesh:
                out.losses.push_back(label("volumes", i, v.name) + ": the mesh fog hull " + v.file +
                                     " is not exported (the script rebuilds analytic and VDB volumes only).");
                continue;
        }
        const auto bakedFile = baked.find(i);
        if (bakedFile != baked.end()) {
            // The baked grid holds sigma_t (mean of the channels) with placement, edge fade and texture;
            // over the medium's own mean sigma_t it is the factor the analytic material's density takes.
            const glm::vec3 sigmaT = v.medium.scattering + v.medium.absorption;
            j["kind"] = "vdb";
            j["matrix"] = rows(kBlenderFromBrume);
            j["file"] = bakedFile->second;
            j["grid"] = "density";
            j["density_scale"] = 3.0f / (sigmaT.x + sigmaT.y + sigmaT.z);
            if (v.density_texture->scroll_mps != glm::vec3(0.0f))
                out.losses.push_back(label("volumes", i, v.name) + ": its density_texture is baked at scene time " +
                                     std::to_string(s.time_s) + " s into " + bakedFile->second +
                                     "; it does not scroll in Blender.");
        } else if (v.density_texture) {
            out.losses.push_back(label("volumes", i, v.name) + ": its density_texture (" + v.density_texture->file +
                                 ") is not exported (the volume renders without it): only box and vdb volumes with "
                                 "sigma_t > 0 are baked, and only when the texture can be read.");
        }
        if (glm::length(v.medium.emission) > 0.0f && glm::length(v.medium.scattering) > 0.0f)
            out.losses.push_back(label("volumes", i, v.name) + ": emission in a scattering medium: Cycles (volume bounces 0) "
                                 "renders 26-79% more of it than Brume's single scattering (docs/export.md).");
        volumes.push_back(j);
    }
    data["volumes"] = volumes;

    ojson lights = ojson::array();
    for (size_t i = 0; i < s.lights.size(); ++i) {
        const Light& l = s.lights[i];
        ojson j;
        j["name"] = l.name.empty() ? "Light" + std::to_string(i) : l.name;
        j["color"] = vec(l.color);
        j["shadows"] = l.shadows;
        if (l.type == LightType::Directional) {
            j["type"] = "SUN";
            j["energy"] = l.intensity;  // Blender's sun strength is irradiance [W/m^2], as Brume's intensity
            j["matrix"] = rows(lookFrame(glm::vec3(0.0f, 10.0f, 0.0f), l.direction, glm::vec3(0, 1, 0)));
        } else {
            j["type"] = l.type == LightType::Point ? "POINT" : "SPOT";
            // Cycles: a point or spot of power P [W] has radiant intensity P / (4 pi) [W/sr].
            j["energy"] = 4.0f * std::numbers::pi_v<float> * l.intensity;
            const glm::vec3 dir = l.type == LightType::Point ? glm::vec3(0, -1, 0) : l.direction;
            j["matrix"] = rows(lookFrame(l.position, dir, glm::vec3(0, 1, 0)));
            if (l.range > 0.0f)
                out.losses.push_back(label("lights", i, l.name) + ": Blender has no range window; range " +
                                     std::to_string(l.range) + " m is dropped (the light reaches further).");
        }
        if (l.type == LightType::Spot) {
            out.losses.push_back(label("lights", i, l.name) + ": Cycles also scales a spot's cone by the cosine of the "
                                 "angle from its axis (" + std::to_string(int(std::round(100.0f * (1.0f - std::cos(glm::radians(l.outer_deg)))))) +
                                 "% darker at the cone's edge).");
            const float cosOuter = std::cos(glm::radians(l.outer_deg)), cosInner = std::cos(glm::radians(l.inner_deg));
            j["spot_size"] = 2.0f * glm::radians(l.outer_deg);
            // Cycles: smoothstep((cos - cos_outer) / ((1 - cos_outer) blend)) = Brume's smoothstep(cos_outer, cos_inner, cos).
            j["spot_blend"] = cosOuter < 1.0f ? std::clamp((cosInner - cosOuter) / (1.0f - cosOuter), 0.0f, 1.0f) : 0.0f;
        }
        if (!l.shadows)
            out.losses.push_back(label("lights", i, l.name) + ": without shadows Cycles also skips the fog's own "
                                 "shadowing of this light (Brume keeps it).");
        if (l.fog_scale != 1.0f)
            out.losses.push_back(label("lights", i, l.name) + ": fog_scale " + std::to_string(l.fog_scale) +
                                 " (the light's effect on fog alone) has no Blender equivalent and is dropped.");
        lights.push_back(j);
    }
    data["lights"] = lights;

    ojson geometry = ojson::array();
    for (size_t i = 0; i < s.geometry.size(); ++i) {
        const Geometry& g = s.geometry[i];
        ojson j;
        j["name"] = g.name.empty() ? "Geometry" + std::to_string(i) : g.name;
        j["type"] = toString(g.type);
        j["albedo"] = vec(g.albedo);
        j["emission"] = vec(g.emission);
        if (g.type == GeometryType::Plane) {
            j["height"] = g.height;
            j["size"] = 4.0f * extent;
        }
        if (g.type == GeometryType::Box) j["matrix"] = rows(kBlenderFromBrume * g.transform.worldFromLocal());
        if (g.type == GeometryType::Sphere) {
            j["center"] = vec(toBlender(g.center));
            j["radius"] = g.radius;
        }
        geometry.push_back(j);
    }
    data["geometry"] = geometry;
    data["losses"] = out.losses;

    std::string& t = out.script;
    t = "# Exported by brume from \"" + oneLine(source.name) + "\" (docs/export.md). Blender 3.4+, Cycles.\n";
    t += "#   blender -b --factory-startup --python THIS.py -- --render OUT.exr [--samples N] [--width W --height H]\n";
    for (const std::string& loss : out.losses) t += "# loss: " + oneLine(loss) + "\n";
    // Single quotes only occur inside JSON strings, where \u0027 means the same: the raw string cannot end early.
    std::string json = data.dump(1, ' ', false, ojson::error_handler_t::replace);
    for (size_t p = 0; (p = json.find('\'', p)) != std::string::npos;) json.replace(p, 1, "\\u0027");
    t += "import json\n\nDATA = json.loads(r'''" + json + "''')\n";
    t += kScript;
    return out;
}

namespace {

const char* const kScript = R"PY(
import argparse
import math
import sys

import bpy
from mathutils import Matrix


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="blender -b --factory-startup --python THIS.py --")
    p.add_argument("--render", metavar="OUT.exr", help="render with Cycles (single scattering) to a linear EXR")
    p.add_argument("--samples", type=int, default=64, help="Cycles samples per pixel (default 64)")
    p.add_argument("--width", type=int, default=DATA["width"])
    p.add_argument("--height", type=int, default=DATA["height"])
    return p.parse_args(argv)


def clear_scene():
    for o in list(bpy.data.objects):
        bpy.data.objects.remove(o, do_unlink=True)


def link(nt, out, inp):
    nt.links.new(out, inp)


def math_node(nt, op, a, b=None, clamp=False):
    n = nt.nodes.new("ShaderNodeMath")
    n.operation = op
    n.use_clamp = clamp
    for i, v in enumerate((a, b)):
        if v is None:
            continue
        if isinstance(v, (int, float)):
            n.inputs[i].default_value = v
        else:
            link(nt, v, n.inputs[i])
    return n.outputs[0]


def separate(nt, vector_socket):
    n = nt.nodes.new("ShaderNodeSeparateXYZ")
    link(nt, vector_socket, n.inputs[0])
    return n.outputs


def shape_field(nt, v):
    """A box, ellipsoid or cylinder's edge profile in its object space (the unit cube): None where
    it is 1 everywhere inside the cube."""
    tc = nt.nodes.new("ShaderNodeTexCoord")
    x, y, z = separate(nt, tc.outputs["Object"])[:3]
    if v["shape"] == "ellipsoid":
        n = nt.nodes.new("ShaderNodeVectorMath")
        n.operation = "LENGTH"
        link(nt, tc.outputs["Object"], n.inputs[0])
        d = math_node(nt, "MULTIPLY", n.outputs["Value"], 2.0)
    elif v["shape"] == "cylinder":
        r = math_node(nt, "SQRT", math_node(nt, "ADD", math_node(nt, "MULTIPLY", x, x), math_node(nt, "MULTIPLY", z, z)))
        d = math_node(nt, "MULTIPLY", math_node(nt, "MAXIMUM", r, math_node(nt, "ABSOLUTE", y)), 2.0)
    else:
        d = math_node(nt, "MAXIMUM", math_node(nt, "ABSOLUTE", x), math_node(nt, "ABSOLUTE", y))
        d = math_node(nt, "MULTIPLY", math_node(nt, "MAXIMUM", d, math_node(nt, "ABSOLUTE", z)), 2.0)
    if v["edge_fade"] <= 0.0:
        # The cube mesh bounds a box; an ellipsoid or cylinder ends at d = 1 inside it.
        return None if v["shape"] == "box" else math_node(nt, "LESS_THAN", d, 1.0)
    mr = nt.nodes.new("ShaderNodeMapRange")
    mr.interpolation_type = "SMOOTHSTEP"
    mr.clamp = True
    link(nt, d, mr.inputs["Value"])
    mr.inputs["From Min"].default_value = 1.0 - v["edge_fade"]
    mr.inputs["From Max"].default_value = 1.0
    mr.inputs["To Min"].default_value = 1.0
    mr.inputs["To Max"].default_value = 0.0
    return mr.outputs["Result"]


def field(nt, v):
    """The density field of a volume (Brume's shaders/shared/media.h), as shader nodes."""
    kind = v["kind"]
    if kind == "box":
        f = shape_field(nt, v)
        if v["height_falloff"] <= 0.0:
            return f
        geo = nt.nodes.new("ShaderNodeNewGeometry")
        above = math_node(nt, "SUBTRACT", separate(nt, geo.outputs["Position"])[2], v["bottom"])
        h = math_node(nt, "EXPONENT", math_node(nt, "MULTIPLY", above, -v["height_falloff"]))
        return h if f is None else math_node(nt, "MULTIPLY", f, h)
    if kind == "vdb":
        a = nt.nodes.new("ShaderNodeAttribute")
        a.attribute_type = "GEOMETRY"
        a.attribute_name = v["grid"].split("#")[0]
        return math_node(nt, "MULTIPLY", a.outputs["Fac"], v["density_scale"])
    geo = nt.nodes.new("ShaderNodeNewGeometry")
    if kind == "depth":
        sub = nt.nodes.new("ShaderNodeVectorMath")
        sub.operation = "DISTANCE"
        link(nt, geo.outputs["Position"], sub.inputs[0])
        sub.inputs[1].default_value = v["camera_position"]
        r = math_node(nt, "MAXIMUM", math_node(nt, "SUBTRACT", sub.outputs["Value"], v["start_distance"]), 0.0)
        e = math_node(nt, "EXPONENT", math_node(nt, "MULTIPLY", r, -3.0 / v["visibility_distance"]))
        return math_node(nt, "SUBTRACT", 1.0, e)
    above = math_node(nt, "MAXIMUM", math_node(nt, "SUBTRACT", separate(nt, geo.outputs["Position"])[2], v["base_height"]), 0.0)
    if kind == "height_exponential":
        return math_node(nt, "EXPONENT", math_node(nt, "MULTIPLY", above, -v["falloff"]))
    return math_node(nt, "SUBTRACT", 1.0, math_node(nt, "DIVIDE", above, v["transition_height"]), clamp=True)


def volume_material(v):
    mat = bpy.data.materials.new(v["name"])
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    pv = nt.nodes.new("ShaderNodeVolumePrincipled")
    pv.inputs["Color"].default_value = (*v["color"], 1.0)
    pv.inputs["Absorption Color"].default_value = (*v["absorption_color"], 1.0)
    pv.inputs["Anisotropy"].default_value = v["anisotropy"]
    pv.inputs["Emission Color"].default_value = (*v["emission_color"], 1.0)
    pv.inputs["Density Attribute"].default_value = ""
    f = field(nt, v)
    if f is None:
        pv.inputs["Density"].default_value = v["density"]
        pv.inputs["Emission Strength"].default_value = v["emission_strength"]
    else:
        link(nt, math_node(nt, "MULTIPLY", f, v["density"]), pv.inputs["Density"])
        link(nt, math_node(nt, "MULTIPLY", f, v["emission_strength"]), pv.inputs["Emission Strength"])
    link(nt, pv.outputs["Volume"], out.inputs["Volume"])
    if v["kind"] not in ("box", "vdb"):
        # Cycles steps through a mesh volume in proportion to its size: the cube of unbounded fog is
        # large, so its steps are cut to what a 60 m cube takes at rate 0.2 (height fog 4.3% -> 2.0%).
        mat.cycles.volume_step_rate = min(1.0, 12.0 / (2.0 * DATA["extent"]))
    return mat


def add_object(name, data, matrix=None):
    obj = bpy.data.objects.new(name, data)
    bpy.context.scene.collection.objects.link(obj)
    if matrix is not None:
        obj.matrix_world = Matrix(matrix)
    return obj


def cube_mesh(name):
    m = bpy.data.meshes.new(name)
    h = 0.5
    verts = [(x, y, z) for x in (-h, h) for y in (-h, h) for z in (-h, h)]
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    m.from_pydata(verts, [], faces)
    m.update()
    return m


def build_volume(v):
    mat = volume_material(v)
    if v["kind"] == "vdb":
        vol = bpy.data.volumes.new(v["name"])
        vol.filepath = v["file"]
        vol.materials.append(mat)
        return add_object(v["name"], vol, v["matrix"])
    mesh = cube_mesh(v["name"])
    mesh.materials.append(mat)
    if v["kind"] == "box":
        return add_object(v["name"], mesh, v["matrix"])
    c, e = DATA["extent_center"], DATA["extent"]
    obj = add_object(v["name"], mesh)
    obj.location = c
    obj.scale = (2 * e, 2 * e, 2 * e)
    return obj


def surface_material(g):
    mat = bpy.data.materials.new(g["name"])
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    diffuse = nt.nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (*g["albedo"], 1.0)
    emission = nt.nodes.new("ShaderNodeEmission")
    emission.inputs["Color"].default_value = (*g["emission"], 1.0)
    emission.inputs["Strength"].default_value = 1.0
    add = nt.nodes.new("ShaderNodeAddShader")
    link(nt, diffuse.outputs[0], add.inputs[0])
    link(nt, emission.outputs[0], add.inputs[1])
    link(nt, add.outputs[0], out.inputs["Surface"])
    return mat


def build_geometry(g):
    if g["type"] == "plane":
        m = bpy.data.meshes.new(g["name"])
        s = g["size"] / 2
        m.from_pydata([(-s, -s, 0), (s, -s, 0), (s, s, 0), (-s, s, 0)], [], [(0, 1, 2, 3)])
        m.update()
        obj = add_object(g["name"], m)
        c = DATA["extent_center"]
        obj.location = (c[0], c[1], g["height"])
    elif g["type"] == "box":
        obj = add_object(g["name"], cube_mesh(g["name"]), g["matrix"])
    else:
        bpy.ops.mesh.primitive_uv_sphere_add(segments=96, ring_count=48, radius=g["radius"], location=g["center"])
        obj = bpy.context.active_object
        obj.name = g["name"]
        bpy.ops.object.shade_smooth()
    obj.data.materials.append(surface_material(g))
    # Brume's emissive surfaces light nothing else: no secondary ray sees any surface.
    obj.visible_diffuse = False
    obj.visible_glossy = False
    obj.visible_transmission = False
    obj.visible_volume_scatter = False
    return obj


def build_light(l):
    light = bpy.data.lights.new(l["name"], l["type"])
    light.color = l["color"]
    light.energy = l["energy"]
    light.cycles.cast_shadow = l["shadows"]
    if l["type"] == "SUN":
        light.angle = 0.0
    else:
        light.shadow_soft_size = 0.0
    if l["type"] == "SPOT":
        light.spot_size = l["spot_size"]
        light.spot_blend = l["spot_blend"]
        light.show_cone = True
    return add_object(l["name"], light, l["matrix"])


def build_camera(c, scene):
    cam = bpy.data.cameras.new("Camera")
    cam.sensor_fit = "VERTICAL"
    cam.angle_y = math.radians(c["fov_y_deg"])
    cam.clip_start = c["near"]
    cam.clip_end = c["far"] * 2.0
    scene.camera = add_object("Camera", cam, c["matrix"])


def build():
    clear_scene()
    scene = bpy.context.scene
    world = bpy.data.worlds.new("Brume ambient")
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (*DATA["ambient"], 1.0)
    bg.inputs["Strength"].default_value = 1.0
    scene.world = world
    for v in DATA["volumes"]:
        build_volume(v)
    for l in DATA["lights"]:
        build_light(l)
    for g in DATA["geometry"]:
        build_geometry(g)
    if DATA["camera"] is not None:
        build_camera(DATA["camera"], scene)
    return scene


def render(scene, args):
    if scene.camera is None:
        sys.exit("error: a preset has no camera to render from; export a scene to render.")
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = args.samples
    c.use_denoising = False
    c.use_adaptive_sampling = False
    # Single scattering, direct light on surfaces: what Brume renders.
    c.max_bounces = 0
    c.diffuse_bounces = 0
    c.glossy_bounces = 0
    c.transmission_bounces = 0
    c.volume_bounces = 0
    c.transparent_max_bounces = 8
    c.volume_step_rate = 0.25
    c.volume_max_steps = 4096
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    scene.render.resolution_x = args.width
    scene.render.resolution_y = args.height
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = False
    s = scene.render.image_settings
    s.file_format = "OPEN_EXR"
    s.color_mode = "RGB"
    s.color_depth = "32"
    scene.render.filepath = args.render
    bpy.ops.render.render(write_still=True)


def main():
    args = parse_args()
    scene = build()
    for loss in DATA["losses"]:
        print("loss: " + loss)
    if args.render:
        render(scene, args)


main()
)PY";

}  // namespace

}  // namespace brume
