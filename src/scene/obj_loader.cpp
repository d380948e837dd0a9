// OBJ/MTL loading: a checking pass over the text (numbers, indices, face sizes → FILE:LINE
// errors), then tinyobjloader parses, and faces are triangulated (scene/triangulate.h); MTL
// constants are mapped per docs/SCENES.md#scene-files.
#include "scene/obj_loader.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <istream>
#include <limits>
#include <map>
#include <stdexcept>
#include <streambuf>
#include <unordered_set>

#include "scene/cancel.h"
#include "scene/message_text.h"
#include "scene/mtl_scan.h"
#include "scene/obj_text.h"
#include "scene/triangulate.h"

namespace luz {
namespace {

using namespace obj_text;

/// Counts of the vertex data defined so far (OBJ indices refer to these).
struct Counts {
    size_t v = 0, vt = 0, vn = 0;
};

/// One index of a vertex reference: 1-based, or negative (relative to the count so far).
void check_index(std::string_view s, size_t count, const char* what, const char* whats,
                 std::string_view token, const std::string& file, size_t line,
                 std::string_view statement) {
    long long k = 0;
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), k);
    const bool number = !s.empty() && ec == std::errc() && ptr == s.data() + s.size();
    const bool in_range = k > 0 ? static_cast<unsigned long long>(k) <= count
                                : k < 0 && static_cast<unsigned long long>(-(k + 1)) < count;
    if (number && in_range) return;  // the usual case, without building any message
    const std::string where = std::string(statement) + ": ";
    if (!number) {
        fail_at(file, line, where + "malformed vertex reference " + quote(token));
    }
    if (k == 0) {
        fail_at(file, line, where + "index 0 in " + quote(token) + " (OBJ indices start at 1)");
    }
    fail_at(file, line,
            where + std::string(what) + " index " + std::to_string(k) + " in " + quote(token) +
                " out of range: " + std::to_string(count) + " " + (count == 1 ? what : whats) +
                " defined before this line");
}

/// A vertex reference v, v/vt, v/vt/vn or v//vn.
void check_reference(std::string_view token, const Counts& c, const std::string& file, size_t line,
                     std::string_view statement) {
    std::string_view parts[3];
    int n = 0;
    size_t start = 0;
    for (;;) {
        const size_t slash = token.find('/', start);
        if (n == 3) {
            fail_at(file, line,
                    std::string(statement) + ": malformed vertex reference " + quote(token) +
                        " (expected v, v/vt, v/vt/vn or v//vn)");
        }
        parts[n++] = token.substr(start, slash == std::string_view::npos ? slash : slash - start);
        if (slash == std::string_view::npos) break;
        start = slash + 1;
    }
    check_index(parts[0], c.v, "vertex", "vertices", token, file, line, statement);
    if (n == 2 || (n == 3 && !parts[1].empty())) {
        check_index(parts[1], c.vt, "texture coordinate", "texture coordinates", token, file, line,
                    statement);
    }
    if (n == 3) check_index(parts[2], c.vn, "normal", "normals", token, file, line, statement);
}

/// tinyobjloader's skin weights (unused here): "vw VERTEX JOINT WEIGHT JOINT WEIGHT …". A joint
/// that is not a number in int range would be undefined behaviour in its conversion (found by
/// fuzzing).
void check_skin_weights(Tokens& tokens, const std::string& file, size_t line) {
    std::string_view token;
    tokens.next(token);  // the vertex: read by atoi, any text goes
    while (tokens.next(token)) {
        const float joint = read_number(token, file, line, "vw");
        if (!(joint >= 0 && joint <= 2147483520.0f)) {  // the largest float below 2^31
            fail_at(file, line, "vw: joint " + quote(token) + " out of range [0, 2147483647]");
        }
        if (tokens.next(token)) read_number(token, file, line, "vw");
    }
}

/// What the checking pass learns about an OBJ file on the way.
struct ObjScan {
    Counts counts;
    std::vector<uint32_t> face_sizes;           ///< corners of each `f`, in file order
    std::map<std::string, size_t> mtllib_line;  ///< MTL file name → first line naming it
    std::map<std::string, size_t> usemtl_line;  ///< material name → first line using it
};

/// The checking pass: every statement tinyobjloader reads is validated here first, so that its
/// silent fallbacks (0 for a malformed number, skipped faces) never happen.
ObjScan scan_obj(std::string_view text, const std::string& file) {
    ObjScan scan;
    Counts& c = scan.counts;
    Lines lines(text);
    std::string_view line;
    float numbers[8];
    while (lines.next(line)) {
        const size_t n = lines.number();
        if (n % 65536 == 0) check_cancel();
        Tokens tokens(line);
        std::string_view keyword;
        if (!tokens.next(keyword) || keyword[0] == '#') continue;
        if (keyword == "v") {
            // x y z, optionally w or an r g b colour
            read_numbers(tokens, numbers, 3, 7, file, n, "v");
            ++c.v;
        } else if (keyword == "vn") {
            read_numbers(tokens, numbers, 3, 3, file, n, "vn");
            ++c.vn;
        } else if (keyword == "vt") {
            read_numbers(tokens, numbers, 1, 3, file, n, "vt");
            ++c.vt;
        } else if (keyword == "f" || keyword == "l" || keyword == "p") {
            std::string_view token;
            size_t corners = 0;
            while (tokens.next(token)) {
                check_reference(token, c, file, n, keyword);
                ++corners;
            }
            const size_t needed = keyword == "f" ? 3 : (keyword == "l" ? 2 : 1);
            if (corners < needed) {
                fail_at(file, n,
                        std::string(keyword) + ": expected at least " + std::to_string(needed) +
                            " vertices, got " + std::to_string(corners));
            }
            if (keyword == "f") scan.face_sizes.push_back(static_cast<uint32_t>(corners));
        } else if (keyword == "vw") {
            check_skin_weights(tokens, file, n);
        } else if (keyword == "mtllib") {
            std::string_view name;
            while (tokens.next(name)) scan.mtllib_line.emplace(std::string(name), n);
        } else if (keyword == "usemtl") {
            std::string_view name;
            if (tokens.next(name)) scan.usemtl_line.emplace(std::string(name), n);
        }
        if (c.v > INT_MAX || c.vt > INT_MAX || c.vn > INT_MAX) {
            fail_at(file, n, "too many vertices for one file");
        }
    }
    return scan;
}

/// A read-only std::streambuf over a string, so tinyobjloader reads it without a copy; given a
/// MiB at a time, so that it ends early (the caller then checks) once the load is cancelled.
class ViewBuffer : public std::streambuf {
  public:
    explicit ViewBuffer(std::string_view s) : s_(s) {
        char* p = const_cast<char*>(s.data());
        setg(p, p, p);
    }

  protected:
    int_type underflow() override {
        const size_t at = static_cast<size_t>(egptr() - s_.data());
        if (at == s_.size() || cancel_requested(cancel_)) return traits_type::eof();
        char* p = const_cast<char*>(s_.data()) + at;
        setg(p, p, p + std::min(s_.size() - at, kWindow));
        return traits_type::to_int_type(*p);
    }

  private:
    static constexpr size_t kWindow = size_t{1} << 20;
    std::string_view s_;
    const std::atomic<bool>* cancel_ = cancel_flag();
};

/// Reads the MTL files an OBJ names (tinyobjloader calls it at each `mtllib`).
class MtlReader : public tinyobj::MaterialReader {
  public:
    MtlReader(const std::string& obj_file, const ObjScan& scan, const TextReader& read,
              std::vector<std::string>& warnings)
        : obj_file_(obj_file), scan_(scan), read_(read), warnings_(warnings) {}

    bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* names, std::string* warn,
                    std::string* err) override {
        const std::string path =
            (std::filesystem::path(obj_file_).parent_path() / name).lexically_normal().string();
        std::string reason;
        const std::optional<std::string> text = read_(path, reason);
        if (!text) {
            const auto it = scan_.mtllib_line.find(name);
            const size_t line = it != scan_.mtllib_line.end() ? it->second : 0;
            warnings_.push_back(at(obj_file_, line) + "cannot read MTL file " + printable(path) +
                                ": " + reason + "; using the default material");
            missing_ = true;
            return false;
        }
        const std::string_view mtl = without_bom(*text);
        const std::string prefix = std::filesystem::path(obj_file_).filename().string() + ":";
        std::vector<Material> mapped = scan_mtl(mtl, path, prefix, warnings_);
        const size_t before = materials->size();
        ViewBuffer buffer(mtl);
        std::istream in(&buffer);
        tinyobj::LoadMtl(names, materials, &in, warn, err);
        if (materials->size() - before != mapped.size()) {
            // a quirk of tinyobjloader's MTL syntax not mirrored in scan_mtl: bad input all the
            // same
            throw InputError(path + ": malformed MTL file: tinyobjloader reads " +
                             std::to_string(materials->size() - before) + " materials, not " +
                             std::to_string(mapped.size()));
        }
        materials_.insert(materials_.end(), mapped.begin(), mapped.end());
        return true;
    }

    /// Every material read so far, in tinyobjloader's material_id order.
    const std::vector<Material>& materials() const { return materials_; }
    bool missing() const { return missing_; }

  private:
    const std::string& obj_file_;
    const ObjScan& scan_;
    const TextReader& read_;
    std::vector<std::string>& warnings_;
    std::vector<Material> materials_;
    bool missing_ = false;
};

}  // namespace

MeshData parse_obj(std::string_view text, const std::string& file, bool with_materials,
                   const TextReader& read, std::vector<std::string>& warnings) {
    text = without_bom(text);
    const ObjScan scan = scan_obj(text, file);

    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> tiny_materials;
    std::string warn, err;
    MtlReader reader(file, scan, read, warnings);
    ViewBuffer buffer(text);
    std::istream in(&buffer);
    if (!tinyobj::LoadObj(&attrib, &shapes, &tiny_materials, &warn, &err, &in,
                          with_materials ? &reader : nullptr, /*triangulate=*/false,
                          /*default_vcols_fallback=*/false)) {
        throw InputError(file + ": " + (err.empty() ? "cannot parse" : err));
    }
    check_cancel();  // the buffer ended early
    if (attrib.vertices.size() != 3 * scan.counts.v ||
        attrib.normals.size() != 3 * scan.counts.vn) {
        throw std::logic_error(file + ": vertex counts differ from tinyobjloader's");
    }

    MeshData mesh;
    mesh.file = file;
    mesh.positions.resize(scan.counts.v);
    for (size_t i = 0; i < scan.counts.v; ++i) {
        mesh.positions[i] = {attrib.vertices[3 * i], attrib.vertices[3 * i + 1],
                             attrib.vertices[3 * i + 2]};
    }
    mesh.normals.resize(scan.counts.vn);
    for (size_t i = 0; i < scan.counts.vn; ++i) {
        mesh.normals[i] = {attrib.normals[3 * i], attrib.normals[3 * i + 1],
                           attrib.normals[3 * i + 2]};
    }

    // Triangles; materials renumbered to those the faces use, in order of first use. The faces
    // come in file order; their sizes are the scan's (tinyobjloader keeps them modulo 256).
    std::vector<int32_t> used(reader.materials().size(), -1);
    std::vector<Vec3> corners;
    std::vector<std::array<uint32_t, 3>> triangles;
    size_t face = 0;
    for (const tinyobj::shape_t& shape : shapes) {
        const tinyobj::mesh_t& m = shape.mesh;
        size_t offset = 0;
        for (size_t f = 0; f < m.num_face_vertices.size(); ++f, ++face) {
            if (f % 65536 == 0) check_cancel();
            const size_t size = face < scan.face_sizes.size() ? scan.face_sizes[face] : 0;
            if ((size & 0xFF) != m.num_face_vertices[f] || offset + size > m.indices.size()) {
                throw std::logic_error(file + ": faces differ from tinyobjloader's");
            }
            const tinyobj::index_t* idx = &m.indices[offset];
            offset += size;
            corners.resize(size);
            for (size_t k = 0; k < size; ++k) {
                corners[k] = mesh.positions[static_cast<size_t>(idx[k].vertex_index)];
            }
            triangles.clear();
            triangulate_polygon(corners, triangles);
            int32_t material = -1;
            const int id = f < m.material_ids.size() ? m.material_ids[f] : -1;
            if (id >= 0 && static_cast<size_t>(id) < used.size() && !triangles.empty()) {
                if (used[id] < 0) {
                    used[id] = static_cast<int32_t>(mesh.materials.size());
                    mesh.materials.push_back(reader.materials()[id]);
                }
                material = used[id];
            }
            for (const std::array<uint32_t, 3>& t : triangles) {
                for (const uint32_t k : t) {
                    mesh.position.push_back(static_cast<uint32_t>(idx[k].vertex_index));
                    mesh.normal.push_back(idx[k].normal_index >= 0 ? idx[k].normal_index : -1);
                }
                mesh.material.push_back(material);
            }
        }
        if (offset != m.indices.size()) {
            throw std::logic_error(file + ": faces differ from tinyobjloader's");
        }
    }
    if (face != scan.face_sizes.size()) {
        throw std::logic_error(file + ": faces differ from tinyobjloader's");
    }

    // Warnings: `usemtl` names no MTL file defines (unless an MTL file was missing, which was
    // said already), and a file without faces.
    if (with_materials && !reader.missing()) {
        std::unordered_set<std::string_view> defined;
        for (const tinyobj::material_t& t : tiny_materials) defined.insert(t.name);
        for (const auto& [name, line] : scan.usemtl_line) {
            if (!defined.count(name)) {
                warnings.push_back(at(file, line) + "usemtl " + printable(name, kMaxQuotedChars) +
                                   ": no such material in the MTL files; its faces use the "
                                   "default material");
            }
        }
    }
    if (mesh.triangle_count() == 0) warnings.push_back(file + ": no faces; the mesh is empty");
    return mesh;
}

MeshData load_obj(const std::string& path, bool with_materials,
                  std::vector<std::string>& warnings) {
    std::string reason;
    const std::optional<std::string> text = read_text_file(path, reason);
    if (!text) throw InputError(path + ": cannot read: " + reason);
    return parse_obj(*text, path, with_materials, read_text_file, warnings);
}

}  // namespace luz
