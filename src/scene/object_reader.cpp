// Reading `objects` (docs/SCENES.md#scene-files) through the shape key table (kShapeKeys in
// shape_desc.h).
#include "scene/object_reader.h"

#include <filesystem>
#include <optional>

#include "scene/embedded_files.h"
#include "scene/json_readers.h"
#include "scene/message_text.h"
#include "scene/number_text.h"
#include "scene/obj_loader.h"

namespace luz::loader {
namespace {

/// `transform`: p_world = T·Rz·Ry·Rx·S·p (docs/SCENES.md#scene-files).
Affine read_transform(const Json& j, const std::string& path, Vec3& scale, Vec3& rotate,
                      Vec3& translate) {
    const Section s(j, path, {"scale", "rotate", "translate"}, "objects.*.transform");
    if (const Json* v = s.get("scale")) {
        const std::string key = s.key("scale");
        if (v->is_number()) {
            scale = Vec3(read_float(*v, key));
        } else if (v->is_array() && v->size() == 3) {
            scale = read_vec3(*v, key);
        } else {
            fail(key, "expected a number or an array of 3 numbers, got " + describe(*v));
        }
        if (scale.x == 0 || scale.y == 0 || scale.z == 0) {
            fail(key, "components must be non-zero, got " + format_vec(scale));
        }
    }
    s.vec3("rotate", rotate);
    s.vec3("translate", translate);
    return translation(translate) * rotation(2, rotate.z) * rotation(1, rotate.y) *
           rotation(0, rotate.x) * scaling(scale);
}

/// What a Section of shape type `t` is made with: the keys it accepts, in the order messages
/// list them, and its pattern in the limits table ("objects.sphere").
struct ShapeSection {
    std::vector<std::string_view> keys;
    std::string pattern;
};

/// The ShapeSection of every shape type, made once.
const ShapeSection& shape_section(ShapeType t) {
    static const std::vector<ShapeSection> sections = [] {
        std::vector<ShapeSection> all;
        for (std::size_t i = 0; i < std::size(kShapeNames); ++i) {
            ShapeSection& s = all.emplace_back();
            s.keys = {"type"};
            for (const ShapeKey& k : kShapeKeys) {
                if (k.type == static_cast<ShapeType>(i)) s.keys.push_back(k.name);
            }
            s.keys.push_back("material");
            s.keys.push_back("transform");
            s.pattern = "objects." + std::string(kShapeNames[i]);
        }
        return all;
    }();
    return sections[static_cast<std::size_t>(t)];
}

/// The `type` key: one of the shape names of LUZ_SHAPES.
ShapeType read_type(const Json& j, const std::string& path) {
    const auto names = [] {  // for the messages only
        std::string all;
        for (std::string_view n : kShapeNames) all += (all.empty() ? "" : ", ") + std::string(n);
        return all;
    };
    const auto it = j.find("type");
    if (it == j.end()) fail(path, "missing key \"type\" (one of: " + names() + ")");
    if (!it->is_string())
        fail(join(path, "type"), "expected one of " + names() + ", got " + describe(*it));
    const std::string& s = it->get_ref<const std::string&>();
    for (std::size_t i = 0; i < std::size(kShapeNames); ++i) {
        if (kShapeNames[i] == s) return static_cast<ShapeType>(i);
    }
    fail(join(path, "type"), "unknown value " + quote(s) + " (allowed: " + names() + ")");
}

/// Reads one key of the shape's table into `o` (absent: the default stays).
void read_shape_key(const Section& s, const ShapeKey& k, ObjectDesc& o,
                    const std::string& base_dir) {
    const Json* v = s.get(k.name);
    if (!v && k.kind != ShapeKeyKind::obj_file) return;  // absent: the default stays
    const KeyPath key = s.at(k.name);
    switch (k.kind) {
        case ShapeKeyKind::point:
            if (v) o.*std::get<Vec3 ObjectDesc::*>(k.member) = read_vec3(*v, key);
            break;
        case ShapeKeyKind::direction:
            if (v) o.*std::get<Vec3 ObjectDesc::*>(k.member) = read_direction(*v, key);
            break;
        case ShapeKeyKind::number:
            if (v) o.*std::get<float ObjectDesc::*>(k.member) = read_float(*v, key, k.limit);
            break;
        case ShapeKeyKind::flag:
            if (v) o.*std::get<bool ObjectDesc::*>(k.member) = read_bool(*v, key);
            break;
        case ShapeKeyKind::vertices:
            if (v) {
                if (!v->is_array() || v->size() != 3) {
                    fail(key.str(), "expected an array of 3 points [x, y, z], got " + describe(*v));
                }
                auto& points = o.*std::get<std::array<Vec3, 3> ObjectDesc::*>(k.member);
                for (std::size_t i = 0; i < 3; ++i)
                    points[i] = read_vec3((*v)[i], join(key.str(), i));
            }
            break;
        case ShapeKeyKind::obj_file: {
            if (!v)
                fail(s.path(),
                     "missing key \"" + std::string(k.name) + "\" (the OBJ file of the mesh)");
            std::string& file = o.*std::get<std::string ObjectDesc::*>(k.member);
            file = read_string(*v, key);
            if (file.empty()) fail(key.str(), "must not be empty");
            if (!base_dir.empty() && !std::filesystem::path(file).is_absolute()) {
                file = (std::filesystem::path(base_dir) / file).string();
            }
            break;
        }
    }
}

}  // namespace

void MeshFiles::load(ObjectDesc& o, bool names_material, MaterialTable& materials) {
    const bool with_materials = !names_material;
    const std::pair<std::string, bool> id{o.file, with_materials};
    Loaded& l = loaded_[id];
    if (!l.mesh) {
        if (cache_ && cache_->count(id)) {
            l.mesh = cache_->at(id);
        } else {
            l.mesh = read_mesh(o.file, with_materials, o.path);
            if (cache_) (*cache_)[id] = l.mesh;
        }
        if (with_materials) {
            for (const Material& m : l.mesh->materials) l.scene_index.push_back(materials.add(m));
        }
    }
    o.mesh = l.mesh;
    o.mesh_materials = l.scene_index;
}

std::shared_ptr<const MeshData> MeshFiles::read_mesh(const std::string& file, bool with_materials,
                                                     const std::string& path) {
    const bool demo = scene_.source.rfind("demo:", 0) == 0;
    const TextReader read = [demo](const std::string& name, std::string& reason) {
        if (demo) {
            if (const auto text = embedded_file(name)) return std::optional(std::string(*text));
        }
        return read_text_file(name, reason);
    };
    std::string reason;
    const std::optional<std::string> text = read(file, reason);
    if (!text) {
        throw InputError(printable(scene_.source) + ": " + path + ".file: cannot read " +
                         printable(file) + ": " + reason);
    }
    return std::make_shared<const MeshData>(
        parse_obj(*text, file, with_materials, read, scene_.warnings));
}

ObjectDesc read_object(const Json& j, const std::string& path, MaterialTable& materials,
                       const std::string& base_dir, MeshFiles& meshes) {
    if (!j.is_object()) fail(path, "expected an object, got " + describe(j));
    ObjectDesc o;
    o.path = path;
    o.type = read_type(j, path);
    const ShapeSection& section = shape_section(o.type);
    const Section s(j, path, section.keys, section.pattern, KeyPath(path, "type"));
    bool has_obj_file = false;
    for (const ShapeKey& k : kShapeKeys) {
        if (k.type != o.type) continue;
        read_shape_key(s, k, o, base_dir);
        has_obj_file = has_obj_file || k.kind == ShapeKeyKind::obj_file;
    }
    if (const std::optional<ShapeProblem> p = check_shape(o)) {
        fail(s.key(p->key), p->what, p->whole_object ? path : std::string());
    }
    if (const Json* m = s.get("material")) o.material = materials.resolve(*m, s.at("material"));
    if (const Json* t = s.get("transform"))
        o.transform = read_transform(*t, s.key("transform"), o.scale, o.rotate, o.translate);
    if (has_obj_file) meshes.load(o, s.get("material") != nullptr, materials);
    return o;
}

}  // namespace luz::loader
