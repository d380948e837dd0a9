// SceneDesc → JSON text (the inverse of scene_loader.cpp).
#include "scene/scene_writer.h"

#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "scene/embedded_files.h"

namespace luz {

namespace {

using Json = nlohmann::ordered_json;
namespace fs = std::filesystem;

/// A float as the shortest decimal that reads back to the same float.
Json num(float v) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::stod(std::string(buf, r.ptr));
}

Json vec(const Vec3& v) { return Json::array({num(v.x), num(v.y), num(v.z)}); }

const char* shape_type(ShapeType t) {
    switch (t) {
        case ShapeType::sphere:
            return "sphere";
        case ShapeType::box:
            return "box";
        case ShapeType::cylinder:
            return "cylinder";
        case ShapeType::cone:
            return "cone";
        case ShapeType::torus:
            return "torus";
        case ShapeType::plane:
            return "plane";
        case ShapeType::triangle:
            return "triangle";
        case ShapeType::mesh:
            return "mesh";
    }
    return "sphere";
}

Json material_json(const Material& m) {
    Json j;
    j["ka"] = vec(m.ka);
    j["kd"] = vec(m.kd);
    j["ks"] = vec(m.ks);
    j["n"] = num(m.n);
    j["reflection"] = num(m.reflection);
    j["transparency"] = num(m.transparency);
    j["ior"] = num(m.ior);
    if (m.checker) {
        j["checker"] = {
            {"size", num(m.checker->size)}, {"ka", vec(m.checker->ka)}, {"kd", vec(m.checker->kd)}};
    }
    return j;
}

/// A mesh file's path for the new scene: relative to out_dir when it lies on disk.
std::string mesh_path(const std::string& file, const std::string& out_dir) {
    std::error_code ec;
    if (!fs::exists(file, ec)) return file;
    const fs::path abs = fs::absolute(file, ec);
    const fs::path rel = fs::relative(abs, fs::absolute(out_dir.empty() ? "." : out_dir), ec);
    if (ec || rel.empty()) return abs.string();
    return rel.generic_string();
}

}  // namespace

std::string scene_to_json(const SceneDesc& d, const std::string& out_dir) {
    Json j;
    j["image"] = {{"width", d.image.width},
                  {"height", d.image.height},
                  {"background", vec(d.image.background)},
                  {"encoding", d.image.encoding == Encoding::srgb ? "srgb" : "linear"}};
    const CameraDesc& c = d.camera;
    j["camera"] = {
        {"projection", c.projection == Projection::perspective ? "perspective" : "orthographic"},
        {"position", vec(c.position)},
        {"look_at", vec(c.look_at)},
        {"up", vec(c.up)},
        {"view_height", num(c.view_height)},
        {"fov_y", num(c.fov_y)}};
    const RenderDesc& r = d.render;
    const AntialiasDesc& aa = r.antialias;
    j["render"] = {{"pipeline", r.pipeline == Pipeline::zbuffer   ? "zbuffer"
                                : r.pipeline == Pipeline::raycast ? "raycast"
                                                                  : "raytrace"},
                   {"model", r.model == Model::lambert ? "lambert" : "phong"},
                   {"max_depth", r.max_depth},
                   {"tree_attenuation", r.tree_attenuation},
                   {"tessellation", d.geometry.tessellation},
                   {"accel", d.geometry.accel == Accel::none ? "none" : "bvh"},
                   {"antialias",
                    {{"mode", aa.mode == AaMode::none   ? "none"
                              : aa.mode == AaMode::grid ? "grid"
                                                        : "adaptive"},
                     {"samples", aa.samples},
                     {"filter", aa.filter == AaFilter::tent ? "tent" : "box"},
                     {"jitter", aa.jitter},
                     {"threshold", num(aa.threshold)},
                     {"max_level", aa.max_level}}}};
    j["ambient"] = vec(d.ambient);
    j["attenuation_k"] = num(d.attenuation_k);
    Json lights = Json::array();
    for (const Light& l : d.lights) {
        lights.push_back({{"position", vec(l.position)},
                          {"intensity", vec(l.intensity)},
                          {"radius", num(l.radius)}});
    }
    j["lights"] = lights;

    // Materials by name; MTL materials (reached only through a mesh's mesh_materials) are left
    // to the MTL file.
    std::set<int> from_mtl;
    for (const ObjectDesc& o : d.objects)
        for (int m : o.mesh_materials) from_mtl.insert(m);
    std::map<int, std::string> key_of;
    std::set<std::string> used;
    Json materials = Json::object();
    for (int i = 0; i < static_cast<int>(d.materials.size()); ++i) {
        if (from_mtl.count(i) && i != 0) continue;
        std::string key = i == 0 ? "default" : d.materials[i].name;
        if (key.empty() || used.count(key) || (i != 0 && key == "default"))
            key = "material_" + std::to_string(i);
        used.insert(key);
        key_of[i] = key;
        materials[key] = material_json(d.materials[i]);
    }
    j["materials"] = materials;

    Json objects = Json::array();
    for (const ObjectDesc& o : d.objects) {
        Json b;
        b["type"] = shape_type(o.type);
        switch (o.type) {
            case ShapeType::sphere:
                b["center"] = vec(o.center);
                b["radius"] = num(o.radius);
                break;
            case ShapeType::box:
                b["min"] = vec(o.min);
                b["max"] = vec(o.max);
                break;
            case ShapeType::cylinder:
            case ShapeType::cone:
                b["base"] = vec(o.base);
                b["axis"] = vec(o.axis);
                b["radius"] = num(o.radius);
                b["height"] = num(o.height);
                b[o.type == ShapeType::cylinder ? "caps" : "cap"] = o.caps;
                break;
            case ShapeType::torus:
                b["center"] = vec(o.center);
                b["axis"] = vec(o.axis);
                b["major_radius"] = num(o.major_radius);
                b["minor_radius"] = num(o.minor_radius);
                break;
            case ShapeType::plane:
                b["point"] = vec(o.point);
                b["normal"] = vec(o.normal);
                break;
            case ShapeType::triangle:
                b["vertices"] =
                    Json::array({vec(o.vertices[0]), vec(o.vertices[1]), vec(o.vertices[2])});
                break;
            case ShapeType::mesh:
                b["file"] = mesh_path(o.file, out_dir);
                b["smooth"] = o.smooth;
                break;
        }
        if (o.type != ShapeType::mesh || o.mesh_materials.empty()) {
            b["material"] = key_of.count(o.material) ? key_of[o.material] : "default";
        }
        b["transform"] = {
            {"scale", vec(o.scale)}, {"rotate", vec(o.rotate)}, {"translate", vec(o.translate)}};
        objects.push_back(b);
    }
    j["objects"] = objects;
    return j.dump(2) + "\n";
}

void write_scene(const std::string& path, const SceneDesc& desc) {
    const std::string out_dir = fs::path(path).parent_path().string();
    // A built-in scene's meshes live in the binary: put a copy next to the saved scene.
    for (const ObjectDesc& o : desc.objects) {
        std::error_code ec;
        if (o.type != ShapeType::mesh || fs::exists(o.file, ec)) continue;
        const auto text = embedded_file(o.file);
        const fs::path target = fs::path(out_dir.empty() ? "." : out_dir) / o.file;
        if (!text || fs::exists(target, ec)) continue;
        std::ofstream f(target, std::ios::binary);
        f << *text;
        if (!f) throw std::runtime_error(target.string() + ": cannot write");
    }
    const std::string text = scene_to_json(desc, out_dir);
    const std::string tmp = path + ".tmp";
    {
        std::ofstream f(tmp, std::ios::binary);
        f << text;
        f.close();
        if (!f) {
            std::remove(tmp.c_str());
            throw std::runtime_error(path + ": cannot write");
        }
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) {
        std::remove(tmp.c_str());
        throw std::runtime_error(path + ": cannot write: " + ec.message());
    }
}

}  // namespace luz
