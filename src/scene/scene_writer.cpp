// SceneDesc → JSON text (the inverse of scene_loader.cpp).
#include "scene/scene_writer.h"

#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "scene/embedded_files.h"
#include "scene/mesh_data.h"

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

Json material_json(const Material& m) {
    Json j;
    j["ka"] = vec(m.ka);
    j["kd"] = vec(m.kd);
    j["ks"] = vec(m.ks);
    j["n"] = num(m.n);
    j["reflection"] = num(m.reflection);
    j["transparency"] = num(m.transparency);
    j["ior"] = num(m.ior);
    j["reflectance"] = m.reflectance == Reflectance::schlick ? "schlick" : "constant";
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

/// The value of shape key `k` of `o`, as the loader reads it (kShapeKeys in shape_desc.h).
Json shape_key_json(const ObjectDesc& o, const ShapeKey& k, const std::string& out_dir) {
    switch (k.kind) {
        case ShapeKeyKind::point:
        case ShapeKeyKind::direction:
            return vec(o.*std::get<Vec3 ObjectDesc::*>(k.member));
        case ShapeKeyKind::number:
            return num(o.*std::get<float ObjectDesc::*>(k.member));
        case ShapeKeyKind::flag:
            return o.*std::get<bool ObjectDesc::*>(k.member);
        case ShapeKeyKind::vertices: {
            const auto& p = o.*std::get<std::array<Vec3, 3> ObjectDesc::*>(k.member);
            return Json::array({vec(p[0]), vec(p[1]), vec(p[2])});
        }
        case ShapeKeyKind::obj_file:
            return mesh_path(o.*std::get<std::string ObjectDesc::*>(k.member), out_dir);
    }
    return nullptr;
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
                   {"min_weight", num(r.min_weight)},
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
    j["attenuation"] = d.attenuation == Attenuation::none     ? "none"
                       : d.attenuation == Attenuation::linear ? "linear"
                                                              : "inverse_square";
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
        b["type"] = shape_name(o.type);
        for (const ShapeKey& k : kShapeKeys) {
            if (k.type == o.type) b[std::string(k.name)] = shape_key_json(o, k, out_dir);
        }
        if (o.mesh_materials.empty()) {  // else the MTL file gives the materials
            b["material"] = key_of.count(o.material) ? key_of[o.material] : "default";
        }
        b["transform"] = {
            {"scale", vec(o.scale)}, {"rotate", vec(o.rotate)}, {"translate", vec(o.translate)}};
        objects.push_back(b);
    }
    j["objects"] = objects;
    return j.dump(2) + "\n";
}

namespace {

/// Writes `text` to `path` whole or not at all (a temporary file renamed over it).
void write_whole(const std::string& path, const std::string& text) {
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

/// A float as the shortest text that reads back as the same bits.
void append_float(std::string& out, float x) {
    char buf[32];
    out.append(buf, std::to_chars(buf, buf + sizeof buf, x).ptr);
}

/// A mesh held only in memory (an NFF file's polygons) as Wavefront OBJ text: the same
/// vertices, normals and triangles, each number read back as the same bits.
std::string obj_text(const MeshData& m) {
    std::string out = "# " + m.file + ", written by luz\n";
    const auto line = [&](const char* tag, const Vec3& p) {
        out += tag;
        for (float x : {p.x, p.y, p.z}) {
            out += ' ';
            append_float(out, x);
        }
        out += '\n';
    };
    for (const Vec3& p : m.positions) line("v", p);
    for (const Vec3& n : m.normals) line("vn", n);
    for (size_t k = 0; k < m.position.size(); k += 3) {
        out += 'f';
        for (size_t c = k; c < k + 3; ++c) {
            out += ' ' + std::to_string(m.position[c] + 1);
            if (m.normal[c] >= 0) out += "//" + std::to_string(m.normal[c] + 1);
        }
        out += '\n';
    }
    return out;
}

/// The file to save `text` in beside the scene: `name`, or name-2, name-3 … when a different
/// file is already there (an existing file is never replaced).
fs::path free_name(const fs::path& dir, const std::string& stem, const std::string& text) {
    for (int k = 1;; ++k) {
        const fs::path p = dir / ((k == 1 ? stem : stem + "-" + std::to_string(k)) + ".obj");
        std::error_code ec;
        if (!fs::exists(p, ec)) return p;
        std::ifstream f(p, std::ios::binary);
        const std::string old{std::istreambuf_iterator<char>(f), {}};
        if (old == text) return p;
    }
}

}  // namespace

void write_scene(const std::string& path, const SceneDesc& desc) {
    const std::string out_dir = fs::path(path).parent_path().string();
    const fs::path dir = out_dir.empty() ? "." : out_dir;
    SceneDesc saved = desc;
    for (ObjectDesc& o : saved.objects) {
        std::error_code ec;
        if (o.file.empty() || fs::exists(o.file, ec)) continue;  // not a mesh, or on disk
        if (const auto text = embedded_file(o.file)) {
            // A built-in scene's meshes live in the binary: a copy next to the saved scene.
            const fs::path target = dir / o.file;
            if (!fs::exists(target, ec)) write_whole(target.string(), std::string(*text));
        } else if (o.mesh) {
            // A mesh that exists only in memory (an NFF file's polygons, named "FILE#MATERIAL"):
            // written as an OBJ file beside the saved scene, which names it.
            std::string stem = fs::path(o.file).filename().string();
            for (char& c : stem) {
                if (c == '#') c = '.';
            }
            const std::string text = obj_text(*o.mesh);
            const fs::path target = free_name(dir, stem, text);
            if (!fs::exists(target, ec)) write_whole(target.string(), text);
            o.file = target.string();
        }
    }
    write_whole(path, scene_to_json(saved, out_dir));
}

}  // namespace luz
