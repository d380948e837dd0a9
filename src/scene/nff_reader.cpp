// NFF statements (docs/SCENES.md#nff) read one by one into the document of the same scene, the
// polygons of each material gathered into one mesh (see nff_reader.h).
#include "scene/nff_reader.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "scene/cancel.h"
#include "scene/message_text.h"
#include "scene/nff_shapes.h"
#include "scene/nff_statements.h"
#include "scene/number_text.h"
#include "scene/obj_text.h"
#include "scene/triangulate.h"

namespace luz::loader {
namespace {

using nff_text::Keyword;
using nff_text::keyword_of;
using nff_text::shape_lines;
using nff_text::Statements;
using obj_text::fail_at;
using obj_text::read_numbers;
using obj_text::Tokens;

/// Most vertices one polygon may announce (far beyond any SPD polygon).
constexpr double kMaxPolygonVertices = 1e8;

/// The polygons of one material, as one mesh.
struct PolygonMesh {
    MeshData data;
    std::size_t object = 0;  ///< its entry in `objects`
    bool smooth = false;     ///< a `pp` patch is in it: its vertex normals are interpolated
};

class NffReader {
  public:
    NffReader(std::string_view text, const std::string& file, const std::string& base_dir,
              bool direct)
        : statements_(text), file_(file), base_dir_(base_dir) {
        if (!direct) return;
        NffScene::Direct& d = scene_.direct.emplace();
        // Room for every line that starts with s or c: vectors grown one by one move their
        // elements at every doubling, onto pages the kernel must fault in. At most a million
        // up front (~100 MB): beyond, they grow as the file proves it holds more.
        const std::size_t n = std::min<std::size_t>(shape_lines(text), 1 << 20);
        d.objects.reserve(n);
        d.materials.reserve(n);
        d.order.reserve(n);
        scene_.object_lines.reserve(n);
    }

    NffScene read() {
        std::string_view line;
        while (statements_.next(line)) {
            check_cancel();
            Tokens tokens(line);
            std::string_view keyword;
            tokens.next(keyword);
            statement(keyword, tokens);
        }
        if (!camera_line_) {
            fail_at(file_, std::max<std::size_t>(statements_.line(), 1),
                    "no \"v\" statement (the viewpoint, which an NFF file starts with)");
        }
        finish();
        return std::move(scene_);
    }

  private:
    void statement(std::string_view keyword, Tokens& tokens) {
        const Keyword k = keyword_of(keyword);
        if (k == Keyword::b) {
            float c[3];
            read_numbers(tokens, c, 3, 3, file_, line(), "b");
            background_ = Vec3(c[0], c[1], c[2]);
            scene_.lines["image.background"] = line();
            return;
        }
        if (k == Keyword::v) {
            if (camera_line_)
                fail_at(file_, line(),
                        "v: a second viewpoint (the first is at line " +
                            std::to_string(camera_line_) + ")");
            if (!tokens.rest().empty()) {
                fail_at(file_, line(),
                        "v: expected nothing after \"v\", got " + quote(tokens.rest()));
            }
            viewpoint();
            return;
        }
        if (k == Keyword::unknown) {
            fail_at(file_, line(),
                    "unknown statement " + quote(keyword) +
                        " (NFF statements: v, b, l, f, s, c, p, pp; # starts a comment)");
        }
        if (!camera_line_) {
            fail_at(file_, line(),
                    std::string(keyword) +
                        ": before \"v\" (the viewpoint must come first; only b may precede it)");
        }
        if (k == Keyword::l) {
            light(tokens);
        } else if (k == Keyword::f) {
            material(tokens);
        } else if (k == Keyword::s) {
            float s[4];
            read_numbers(tokens, s, 4, 4, file_, line(), "s");
            NffShape sphere;
            sphere.point = Vec3(s[0], s[1], s[2]);
            sphere.radius = std::fabs(s[3]);
            add_shape(sphere, line());
        } else if (k == Keyword::c) {
            cone(tokens);
        } else {
            polygon(tokens, k == Keyword::pp);
        }
    }

    std::size_t line() const { return statements_.line(); }

    /// The next statement line of a statement that began at `first` (`what()` names what was
    /// expected there, for the message only); the file must not end before it.
    template <class What>
    Tokens continuation(std::string_view statement, std::size_t first, const What& what) {
        std::string_view text;
        if (!statements_.next(text)) {
            fail_at(file_, first,
                    std::string(statement) + ": the file ends before " + what() + " (line " +
                        std::to_string(first) + " on)");
        }
        return Tokens(text);
    }

    /// `v` and its lines: from, at, up, angle, hither, resolution, in that order.
    void viewpoint() {
        camera_line_ = line();
        const auto field = [&](const char* name, float* out, int count, const char* key) {
            Tokens t = continuation("v", camera_line_,
                                    [&] { return "its \"" + std::string(name) + "\" line"; });
            std::string_view keyword;
            t.next(keyword);
            if (keyword != name) {
                fail_at(file_, line(),
                        "v: expected \"" + std::string(name) +
                            "\" here (v is followed by from, "
                            "at, up, angle, hither and resolution), got " +
                            quote(keyword));
            }
            read_numbers(t, out, count, count, file_, line(), name);
            if (key) scene_.lines[key] = line();
        };
        float from[3], at[3], up[3], angle, hither, resolution[2];
        field("from", from, 3, "camera.position");
        field("at", at, 3, "camera.look_at");
        field("up", up, 3, "camera.up");
        field("angle", &angle, 1, "camera.fov_y");
        const std::size_t angle_line = line();
        field("hither", &hither, 1, nullptr);  // ignored (docs/SCENES.md#nff)
        field("resolution", resolution, 2, "image");
        for (float r : resolution) {
            if (!(r >= 1 && r <= 65536 && r == std::floor(r))) {
                fail_at(file_, line(),
                        "resolution: expected two whole numbers in [1, 65536], got " +
                            format_number(resolution[0]) + " " + format_number(resolution[1]));
            }
        }
        if (!(angle > 0 && angle < 180)) {
            fail_at(file_, angle_line,
                    "angle: must be in (0, 180) degrees, got " + format_number(angle));
        }
        width_ = static_cast<int>(resolution[0]);
        height_ = static_cast<int>(resolution[1]);
        // `angle` spans the centres of the top and bottom pixel rows: the image's edges lie
        // half a pixel further out, fov_y = 2·atan(tan(angle/2)·H/(H − 1)).
        const double half = angle * kDegree / 2;
        const double H = height_;
        const double fov_y = H > 1 ? 2 * std::atan(std::tan(half) * H / (H - 1)) / kDegree : angle;
        scene_.lines["camera"] = camera_line_;
        scene_.doc["image"] = {{"width", width_}, {"height", height_}};
        scene_.doc["camera"] = {{"projection", "perspective"},
                                {"position", json_vec({from[0], from[1], from[2]})},
                                {"look_at", json_vec({at[0], at[1], at[2]})},
                                {"up", json_vec({up[0], up[1], up[2]})},
                                {"fov_y", fov_y}};
    }

    void light(Tokens& tokens) {
        float l[6];
        const int n = read_numbers(tokens, l, 3, 6, file_, line(), "l");
        if (n != 3 && n != 6) {
            fail_at(file_, line(),
                    "l: expected 3 numbers (x y z) or 6 (x y z r g b), got " + std::to_string(n));
        }
        scene_.lines["lights." + std::to_string(lights_.size())] = line();
        lights_.push_back({Vec3(l[0], l[1], l[2]), n == 6, Vec3(l[3], l[4], l[5])});
    }

    /// `f r g b Kd Ks Shine T ior`: identical lines share one material, f1, f2, … in order.
    void material(Tokens& tokens) {
        std::array<float, 8> f;
        read_numbers(tokens, f.data(), 8, 8, file_, line(), "f");
        const auto [it, added] = material_names_.try_emplace(f, "");
        if (added) {
            it->second = "f" + std::to_string(material_names_.size());
            scene_.lines["materials." + it->second] = line();
            const float Kd = f[3], Ks = f[4];
            const Json kd = json_vec({Kd * f[0], Kd * f[1], Kd * f[2]});
            materials_[it->second] = {{"ka", kd},
                                      {"kd", kd},
                                      {"ks", Ks},
                                      {"n", f[5]},
                                      {"reflection", Ks},
                                      {"transparency", f[6]},
                                      {"ior", std::max(f[7], 1.0f)}};
        }
        material_ = it->second;
        material_index_ = static_cast<int>(
            std::distance(material_order_.begin(),
                          std::find(material_order_.begin(), material_order_.end(), material_)));
        if (material_index_ == static_cast<int>(material_order_.size())) {
            material_order_.push_back(material_);
        }
    }

    /// `c`: base point and radius, apex point and radius, on the line or the two after it.
    void cone(Tokens& tokens) {
        const std::size_t first = line();
        float c[8];
        const int n = read_numbers(tokens, c, 0, 8, file_, line(), "c");
        if (n == 0) {
            Tokens base = continuation("c", first, [] { return "its base line (x y z radius)"; });
            read_numbers(base, c, 4, 4, file_, line(), "c base");
            Tokens apex = continuation("c", first, [] { return "its apex line (x y z radius)"; });
            read_numbers(apex, c + 4, 4, 4, file_, line(), "c apex");
        } else if (n != 8) {
            fail_at(file_, line(),
                    "c: expected 8 numbers (base x y z radius, apex x y z radius) or none (then "
                    "on the two lines after it), got " +
                        std::to_string(n));
        }
        Vec3 base(c[0], c[1], c[2]), apex(c[4], c[5], c[6]);
        float r0 = std::fabs(c[3]), r1 = std::fabs(c[7]);
        const double dx = double(apex.x) - base.x, dy = double(apex.y) - base.y,
                     dz = double(apex.z) - base.z;
        const double height = std::sqrt(dx * dx + dy * dy + dz * dz);
        if (!(height > 0) || !std::isfinite(height)) {
            fail_at(file_, first,
                    "c: base and apex must be distinct points at a finite distance, got " +
                        format_vec(base) + " and " + format_vec(apex));
        }
        NffShape shape;
        shape.type = ShapeType::cylinder;
        shape.radius = r0;
        shape.height = height;
        double sign = 1 / height;
        if (r0 != r1) {
            shape.type = ShapeType::cone;
            if (r1 > r0) {  // the wider end is the cone's base
                std::swap(base, apex);
                std::swap(r0, r1);
                sign = -sign;
            }
            shape.radius = r0;
            shape.apex_radius = r1;
        }
        shape.point = base;
        // a cylinder's axis as dx/height, a cone's as dx·(±1/height): the document's own values
        const bool cylinder = shape.type == ShapeType::cylinder;
        shape.axis[0] = cylinder ? dx / height : sign * dx;
        shape.axis[1] = cylinder ? dy / height : sign * dy;
        shape.axis[2] = cylinder ? dz / height : sign * dz;
        add_shape(shape, first);
    }

    /// The N of `p N` or `pp N`, whole: read as a double (a count above 2²⁴ is exact too, a
    /// float's is not), after read_numbers() checked that it is one number.
    double vertex_count(Tokens& tokens, const char* name) {
        std::string_view token;
        Tokens(tokens).next(token);  // the token read_numbers() reads, as text
        float as_float = 0;
        read_numbers(tokens, &as_float, 1, 1, file_, line(), name);
        double count = as_float;
        std::from_chars(token.data(), token.data() + token.size(), count);
        if (count != std::floor(count)) {
            fail_at(file_, line(),
                    std::string(name) + ": expected a whole number of vertices, got " +
                        format_number(count));
        }
        return count;
    }

    /// `p N` (N lines x y z) or `pp N` (N lines x y z nx ny nz), triangulated into the mesh of
    /// the current material.
    void polygon(Tokens& tokens, bool patch) {
        const char* name = patch ? "pp" : "p";
        const std::size_t first = line();
        const double count = vertex_count(tokens, name);
        if (count < 3) {
            fail_at(file_, line(),
                    std::string(name) + ": a polygon needs at least 3 vertices, got " +
                        format_number(count));
        }
        if (count > kMaxPolygonVertices) {
            fail_at(file_, line(),
                    std::string(name) + ": a polygon may have at most " +
                        format_number(kMaxPolygonVertices) + " vertices, got " +
                        format_number(count));
        }
        const auto n = static_cast<std::size_t>(count);
        corners_.clear();
        normals_.clear();
        const int numbers = patch ? 6 : 3;
        for (std::size_t i = 0; i < n; ++i) {
            Tokens t = continuation(name, first, [&] {
                return "its " + std::to_string(n) + " vertices (it has " + std::to_string(i) + ")";
            });
            float v[6];
            read_numbers(t, v, numbers, numbers, file_, line(),
                         patch ? "pp vertex (x y z nx ny nz)" : "p vertex (x y z)");
            corners_.emplace_back(v[0], v[1], v[2]);
            if (patch) normals_.emplace_back(v[3], v[4], v[5]);
        }
        triangles_.clear();
        triangulate_polygon(corners_, triangles_);
        if (triangles_.empty()) return;  // no area: nothing to see

        PolygonMesh& m = mesh(first);
        MeshData& d = m.data;
        const auto p0 = static_cast<uint32_t>(d.positions.size());
        const auto n0 = static_cast<int32_t>(d.normals.size());
        d.positions.insert(d.positions.end(), corners_.begin(), corners_.end());
        d.normals.insert(d.normals.end(), normals_.begin(), normals_.end());
        m.smooth = m.smooth || patch;
        for (const auto& tri : triangles_) {
            for (uint32_t k : tri) {
                d.position.push_back(p0 + k);
                d.normal.push_back(patch ? n0 + static_cast<int32_t>(k) : -1);
            }
            d.material.push_back(-1);
        }
    }

    /// The mesh of the current material, its object added at `first` if new.
    PolygonMesh& mesh(std::size_t first) {
        auto [it, added] = meshes_.try_emplace(material_index_);
        if (added) {
            const std::string stem = std::filesystem::path(file_).filename().string();
            it->second.data.file = stem + "#" + (material_.empty() ? "default" : material_);
            it->second.object = objects_.size();
            add_object({{"type", "mesh"}, {"file", it->second.data.file}, {"smooth", false}},
                       first);
        }
        return it->second;
    }

    void add_object(Json object, std::size_t at = 0) {
        if (!material_.empty()) {  // appended: no object has the key yet
            object.get_ref<Json::object_t&>().emplace_back("material", material_);
        }
        scene_.object_lines.push_back(at ? at : line());
        if (scene_.direct) scene_.direct->order.push_back(-1 - std::int64_t(objects_.size()));
        objects_.push_back(std::move(object));
    }

    /// A sphere, cylinder or cone of the current material, from line `at`: read directly
    /// (NffScene::direct) or into the document.
    void add_shape(const NffShape& shape, std::size_t at) {
        if (!scene_.direct) {
            add_object(shape_json(shape), at);
            return;
        }
        NffScene::Direct& d = *scene_.direct;
        scene_.object_lines.push_back(at);
        d.order.push_back(std::int64_t(d.objects.size()));
        shape_object(shape);  // checked now: NffNotDirect sends the file to the document
        d.objects.push_back(shape);
        d.materials.push_back(material_);
    }

    /// The settings the file implies (docs/SCENES.md#nff), the lights' intensities, the meshes.
    void finish() {
        Json& doc = scene_.doc;
        doc["image"]["background"] = json_vec(background_);
        doc["render"] = {{"pipeline", "raytrace"},
                         {"model", "phong"},
                         {"max_depth", 4},
                         {"tree_attenuation", false},
                         {"min_weight", 0}};
        // Ia = √L/(2L), the SPD's suggestion (L = 1 when the file has no light).
        const double L = std::max<double>(lights_.size(), 1);
        doc["ambient"] = std::sqrt(L) / (2 * L);
        doc["attenuation"] = "none";  // NFF lights do not fade with distance
        doc["lights"] = Json::array();
        for (const NffLight& l : lights_) {
            const Vec3 I = l.coloured ? l.colour : Vec3(float(1 / std::sqrt(L)));
            doc["lights"].push_back(
                {{"position", json_vec(l.position)}, {"intensity", json_vec(I)}});
        }
        doc["materials"] = Json::object();
        for (const std::string& name : material_order_) {
            doc["materials"][name] = std::move(materials_[name]);
        }
        for (auto& [material, m] : meshes_) {
            objects_[m.object]["smooth"] = m.smooth;
            std::string file = m.data.file;
            if (!base_dir_.empty()) file = (std::filesystem::path(base_dir_) / file).string();
            scene_.meshes[{file, material < 0}] =
                std::make_shared<const MeshData>(std::move(m.data));
        }
        doc["objects"] = std::move(objects_);
    }

    static constexpr double kDegree = 3.14159265358979323846 / 180;

    struct NffLight {
        Vec3 position;
        bool coloured;
        Vec3 colour;
    };

    Statements statements_;
    const std::string& file_;
    const std::string& base_dir_;
    NffScene scene_;
    std::size_t camera_line_ = 0;
    int width_ = 0, height_ = 0;
    Vec3 background_{0.0f};
    std::vector<NffLight> lights_;
    std::map<std::array<float, 8>, std::string> material_names_;
    std::map<std::string, Json> materials_;
    std::vector<std::string> material_order_;
    std::string material_;     ///< the current material's name ("" before any `f`)
    int material_index_ = -1;  ///< its index in material_order_ (−1 before any `f`)
    std::map<int, PolygonMesh> meshes_;
    Json objects_ = Json::array();
    std::vector<Vec3> corners_, normals_;
    std::vector<std::array<uint32_t, 3>> triangles_;
};

/// N when `path` is "objects.N" (N written as std::to_string writes it).
std::optional<std::size_t> object_index(std::string_view path) {
    constexpr std::string_view kObjects = "objects.";
    if (!path.starts_with(kObjects)) return std::nullopt;
    const std::string_view digits = path.substr(kObjects.size());
    std::size_t n = 0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
    if (ec != std::errc() || end != digits.data() + digits.size() ||
        (digits.size() > 1 && digits[0] == '0')) {
        return std::nullopt;
    }
    return n;
}

}  // namespace

bool is_nff_file(std::string_view label) {
    if (label.size() < 4) return false;
    std::string tail(label.substr(label.size() - 4));
    for (char& c : tail) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return tail == ".nff";
}

std::size_t NffScene::line_of(std::string_view path) const {
    std::string p(path);
    while (!p.empty()) {
        if (const auto n = object_index(p); n && *n < object_lines.size()) return object_lines[*n];
        if (const auto it = lines.find(p); it != lines.end()) return it->second;
        const std::size_t dot = p.rfind('.');
        if (dot == std::string::npos) break;
        p.resize(dot);
    }
    return 0;
}

NffScene read_nff(std::string_view text, const std::string& file, const std::string& base_dir,
                  bool direct) {
    return NffReader(text, file, base_dir, direct).read();
}

}  // namespace luz::loader
