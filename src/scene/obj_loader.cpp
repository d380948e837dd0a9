// OBJ/MTL loading: a checking pass over the text (numbers, indices, face sizes → FILE:LINE
// errors), then tinyobjloader parses and triangulates; MTL constants are mapped per SPEC §2.
#include "scene/obj_loader.h"

#include <tiny_obj_loader.h>

#include <algorithm>
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

#include "scene/cancel.h"
#include "scene/message_text.h"

namespace luz {
namespace {

std::string at(const std::string& file, size_t line) {
    return file + ":" + std::to_string(line) + ": ";
}

[[noreturn]] void fail_at(const std::string& file, size_t line, const std::string& what) {
    throw InputError(at(file, line) + what);
}

/// Text without a leading UTF-8 byte order mark.
std::string_view without_bom(std::string_view text) {
    if (text.size() >= 3 && text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
    return text;
}

/// The lines of a text, numbered from 1; "\n", "\r\n" and a lone "\r" end a line (as
/// tinyobjloader counts them).
class Lines {
  public:
    explicit Lines(std::string_view text) : text_(text) {}

    bool next(std::string_view& line) {
        if (pos_ >= text_.size()) return false;
        size_t end = text_.find_first_of("\r\n", pos_);
        if (end == std::string_view::npos) end = text_.size();
        line = text_.substr(pos_, end - pos_);
        pos_ = end;
        if (end < text_.size()) {
            pos_ = end + 1;
            if (text_[end] == '\r' && pos_ < text_.size() && text_[pos_] == '\n') ++pos_;
        }
        ++number_;
        return true;
    }
    size_t number() const { return number_; }

  private:
    std::string_view text_;
    size_t pos_ = 0;
    size_t number_ = 0;
};

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

/// The whitespace-separated tokens of a line.
class Tokens {
  public:
    explicit Tokens(std::string_view line) : rest_(line) {}
    bool next(std::string_view& token) {
        size_t i = 0;
        while (i < rest_.size() && is_blank(rest_[i])) ++i;
        size_t j = i;
        while (j < rest_.size() && !is_blank(rest_[j])) ++j;
        token = rest_.substr(i, j - i);
        rest_.remove_prefix(j);
        return !token.empty();
    }
    /// What is left after the tokens read so far, without leading blanks.
    std::string_view rest() const {
        size_t i = 0;
        while (i < rest_.size() && is_blank(rest_[i])) ++i;
        return rest_.substr(i);
    }

  private:
    std::string_view rest_;
};

/// A number token as a float: the whole token must be a number, finite, in float range.
float read_number(std::string_view token, const std::string& file, size_t line,
                  std::string_view statement) {
    std::string_view t = token;
    if (!t.empty() && t[0] == '+') t.remove_prefix(1);
    double d = 0;
    const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), d);
    if (ec == std::errc() && ptr == t.data() + t.size() && !t.empty() && t[0] != '+' &&
        std::fabs(d) <= std::numeric_limits<float>::max()) {
        return static_cast<float>(d);  // the usual case, without building any message
    }
    const std::string where = std::string(statement) + ": ";
    if (t.empty() || t[0] == '+' || ptr != t.data() + t.size() ||
        (ec != std::errc() && ec != std::errc::result_out_of_range)) {
        fail_at(file, line, where + "malformed number " + quote(token));
    }
    if (ec == std::errc::result_out_of_range) {
        // from_chars leaves d alone: strtod tells overflow (±HUGE_VAL) from underflow (≈ 0)
        d = std::strtod(std::string(t).c_str(), nullptr);
        if (std::isinf(d)) fail_at(file, line, where + "number out of range " + quote(token));
    }
    if (!std::isfinite(d)) fail_at(file, line, where + "not a finite number " + quote(token));
    if (!(std::fabs(d) <= std::numeric_limits<float>::max())) {
        fail_at(file, line, where + "number out of float range " + quote(token));
    }
    return static_cast<float>(d);
}

/// Reads the numbers of a statement (at least `min_count`, at most `max_count`).
int read_numbers(Tokens& tokens, float* out, int min_count, int max_count, const std::string& file,
                 size_t line, std::string_view statement) {
    int n = 0;
    std::string_view token;
    while (tokens.next(token)) {
        if (n == max_count) {
            fail_at(file, line,
                    std::string(statement) + ": expected at most " + std::to_string(max_count) +
                        " numbers, got more (" + quote(token) + ")");
        }
        out[n++] = read_number(token, file, line, statement);
    }
    if (n < min_count) {
        fail_at(file, line,
                std::string(statement) + ": expected " +
                    (min_count == max_count ? "" : "at least ") + std::to_string(min_count) +
                    " number" + (min_count == 1 ? "" : "s") + ", got " + std::to_string(n));
    }
    return n;
}

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

/// What the checking pass learns about an OBJ file on the way.
struct ObjScan {
    Counts counts;
    size_t faces = 0;
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
            if (keyword == "f") ++scan.faces;
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

// ---- MTL ------------------------------------------------------------------------------------

/// Clamps a constant to [0, 1] (SPEC §2), with a warning when it had to.
float unit(float x, const char* key, const std::string& file, size_t line,
           std::vector<std::string>& warnings) {
    if (x >= 0 && x <= 1) return x;
    const float c = x < 0 ? 0.0f : 1.0f;
    char buf[96];
    std::snprintf(buf, sizeof buf, "%s %g is outside [0, 1]; %g is used", key, double(x),
                  double(c));
    warnings.push_back(at(file, line) + buf);
    return c;
}

/// The MTL materials of `text` in the order tinyobjloader's LoadMtl lists them (a material is
/// listed at the next `newmtl` if it has a name, and the last one always), mapped per SPEC §2;
/// names get `prefix`. Values are read here, strictly, rather than from tinyobjloader, whose
/// number parser falls back to 0 silently and reads "Kd 0.5" as (0.5, 0, 0).
std::vector<Material> scan_mtl(std::string_view text, const std::string& file,
                               const std::string& prefix, std::vector<std::string>& warnings) {
    std::vector<Material> out;
    Material m;
    std::string name;
    int illum = -1;
    bool has_d = false;
    const auto flush = [&] {
        // illum 3–7: ray-traced reflection, weighted by Ks in the MTL model
        m.reflection = (illum >= 3 && illum <= 7) ? (m.ks.x + m.ks.y + m.ks.z) / 3.0f : 0.0f;
        m.name = prefix + name;
        out.push_back(m);
    };
    Lines lines(text);
    std::string_view line;
    float v[3];
    while (lines.next(line)) {
        const size_t n = lines.number();
        Tokens tokens(line);
        std::string_view key;
        if (!tokens.next(key) || key[0] == '#') continue;
        if (key == "newmtl") {
            if (!name.empty()) flush();
            m = Material{};
            illum = -1;
            has_d = false;
            // as LoadMtl: the rest of the line, trailing blanks removed
            std::string_view rest = tokens.rest();
            while (!rest.empty() && is_blank(rest.back())) rest.remove_suffix(1);
            // tinyobjloader skips an unnamed `newmtl` and cuts a name at a NUL: refuse both,
            // so that both readers list the same materials (found by fuzzing)
            if (rest.empty()) fail_at(file, n, "newmtl: expected a material name");
            for (const char c : rest) {
                if (static_cast<unsigned char>(c) < 0x20 && c != '\t') {
                    fail_at(file, n, "newmtl: control character in the material name");
                }
            }
            name = std::string(rest);
        } else if (key == "Ka" || key == "Kd" || key == "Ks") {
            const std::string k(key);
            // "Kd r g b", or "Kd r" meaning r r r
            const int count = read_numbers(tokens, v, 1, 3, file, n, k);
            if (count == 2) fail_at(file, n, k + ": expected 1 or 3 numbers, got 2");
            if (count == 1) v[1] = v[2] = v[0];
            Rgb& target = key == "Ka" ? m.ka : (key == "Kd" ? m.kd : m.ks);
            target = Rgb{unit(v[0], k.c_str(), file, n, warnings),
                         unit(v[1], k.c_str(), file, n, warnings),
                         unit(v[2], k.c_str(), file, n, warnings)};
        } else if (key == "Ns") {
            read_numbers(tokens, v, 1, 1, file, n, "Ns");
            m.n = v[0] > 0 ? v[0] : 1.0f;  // SPEC: n > 0
        } else if (key == "Ni") {
            read_numbers(tokens, v, 1, 1, file, n, "Ni");
            m.ior = v[0] >= 1 ? v[0] : 1.0f;  // SPEC: ior ≥ 1
        } else if (key == "d") {
            std::string_view first = tokens.rest();
            if (first.substr(0, 5) == "-halo") {
                std::string_view skip;
                tokens.next(skip);
            }
            read_numbers(tokens, v, 1, 1, file, n, "d");
            m.transparency = 1.0f - unit(v[0], "d", file, n, warnings);
            has_d = true;
        } else if (key == "Tr") {
            read_numbers(tokens, v, 1, 1, file, n, "Tr");
            if (!has_d) m.transparency = unit(v[0], "Tr", file, n, warnings);  // d wins
        } else if (key == "illum") {
            std::string_view token;
            tokens.next(token);
            const auto [ptr, ec] =
                std::from_chars(token.data(), token.data() + token.size(), illum);
            std::string_view extra;
            if (token.empty() || ec != std::errc() || ptr != token.data() + token.size() ||
                tokens.next(extra)) {
                fail_at(file, n, "illum: expected an integer, got " + quote(line));
            }
        }
    }
    flush();
    return out;
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
            warnings_.push_back(at(obj_file_, line) + "cannot read MTL file " + path + ": " +
                                reason + "; using the default material");
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
                          with_materials ? &reader : nullptr, /*triangulate=*/true,
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

    // Triangles; materials renumbered to those the faces use, in order of first use.
    std::vector<int32_t> used(reader.materials().size(), -1);
    for (const tinyobj::shape_t& shape : shapes) {
        const tinyobj::mesh_t& m = shape.mesh;
        size_t offset = 0;
        for (size_t f = 0; f < m.num_face_vertices.size(); ++f) {
            if (f % 65536 == 0) check_cancel();
            const size_t corners = m.num_face_vertices[f];
            if (corners == 3) {
                for (size_t k = 0; k < 3; ++k) {
                    const tinyobj::index_t& idx = m.indices[offset + k];
                    mesh.position.push_back(static_cast<uint32_t>(idx.vertex_index));
                    mesh.normal.push_back(idx.normal_index >= 0 ? idx.normal_index : -1);
                }
                int32_t material = -1;
                const int id = f < m.material_ids.size() ? m.material_ids[f] : -1;
                if (id >= 0 && static_cast<size_t>(id) < used.size()) {
                    if (used[id] < 0) {
                        used[id] = static_cast<int32_t>(mesh.materials.size());
                        mesh.materials.push_back(reader.materials()[id]);
                    }
                    material = used[id];
                }
                mesh.material.push_back(material);
            }
            offset += corners;
        }
    }

    // Warnings: `usemtl` names no MTL file defines (unless an MTL file was missing, which was
    // said already), and a file without faces.
    if (with_materials && !reader.missing()) {
        for (const auto& [name, line] : scan.usemtl_line) {
            bool found = false;
            for (const tinyobj::material_t& t : tiny_materials) found = found || t.name == name;
            if (!found) {
                warnings.push_back(at(file, line) + "usemtl " + name +
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
