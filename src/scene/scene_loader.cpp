// BuiltScene loading (SPEC §2): JSON text → --set overrides applied to the document → validation
// into a SceneDesc with every default filled. Every error names the file (or the override)
// and the line:column or key path.
#include "scene/scene_loader.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <utility>

#include "scene/demo_scenes.h"
#include "scene/embedded_files.h"
#include "scene/obj_loader.h"
#include "scene/presets.h"

namespace luz {
namespace {

// ordered_json keeps the file's key order: materials keep their order and the first unknown
// key reported is the first one in the file.
using Json = nlohmann::ordered_json;

// ---------------------------------------------------------------------------------------------
// Errors found while reading the document: a key path and what is wrong. parse_scene turns them
// into an InputError naming the file, or the override that put the bad value there.

struct KeyError {
    std::string path;   ///< e.g. "objects.2.radius"; empty for the document itself
    std::string what;   ///< e.g. "must be > 0, got -1"
    std::string scope;  ///< for checks across keys (box min/max…): the object they belong to
};

[[noreturn]] void fail(std::string path, std::string what, std::string scope = {}) {
    throw KeyError{std::move(path), std::move(what), std::move(scope)};
}

std::string join(const std::string& path, std::string_view key) {
    return path.empty() ? std::string(key) : path + "." + std::string(key);
}
std::string join(const std::string& path, std::size_t index) {
    return join(path, std::to_string(index));
}

/// True when key path `path` is `root` or lies inside it ("a.b.c" is under "a.b", not "a.bc").
bool is_under(std::string_view path, std::string_view root) {
    if (root.empty() || path.size() < root.size() || path.substr(0, root.size()) != root) {
        return false;
    }
    return path.size() == root.size() || path[root.size()] == '.';
}

/// A short description of a JSON value for "got …" in messages.
std::string describe(const Json& j) {
    std::string s;
    if (j.is_object()) return "an object";
    if (j.is_string()) {
        s = "string " + j.dump();
    } else {
        s = j.dump(-1, ' ', false, Json::error_handler_t::replace);
    }
    if (s.size() > 60) s = s.substr(0, 57) + "...";
    return s;
}

/// A number as it would be written in the scene (shortest form: 1, 0.5, 1e+39).
template <typename T>
std::string format_number(T d) {
    if (std::isnan(d)) return "nan";
    if (std::isinf(d)) return d > 0 ? "inf" : "-inf";
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, d + T(0));  // -0 → 0
    return std::string(buffer, result.ptr);
}

std::string format_vec(const Vec3& v) {
    return "[" + format_number(v.x) + ", " + format_number(v.y) + ", " + format_number(v.z) + "]";
}

std::string comma_list(const std::vector<std::string_view>& names) {
    std::string s;
    for (std::string_view n : names) s += (s.empty() ? "" : ", ") + std::string(n);
    return s;
}

// ---------------------------------------------------------------------------------------------
// Typed readers. Each takes the value and its key path and returns it converted, or fails.

/// An allowed interval for a number; open or closed at either end, unbounded by default.
struct Limits {
    double lo = -std::numeric_limits<double>::infinity();
    double hi = std::numeric_limits<double>::infinity();
    bool lo_open = false, hi_open = false;

    bool contains(double d) const {
        return (lo_open ? d > lo : d >= lo) && (hi_open ? d < hi : d <= hi);
    }
    std::string text() const {
        const auto g = [](double d) { return format_number(d); };
        const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
        if (has_lo && has_hi) {
            return std::string("must be in ") + (lo_open ? "(" : "[") + g(lo) + ", " + g(hi) +
                   (hi_open ? ")" : "]");
        }
        if (has_lo) return std::string("must be ") + (lo_open ? "> " : ">= ") + g(lo);
        if (has_hi) return std::string("must be ") + (hi_open ? "< " : "<= ") + g(hi);
        return "";
    }
};
constexpr Limits kAny{};
constexpr Limits kPositive{0, std::numeric_limits<double>::infinity(), true, false};
constexpr Limits kNonNegative{0, std::numeric_limits<double>::infinity(), false, false};
constexpr Limits kUnit{0, 1, false, false};

/// A finite number (finite also once converted to float) within `limits`.
double read_number(const Json& j, const std::string& path, const Limits& limits = kAny) {
    if (!j.is_number()) fail(path, "expected a number, got " + describe(j));
    const double d = j.get<double>();
    if (!std::isfinite(d)) fail(path, "must be a finite number, got " + format_number(d));
    if (!std::isfinite(static_cast<float>(d))) {
        fail(path, "must be a finite number (a float: |x| < 3.4e38), got " + j.dump());
    }
    // The float must be in range too: 1e-50 is > 0 but becomes 0 as a float.
    if (!limits.contains(d) || !limits.contains(static_cast<float>(d))) {
        fail(path, limits.text() + ", got " + j.dump());
    }
    return d;
}

float read_float(const Json& j, const std::string& path, const Limits& limits = kAny) {
    return static_cast<float>(read_number(j, path, limits));
}

/// An integer in [lo, hi] (a float with an integral value, like 800.0, is accepted).
int read_int(const Json& j, const std::string& path, long long lo, long long hi) {
    if (!j.is_number()) fail(path, "expected an integer, got " + describe(j));
    const double d = j.get<double>();
    if (!std::isfinite(d)) fail(path, "must be a finite number, got " + format_number(d));
    if (!j.is_number_integer() && std::floor(d) != d) {
        fail(path, "expected an integer, got " + j.dump());
    }
    bool in;
    if (j.is_number_unsigned()) {
        const std::uint64_t v = j.get<std::uint64_t>();
        in = v <= static_cast<std::uint64_t>(std::max(hi, 0LL)) &&
             (lo <= 0 || v >= static_cast<std::uint64_t>(lo));
    } else if (j.is_number_integer()) {
        const std::int64_t v = j.get<std::int64_t>();
        in = v >= lo && v <= hi;
    } else {
        in = d >= static_cast<double>(lo) && d <= static_cast<double>(hi);
    }
    if (!in) {
        fail(path, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                       j.dump());
    }
    return static_cast<int>(d);
}

bool read_bool(const Json& j, const std::string& path) {
    if (!j.is_boolean()) fail(path, "expected true or false, got " + describe(j));
    return j.get<bool>();
}

std::string read_string(const Json& j, const std::string& path) {
    if (!j.is_string()) fail(path, "expected a string, got " + describe(j));
    return j.get<std::string>();
}

/// A point or direction: an array of 3 finite numbers.
Vec3 read_vec3(const Json& j, const std::string& path) {
    if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() ||
        !j[2].is_number()) {
        fail(path, "expected an array of 3 numbers, got " + describe(j));
    }
    return {read_float(j[0], path), read_float(j[1], path), read_float(j[2], path)};
}

/// A colour constant: a scalar (all channels) or an array of 3 numbers, each within `limits`.
Rgb read_rgb(const Json& j, const std::string& path, const Limits& limits) {
    if (j.is_number()) return Rgb(read_float(j, path, limits));
    if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() ||
        !j[2].is_number()) {
        fail(path, "expected a number or an array of 3 numbers, got " + describe(j));
    }
    return {read_float(j[0], path, limits), read_float(j[1], path, limits),
            read_float(j[2], path, limits)};
}

/// A direction that can be normalised (not zero-length, length within float range).
Vec3 read_direction(const Json& j, const std::string& path) {
    const Vec3 v = read_vec3(j, path);
    const float len = length(v);
    if (v == Vec3(0.0f)) fail(path, "must not be zero-length, got " + format_vec(v));
    if (!(len > 0) || !std::isfinite(len) || !is_finite(v / len)) {
        fail(path, "cannot be normalised (length out of float range), got " + format_vec(v));
    }
    return v;
}

/// One of the strings of `table` (name → value).
template <typename E>
E read_enum(const Json& j, const std::string& path,
            std::initializer_list<std::pair<std::string_view, E>> table) {
    std::string allowed;
    for (const auto& [name, value] : table) {
        allowed += (allowed.empty() ? "" : ", ") + std::string(name);
    }
    if (!j.is_string()) fail(path, "expected one of " + allowed + ", got " + describe(j));
    const std::string s = j.get<std::string>();
    for (const auto& [name, value] : table) {
        if (name == s) return value;
    }
    fail(path, "unknown value \"" + s + "\" (allowed: " + allowed + ")");
}

/// An object whose keys must all be among `known`; gives access to the present ones.
class Section {
  public:
    /// `unknown_scope`: the key that decides which keys are known, when there is one (an
    /// object's `type`), so that an override changing it is blamed for unknown keys.
    Section(const Json& j, std::string path, const std::vector<std::string_view>& known,
            const std::string& unknown_scope = {})
        : j_(j), path_(std::move(path)) {
        if (!j.is_object()) {
            fail(path_, path_.empty()
                            ? "expected a JSON object at the top level, got " + describe(j)
                            : "expected an object, got " + describe(j));
        }
        for (const auto& item : j.items()) {
            bool found = false;
            for (std::string_view k : known) found = found || k == item.key();
            if (!found) {
                fail(key(item.key()), "unknown key (known: " + comma_list(known) + ")",
                     unknown_scope);
            }
        }
    }
    /// The value of `name`, or nullptr when absent.
    const Json* get(std::string_view name) const {
        const auto it = j_.find(std::string(name));
        return it == j_.end() ? nullptr : &*it;
    }
    std::string key(std::string_view name) const { return join(path_, name); }
    const std::string& path() const { return path_; }

    // Readers that leave `out` at its default when the key is absent.
    void number(std::string_view name, float& out, const Limits& limits = kAny) const {
        if (const Json* v = get(name)) out = read_float(*v, key(name), limits);
    }
    void integer(std::string_view name, int& out, long long lo, long long hi) const {
        if (const Json* v = get(name)) out = read_int(*v, key(name), lo, hi);
    }
    void boolean(std::string_view name, bool& out) const {
        if (const Json* v = get(name)) out = read_bool(*v, key(name));
    }
    void vec3(std::string_view name, Vec3& out) const {
        if (const Json* v = get(name)) out = read_vec3(*v, key(name));
    }
    void direction(std::string_view name, Vec3& out) const {
        if (const Json* v = get(name)) out = read_direction(*v, key(name));
    }
    void rgb(std::string_view name, Rgb& out, const Limits& limits) const {
        if (const Json* v = get(name)) out = read_rgb(*v, key(name), limits);
    }
    template <typename E>
    void enumeration(std::string_view name, E& out,
                     std::initializer_list<std::pair<std::string_view, E>> table) const {
        if (const Json* v = get(name)) out = read_enum(*v, key(name), table);
    }

  private:
    const Json& j_;
    std::string path_;
};

// ---------------------------------------------------------------------------------------------
// Sections of the scene.

void read_image(const Json& j, ImageDesc& image) {
    const Section s(j, "image", {"width", "height", "background", "encoding"});
    s.integer("width", image.width, 1, 65536);
    s.integer("height", image.height, 1, 65536);
    constexpr long long kMaxPixels = 1LL << 28;
    if (static_cast<long long>(image.width) * image.height > kMaxPixels) {
        fail("image",
             "width*height must be at most 268435456 (2^28) pixels, got " +
                 std::to_string(image.width) + "x" + std::to_string(image.height),
             "image");
    }
    s.rgb("background", image.background, kNonNegative);
    s.enumeration("encoding", image.encoding,
                  {{"linear", Encoding::linear}, {"srgb", Encoding::srgb}});
}

void read_camera(const Json* j, CameraDesc& camera) {
    if (j) {
        const Section s(*j, "camera",
                        {"projection", "position", "look_at", "up", "view_height", "fov_y"});
        s.enumeration(
            "projection", camera.projection,
            {{"orthographic", Projection::orthographic}, {"perspective", Projection::perspective}});
        s.vec3("position", camera.position);
        s.vec3("look_at", camera.look_at);
        s.direction("up", camera.up);
        s.number("view_height", camera.view_height, kPositive);
        s.number("fov_y", camera.fov_y, Limits{0, 180, true, true});
    }
    // The basis of SPEC §1.3 must exist: w = normalize(position − look_at), u = up × w ≠ 0.
    const Vec3 d = camera.position - camera.look_at;
    const float len = length(d);
    if (d == Vec3(0.0f)) {
        fail("camera.look_at",
             "must differ from camera.position, got " + format_vec(camera.look_at) + " for both",
             "camera");
    }
    if (!(len > 0) || !std::isfinite(len)) {
        fail("camera.look_at",
             "is too far from camera.position (their distance overflows a float), got " +
                 format_vec(camera.look_at) + " and " + format_vec(camera.position),
             "camera");
    }
    const Vec3 w = d / len;
    const Vec3 up = normalize(camera.up);
    if (!(length(cross(up, w)) > 1e-6f)) {
        fail("camera.up",
             "must not be parallel to the view direction, got up " + format_vec(camera.up) +
                 " and look_at - position = " + format_vec(-d),
             "camera");
    }
}

void read_render(const Json& j, RenderDesc& render, GeometryDesc& geometry) {
    const Section s(j, "render",
                    {"pipeline", "model", "max_depth", "tree_attenuation", "tessellation", "accel",
                     "antialias"});
    s.enumeration("pipeline", render.pipeline,
                  {{"zbuffer", Pipeline::zbuffer},
                   {"raycast", Pipeline::raycast},
                   {"raytrace", Pipeline::raytrace}});
    s.enumeration("model", render.model, {{"lambert", Model::lambert}, {"phong", Model::phong}});
    s.integer("max_depth", render.max_depth, 0, 64);
    s.boolean("tree_attenuation", render.tree_attenuation);
    s.integer("tessellation", geometry.tessellation, 3, 4096);
    s.enumeration("accel", geometry.accel, {{"bvh", Accel::bvh}, {"none", Accel::none}});
    if (const Json* aj = s.get("antialias")) {
        AntialiasDesc& aa = render.antialias;
        const Section a(*aj, s.key("antialias"),
                        {"mode", "samples", "filter", "jitter", "threshold", "max_level"});
        a.enumeration(
            "mode", aa.mode,
            {{"none", AaMode::none}, {"grid", AaMode::grid}, {"adaptive", AaMode::adaptive}});
        if (const Json* v = a.get("samples")) {
            const std::string key = a.key("samples");
            const char* what = "must be a perfect square in [1, 256] (1, 4, 9, 16, ...), got ";
            if (!v->is_number()) fail(key, "expected an integer, got " + describe(*v));
            const double d = v->get<double>();
            if (!(d >= 1 && d <= 256) || std::floor(d) != d) fail(key, what + v->dump());
            aa.samples = static_cast<int>(d);
            const int s_root = static_cast<int>(std::lround(std::sqrt(d)));
            if (s_root * s_root != aa.samples) fail(key, what + v->dump());
        }
        a.enumeration("filter", aa.filter, {{"box", AaFilter::box}, {"tent", AaFilter::tent}});
        a.boolean("jitter", aa.jitter);
        a.number("threshold", aa.threshold, kNonNegative);
        a.integer("max_level", aa.max_level, 0, 6);
    }
}

std::string preset_names() {
    std::string s;
    for (const Preset& p : presets()) {
        s += (s.empty() ? "" : ", ") + std::string(p.name) + "/" + std::string(p.alias);
    }
    return s;
}

/// The scene's materials: materials[0] is the default, then those of `materials` in file
/// order, then the presets and inline materials objects refer to, one entry per name.
class MaterialTable {
  public:
    explicit MaterialTable(std::vector<Material>& list) : list_(list) {
        list_.clear();
        Material def;  // SPEC §1: the slide's Ka = 0.1, Kd = 0.45
        def.name = "default";
        list_.push_back(def);
        by_name_["default"] = 0;
    }

    /// Reads the `materials` section. A material named "default" replaces the default one
    /// (the material of every object that names none).
    void read_section(const Json& j) {
        if (!j.is_object()) {
            fail("materials", "expected an object of named materials, got " + describe(j));
        }
        for (const auto& item : j.items()) {
            const std::string path = join("materials", item.key());
            Material m = read_material(item.value(), path);
            m.name = item.key();
            if (item.key() == "default") {
                list_[0] = m;
                by_name_[item.key()] = 0;
            } else {
                by_name_[item.key()] = static_cast<int>(list_.size());
                list_.push_back(m);
            }
        }
    }

    /// The `material` key of an object: a name from `materials`, a preset, or an inline object.
    int resolve(const Json& j, const std::string& path) {
        if (j.is_string()) {
            const std::string name = j.get<std::string>();
            if (const auto it = by_name_.find(name); it != by_name_.end()) return it->second;
            if (const Preset* p = find_preset(name)) {
                const auto it = by_preset_.find(p);
                if (it != by_preset_.end()) return it->second;
                Material m = p->material;
                m.name = std::string(p->name);
                by_preset_[p] = static_cast<int>(list_.size());
                list_.push_back(m);
                return by_preset_[p];
            }
            std::string defined;
            for (const auto& [n, i] : by_name_) defined += (defined.empty() ? "" : ", ") + n;
            fail(path, "unknown material \"" + name +
                           "\" (defined in materials: " + (defined.empty() ? "none" : defined) +
                           "; presets: " + preset_names() + ")");
        }
        if (j.is_object()) {
            Material m = read_material(j, path);
            m.name = path;
            list_.push_back(m);
            return static_cast<int>(list_.size()) - 1;
        }
        fail(path, "expected a material name or a material object, got " + describe(j));
    }

    /// Adds a material no key names (an MTL material); returns its index.
    int add(const Material& m) {
        list_.push_back(m);
        return static_cast<int>(list_.size()) - 1;
    }

  private:
    /// A material object: optionally `preset` first, then the constants it overrides.
    static Material read_material(const Json& j, const std::string& path) {
        const Section s(
            j, path,
            {"preset", "ka", "kd", "ks", "n", "reflection", "transparency", "ior", "checker"});
        Material m;
        if (const Json* p = s.get("preset")) {
            const std::string name = read_string(*p, s.key("preset"));
            const Preset* preset = find_preset(name);
            if (!preset) {
                fail(s.key("preset"),
                     "unknown preset \"" + name + "\" (known: " + preset_names() + ")");
            }
            m = preset->material;
        }
        s.rgb("ka", m.ka, kUnit);
        s.rgb("kd", m.kd, kUnit);
        s.rgb("ks", m.ks, kUnit);
        s.number("n", m.n, kPositive);
        s.number("reflection", m.reflection, kUnit);
        s.number("transparency", m.transparency, kUnit);
        s.number("ior", m.ior, Limits{1, std::numeric_limits<double>::infinity(), false, false});
        if (const Json* cj = s.get("checker")) {
            Checker c;
            const Section cs(*cj, s.key("checker"), {"size", "ka", "kd"});
            cs.number("size", c.size, kPositive);
            cs.rgb("ka", c.ka, kUnit);
            cs.rgb("kd", c.kd, kUnit);
            m.checker = c;
        }
        return m;
    }

    std::vector<Material>& list_;
    std::map<std::string, int> by_name_;
    std::map<const Preset*, int> by_preset_;
};

/// `transform`: p_world = T·Rz·Ry·Rx·S·p (SPEC §2).
Affine read_transform(const Json& j, const std::string& path, Vec3& scale, Vec3& rotate,
                      Vec3& translate) {
    const Section s(j, path, {"scale", "rotate", "translate"});
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

/// The keys each shape type accepts, in the order messages list them.
std::vector<std::string_view> keys_of(ShapeType t) {
    switch (t) {
        case ShapeType::sphere:
            return {"type", "center", "radius", "material", "transform"};
        case ShapeType::box:
            return {"type", "min", "max", "material", "transform"};
        case ShapeType::cylinder:
            return {"type", "base", "axis", "radius", "height", "caps", "material", "transform"};
        case ShapeType::cone:
            return {"type", "base", "axis", "radius", "height", "cap", "material", "transform"};
        case ShapeType::torus:
            return {"type",         "center",   "axis",     "major_radius",
                    "minor_radius", "material", "transform"};
        case ShapeType::plane:
            return {"type", "point", "normal", "material", "transform"};
        case ShapeType::triangle:
            return {"type", "vertices", "material", "transform"};
        case ShapeType::mesh:
            return {"type", "file", "smooth", "material", "transform"};
    }
    return {};
}

/// The OBJ files of the scene's meshes, each loaded once (SPEC §2 `mesh`).
class MeshFiles {
  public:
    explicit MeshFiles(SceneDesc& scene) : scene_(scene) {}

    /// Loads o.file into o.mesh. Without a `material` key, the MTL materials its faces use join
    /// the scene's materials (named "file.obj:name") and o.mesh_materials maps them. A built-in
    /// scene reads its meshes from the binary (embedded_files.h), other files from disk.
    void load(ObjectDesc& o, bool names_material, MaterialTable& materials) {
        const bool with_materials = !names_material;
        Loaded& l = loaded_[{o.file, with_materials}];
        if (!l.mesh) {
            const bool demo = scene_.source.rfind("demo:", 0) == 0;
            const TextReader read = [demo](const std::string& path, std::string& reason) {
                if (demo) {
                    if (const auto text = embedded_file(path))
                        return std::optional(std::string(*text));
                }
                return read_text_file(path, reason);
            };
            std::string reason;
            const std::optional<std::string> text = read(o.file, reason);
            if (!text) {
                throw InputError(scene_.source + ": " + o.path + ".file: cannot read " + o.file +
                                 ": " + reason);
            }
            l.mesh = std::make_shared<const MeshData>(
                parse_obj(*text, o.file, with_materials, read, scene_.warnings));
            if (with_materials) {
                for (const Material& m : l.mesh->materials)
                    l.scene_index.push_back(materials.add(m));
            }
        }
        o.mesh = l.mesh;
        o.mesh_materials = l.scene_index;
    }

  private:
    struct Loaded {
        std::shared_ptr<const MeshData> mesh;
        std::vector<int> scene_index;
    };
    SceneDesc& scene_;
    std::map<std::pair<std::string, bool>, Loaded> loaded_;
};

ObjectDesc read_object(const Json& j, const std::string& path, MaterialTable& materials,
                       const std::string& base_dir, MeshFiles& meshes) {
    if (!j.is_object()) fail(path, "expected an object, got " + describe(j));
    ObjectDesc o;
    o.path = path;
    const auto type_it = j.find("type");
    if (type_it == j.end()) {
        fail(path,
             "missing key \"type\" (one of: sphere, box, cylinder, cone, torus, plane, "
             "triangle, mesh)");
    }
    o.type = read_enum<ShapeType>(*type_it, join(path, "type"),
                                  {{"sphere", ShapeType::sphere},
                                   {"box", ShapeType::box},
                                   {"cylinder", ShapeType::cylinder},
                                   {"cone", ShapeType::cone},
                                   {"torus", ShapeType::torus},
                                   {"plane", ShapeType::plane},
                                   {"triangle", ShapeType::triangle},
                                   {"mesh", ShapeType::mesh}});
    const Section s(j, path, keys_of(o.type), join(path, "type"));

    switch (o.type) {
        case ShapeType::sphere:
            s.vec3("center", o.center);
            s.number("radius", o.radius, kPositive);
            break;
        case ShapeType::box:
            s.vec3("min", o.min);
            s.vec3("max", o.max);
            if (!(o.min.x < o.max.x && o.min.y < o.max.y && o.min.z < o.max.z)) {
                fail(s.key("max"),
                     "must be greater than min on every axis, got min " + format_vec(o.min) +
                         " and max " + format_vec(o.max),
                     path);
            }
            break;
        case ShapeType::cylinder:
        case ShapeType::cone:
            s.vec3("base", o.base);
            s.direction("axis", o.axis);
            s.number("radius", o.radius, kPositive);
            s.number("height", o.height, kPositive);
            s.boolean(o.type == ShapeType::cylinder ? "caps" : "cap", o.caps);
            break;
        case ShapeType::torus:
            s.vec3("center", o.center);
            s.direction("axis", o.axis);
            s.number("major_radius", o.major_radius, kPositive);
            s.number("minor_radius", o.minor_radius, kPositive);
            if (!(o.minor_radius < o.major_radius)) {
                fail(s.key("minor_radius"),
                     "must be < major_radius (" + format_number(o.major_radius) + "), got " +
                         format_number(o.minor_radius),
                     path);
            }
            break;
        case ShapeType::plane:
            s.vec3("point", o.point);
            s.direction("normal", o.normal);
            break;
        case ShapeType::triangle:
            if (const Json* v = s.get("vertices")) {
                const std::string key = s.key("vertices");
                if (!v->is_array() || v->size() != 3) {
                    fail(key, "expected an array of 3 points [x, y, z], got " + describe(*v));
                }
                for (std::size_t i = 0; i < 3; ++i)
                    o.vertices[i] = read_vec3((*v)[i], join(key, i));
            }
            {
                // Zero area: the edges are (nearly) parallel, |e1 × e2| ≈ 0 relative to |e1||e2|.
                const auto& p = o.vertices;
                const double e1[3] = {double(p[1].x) - p[0].x, double(p[1].y) - p[0].y,
                                      double(p[1].z) - p[0].z};
                const double e2[3] = {double(p[2].x) - p[0].x, double(p[2].y) - p[0].y,
                                      double(p[2].z) - p[0].z};
                const double c[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                                     e1[0] * e2[1] - e1[1] * e2[0]};
                const double cross_len = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
                const double l1 = std::sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
                const double l2 = std::sqrt(e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]);
                if (!(cross_len > 1e-7 * l1 * l2) || !(cross_len > 0)) {
                    fail(s.key("vertices"), "degenerate triangle (zero area): " + format_vec(p[0]) +
                                                ", " + format_vec(p[1]) + ", " + format_vec(p[2]));
                }
            }
            break;
        case ShapeType::mesh:
            if (const Json* v = s.get("file")) {
                o.file = read_string(*v, s.key("file"));
                if (o.file.empty()) fail(s.key("file"), "must not be empty");
            } else {
                fail(path, "missing key \"file\" (the OBJ file of the mesh)");
            }
            if (!base_dir.empty() && !std::filesystem::path(o.file).is_absolute()) {
                o.file = (std::filesystem::path(base_dir) / o.file).string();
            }
            s.boolean("smooth", o.smooth);
            break;
    }
    if (const Json* m = s.get("material")) o.material = materials.resolve(*m, s.key("material"));
    if (const Json* t = s.get("transform"))
        o.transform = read_transform(*t, s.key("transform"), o.scale, o.rotate, o.translate);
    if (o.type == ShapeType::mesh) meshes.load(o, s.get("material") != nullptr, materials);
    return o;
}

/// Where the implicit light sits: at the camera's upper left, half the viewing distance away:
/// position + (−u + v)·(0.5·|position − look_at|), with u, v as in SPEC §1.3.
Vec3 upper_left_of_camera(const CameraDesc& c) {
    const Vec3 w = normalize(c.position - c.look_at);
    const Vec3 u = normalize(cross(c.up, w));
    const Vec3 v = cross(w, u);
    return c.position + (v - u) * (0.5f * length(c.position - c.look_at));
}

void read_lights(const Json* j, SceneDesc& scene) {
    const Vec3 default_position = upper_left_of_camera(scene.camera);
    if (j) {
        if (!j->is_array()) fail("lights", "expected an array of lights, got " + describe(*j));
        for (std::size_t i = 0; i < j->size(); ++i) {
            const Section s((*j)[i], join("lights", i), {"position", "intensity", "radius"});
            Light light;
            light.position =
                default_position;  // a light without position: where the implicit one sits
            s.vec3("position", light.position);
            s.rgb("intensity", light.intensity, kNonNegative);
            s.number("radius", light.radius, kNonNegative);
            scene.lights.push_back(light);
        }
    }
    if (scene.lights.empty()) {
        // No lights: one white light at the camera's upper left. Under `lambert` Il = 1 (the
        // slide's value). Under `phong` Il/(d+K) would make Il = 1 very dim, so Il = d + K with
        // d the light's distance to look_at: Il/(d+K) = 1 at the look-at point (SPEC §1 model 2).
        Light light;
        light.position = default_position;
        const float Il = scene.render.model == Model::lambert
                             ? 1.0f
                             : length(light.position - scene.camera.look_at) + scene.attenuation_k;
        light.intensity = Rgb(Il);
        scene.lights.push_back(light);
    }
}

/// The document (overrides already applied) → SceneDesc. Throws KeyError.
void read_scene(const Json& doc, const std::string& base_dir, SceneDesc& scene) {
    const Section top(doc, "",
                      {"image", "camera", "render", "ambient", "attenuation_k", "lights",
                       "materials", "objects"});
    if (const Json* j = top.get("image")) read_image(*j, scene.image);
    read_camera(top.get("camera"), scene.camera);
    if (const Json* j = top.get("render")) read_render(*j, scene.render, scene.geometry);
    top.rgb("ambient", scene.ambient, kNonNegative);
    top.number("attenuation_k", scene.attenuation_k, kPositive);

    MaterialTable materials(scene.materials);
    MeshFiles meshes(scene);
    if (const Json* j = top.get("materials")) materials.read_section(*j);
    if (const Json* j = top.get("objects")) {
        if (!j->is_array()) fail("objects", "expected an array of objects, got " + describe(*j));
        for (std::size_t i = 0; i < j->size(); ++i) {
            scene.objects.push_back(
                read_object((*j)[i], join("objects", i), materials, base_dir, meshes));
        }
    }
    read_lights(top.get("lights"), scene);
}

// ---------------------------------------------------------------------------------------------
// JSON text.

/// nlohmann's message without its "[json.exception…] parse error at line…:" prefix.
std::string strip_exception_prefix(std::string s) {
    if (s.rfind("[json.exception", 0) == 0) {
        const auto close = s.find("] ");
        if (close != std::string::npos) s = s.substr(close + 2);
    }
    if (s.rfind("parse error", 0) == 0) {
        const auto colon = s.find(": ");
        if (colon != std::string::npos) s = s.substr(colon + 2);
    }
    if (s.rfind("syntax error ", 0) == 0) s = s.substr(13);
    return s;
}

/// A SAX pass that only records where and why parsing failed (the DOM parser's exceptions do
/// not all carry the position, e.g. number overflow).
struct ErrorLocator : nlohmann::json_sax<Json> {
    std::size_t position = 0;
    std::string token, message;
    int id = 0;
    bool null() override { return true; }
    bool boolean(bool) override { return true; }
    bool number_integer(number_integer_t) override { return true; }
    bool number_unsigned(number_unsigned_t) override { return true; }
    bool number_float(number_float_t, const string_t&) override { return true; }
    bool string(string_t&) override { return true; }
    bool binary(binary_t&) override { return true; }
    bool start_object(std::size_t) override { return true; }
    bool key(string_t&) override { return true; }
    bool end_object() override { return true; }
    bool start_array(std::size_t) override { return true; }
    bool end_array() override { return true; }
    bool parse_error(std::size_t pos, const std::string& last_token,
                     const nlohmann::detail::exception& ex) override {
        position = pos;
        token = last_token;
        message = ex.what();
        id = ex.id;
        return false;
    }
};

/// Line and column (1-based; columns count UTF-8 characters) of byte `offset` in `text`.
std::pair<int, int> line_column(std::string_view text, std::size_t offset) {
    offset = std::min(offset, text.size());
    int line = 1, column = 1;
    for (std::size_t i = 0; i < offset; ++i) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (c == '\n') {
            ++line;
            column = 1;
        } else if ((c & 0xC0) != 0x80) {  // not a UTF-8 continuation byte
            ++column;
        }
    }
    return {line, column};
}

/// Deepest nesting of arrays and objects accepted (a scene needs 5). Deeper text is refused
/// before parsing: nlohmann's dump() recurses, and "got …" messages dump values.
constexpr int kMaxJsonNesting = 64;

/// Byte offset of the first '[' or '{' nested deeper than kMaxJsonNesting outside strings, or
/// npos.
std::size_t too_deep_at(std::string_view text) {
    int depth = 0;
    bool in_string = false, escaped = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (in_string) {
            if (escaped) {
                escaped = false;
            } else if (c == '\\') {
                escaped = true;
            } else if (c == '"') {
                in_string = false;
            }
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++depth > kMaxJsonNesting) return i;
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
    return std::string_view::npos;
}

/// Parses JSON text; on failure throws InputError "FILE:LINE:COL: JSON syntax error: …".
Json parse_text(std::string_view text, const std::string& file) {
    if (const std::size_t at = too_deep_at(text); at != std::string_view::npos) {
        const auto [line, column] = line_column(text, at);
        throw InputError(file + ":" + std::to_string(line) + ":" + std::to_string(column) +
                         ": JSON nested deeper than " + std::to_string(kMaxJsonNesting) +
                         " levels");
    }
    try {
        return Json::parse(text);
    } catch (const Json::exception&) {
        ErrorLocator locator;
        Json::sax_parse(text, &locator);
        // The position counts the characters read: the offending one is at position − 1. For a
        // number overflow the position is just past the number: point at its start instead.
        std::size_t offset = locator.position > 0 ? locator.position - 1 : 0;
        std::string what = "JSON syntax error: " + strip_exception_prefix(locator.message);
        if (locator.id == 406) {
            offset = locator.position >= locator.token.size()
                         ? locator.position - locator.token.size()
                         : 0;
            what = "number out of range: " + locator.token + " is not a finite number";
        }
        const auto [line, column] = line_column(text, offset);
        throw InputError(file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " +
                         what);
    }
}

// ---------------------------------------------------------------------------------------------
// Overrides.

std::string override_label(const Override& o) {
    if (o.origin == "--set") return "--set " + o.path + "=" + o.json;
    return o.origin + " " + o.json;
}

/// A word a user would not quote on a command line (raytrace, demo, bunny.obj): starts with a
/// letter or '_' and holds only letters, digits and _ - . /
bool is_bare_word(std::string_view s) {
    if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) {
        return false;
    }
    for (char ch : s) {
        const auto c = static_cast<unsigned char>(ch);
        if (!(std::isalnum(c) || c == '_' || c == '-' || c == '.' || c == '/')) return false;
    }
    return true;
}

/// The value of an override. Text that is not valid JSON but is a bare word (`--set
/// render.pipeline=raytrace`) is taken as that string: what a user typing a shell command
/// expects, since the shell has already eaten any quotes.
Json override_value(const Override& o) {
    if (too_deep_at(o.json) != std::string_view::npos) {
        throw InputError(override_label(o) + ": JSON nested deeper than " +
                         std::to_string(kMaxJsonNesting) + " levels");
    }
    try {
        return Json::parse(o.json);
    } catch (const Json::exception& e) {
        if (is_bare_word(o.json)) return Json(o.json);
        const std::string what = strip_exception_prefix(e.what());
        if (e.id == 406) throw InputError(override_label(o) + ": number out of range: " + what);
        throw InputError(override_label(o) + ": JSON syntax error: " + what);
    }
}

std::vector<std::string> split_path(const Override& o) {
    std::vector<std::string> segments;
    if (o.path.empty()) throw InputError(override_label(o) + ": empty key path");
    std::size_t start = 0;
    while (true) {
        const std::size_t dot = o.path.find('.', start);
        segments.push_back(o.path.substr(start, dot - start));
        if (segments.back().empty()) {
            throw InputError(override_label(o) + ": empty segment in key path \"" + o.path + "\"");
        }
        if (dot == std::string::npos) break;
        start = dot + 1;
    }
    return segments;
}

bool is_index(std::string_view s) {
    if (s.empty() || s.size() > 9) return false;
    for (char c : s) {
        if (c < '0' || c > '9') return false;
    }
    return true;
}

/// Sets the value at the override's dotted path in `doc`. A numeric segment indexes an array
/// (index == size appends a new element), a missing object key is created (as an array when
/// the next segment is an index, else as an object). Returns the shallowest key path the
/// override created or replaced: errors found under it are the override's.
std::string apply_override(Json& doc, const Override& o) {
    const std::vector<std::string> segments = split_path(o);
    Json value = override_value(o);
    Json* node = &doc;
    std::string at, root;
    for (std::size_t i = 0; i < segments.size(); ++i) {
        const std::string& seg = segments[i];
        const bool last = i + 1 == segments.size();
        const auto fresh = [&] {
            if (last) return Json();
            return is_index(segments[i + 1]) ? Json::array() : Json::object();
        };
        const std::string here = join(at, seg);
        if (node->is_object()) {
            if (node->find(seg) == node->end()) {
                if (root.empty()) root = here;
                (*node)[seg] = fresh();
            }
            node = &(*node)[seg];
        } else if (node->is_array()) {
            if (!is_index(seg)) {
                throw InputError(override_label(o) + ": " + (at.empty() ? "the scene" : at) +
                                 " is an array: \"" + seg + "\" is not an index");
            }
            const std::size_t index = std::stoul(seg);
            if (index > node->size()) {
                throw InputError(override_label(o) + ": index " + seg + " is past the end of " +
                                 at + " (size " + std::to_string(node->size()) + "; use index " +
                                 std::to_string(node->size()) + " to append)");
            }
            if (index == node->size()) {
                if (root.empty()) root = here;
                node->push_back(fresh());
            }
            node = &(*node)[index];
        } else {
            throw InputError(override_label(o) + ": " + (at.empty() ? "the scene" : at) + " is " +
                             describe(*node) + ", not an object or array: cannot set \"" + seg +
                             "\" in it");
        }
        at = here;
    }
    *node = std::move(value);
    return root.empty() ? o.path : root;
}

}  // namespace

Override parse_set(const std::string& arg) {
    const std::size_t eq = arg.find('=');
    if (eq == std::string::npos) {
        throw InputError("--set " + arg + ": expected PATH=JSON, e.g. objects.0.radius=2");
    }
    Override o{arg.substr(0, eq), arg.substr(eq + 1), "--set"};
    split_path(o);      // an empty path or segment
    override_value(o);  // a value that is neither JSON nor a bare word
    return o;
}

SceneDesc parse_scene(std::string_view json_text, const std::string& file,
                      const std::string& base_dir, const std::vector<Override>& overrides) {
    Json doc = parse_text(json_text, file);

    std::vector<std::string> roots;  // per override: what it created or replaced
    roots.reserve(overrides.size());
    for (const Override& o : overrides) roots.push_back(apply_override(doc, o));

    SceneDesc scene;
    scene.source = file;
    if (file.rfind("demo:", 0) == 0) {
        scene.name = file.substr(5);
    } else {
        scene.name = std::filesystem::path(file).stem().string();
    }
    if (scene.name.empty()) scene.name = "scene";

    try {
        read_scene(doc, base_dir, scene);
    } catch (const KeyError& e) {
        // The latest override that put the bad value there (or, for a check across keys, that
        // changed one of the keys involved) is to blame; otherwise the file.
        for (std::size_t i = overrides.size(); i-- > 0;) {
            const Override& o = overrides[i];
            if (!e.path.empty() &&
                (is_under(e.path, roots[i]) || (!e.scope.empty() && is_under(roots[i], e.scope)))) {
                const bool same = e.path == o.path && o.origin == "--set";
                throw InputError(override_label(o) + ": " + (same ? "" : e.path + ": ") + e.what);
            }
        }
        throw InputError(file + ": " + (e.path.empty() ? "" : e.path + ": ") + e.what);
    }
    return scene;
}

SceneDesc load_scene(const std::string& source, const std::vector<Override>& overrides) {
    if (source.rfind("demo:", 0) == 0) {
        const std::string name = source.substr(5);
        const DemoScene* demo = find_demo(name);
        if (!demo) {
            std::string known;
            for (const DemoScene& d : demo_scenes()) {
                known += (known.empty() ? "" : ", ") + std::string("demo:") + std::string(d.name);
            }
            throw InputError(source + ": no such built-in scene (known: " + known + ")");
        }
        return parse_scene(demo->json, source, "", overrides);
    }

    std::error_code ec;
    if (std::filesystem::is_directory(source, ec)) {
        throw InputError(source + ": cannot read: is a directory");
    }
    std::FILE* f = std::fopen(source.c_str(), "rb");
    if (!f) throw InputError(source + ": cannot read: " + std::strerror(errno));
    std::string text;
    char buffer[1 << 16];
    std::size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0) text.append(buffer, n);
    const bool failed = std::ferror(f) != 0;
    const int err = errno;
    std::fclose(f);
    if (failed) throw InputError(source + ": cannot read: " + std::strerror(err));

    const std::string base_dir = std::filesystem::path(source).parent_path().string();
    return parse_scene(text, source, base_dir, overrides);
}

}  // namespace luz
