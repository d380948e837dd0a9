// Typed readers of scene JSON values and Section (see json_readers.h).
#include "scene/json_readers.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "scene/number_text.h"

namespace luz::loader {

void fail(std::string path, std::string what, std::string scope) {
    throw KeyError{std::move(path), std::move(what), std::move(scope)};
}

std::string join(const std::string& path, std::string_view key) {
    if (path.empty()) return std::string(key);
    std::string s;  // one allocation at most
    s.reserve(path.size() + 1 + key.size());
    s += path;
    s += '.';
    s += key;
    return s;
}
std::string join(const std::string& path, std::size_t index) {
    char digits[24];
    const auto end = std::to_chars(digits, digits + sizeof digits, index).ptr;
    return join(path, std::string_view(digits, static_cast<std::size_t>(end - digits)));
}

bool is_under(std::string_view path, std::string_view root) {
    if (root.empty() || path.size() < root.size() || path.substr(0, root.size()) != root) {
        return false;
    }
    return path.size() == root.size() || path[root.size()] == '.';
}

std::string describe(const Json& j) {
    if (j.is_object()) return "an object";
    if (j.is_string()) return "string " + quote(j.get_ref<const std::string&>());
    if (j.is_array() && j.size() > 16) return "an array of " + std::to_string(j.size()) + " values";
    return printable(j.dump(-1, ' ', false, Json::error_handler_t::replace), 57);
}

std::string comma_list(const std::vector<std::string_view>& names) {
    std::string s;
    for (std::string_view n : names) s += (s.empty() ? "" : ", ") + std::string(n);
    return s;
}

double read_number(const Json& j, const KeyPath& path, const Limit& limit) {
    if (!j.is_number()) fail(path.str(), "expected a number, got " + describe(j));
    const double d = j.get<double>();
    if (!std::isfinite(d)) fail(path.str(), "must be a finite number, got " + format_number(d));
    if (!std::isfinite(static_cast<float>(d))) {
        fail(path.str(), "must be a finite number (a float: |x| < 3.4e38), got " + j.dump());
    }
    // The float must be in range too: 1e-50 is > 0 but becomes 0 as a float.
    if (!limit.contains(d) || !limit.contains(static_cast<float>(d))) {
        fail(path.str(), limit.text() + ", got " + format_number(d));  // 0.2 read as a float: 0.2
    }
    return d;
}

float read_float(const Json& j, const KeyPath& path, const Limit& limit) {
    return static_cast<float>(read_number(j, path, limit));
}

int read_int(const Json& j, const KeyPath& path, long long lo, long long hi) {
    if (!j.is_number()) fail(path.str(), "expected an integer, got " + describe(j));
    const double d = j.get<double>();
    if (!std::isfinite(d)) fail(path.str(), "must be a finite number, got " + format_number(d));
    if (!j.is_number_integer() && std::floor(d) != d) {
        fail(path.str(), "expected an integer, got " + j.dump());
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
        fail(path.str(), "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                             "], got " + j.dump());
    }
    return static_cast<int>(d);
}

bool read_bool(const Json& j, const KeyPath& path) {
    if (!j.is_boolean()) fail(path.str(), "expected true or false, got " + describe(j));
    return j.get<bool>();
}

std::string read_string(const Json& j, const KeyPath& path) {
    if (!j.is_string()) fail(path.str(), "expected a string, got " + describe(j));
    return j.get<std::string>();
}

Vec3 read_vec3(const Json& j, const KeyPath& path) {
    if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() ||
        !j[2].is_number()) {
        fail(path.str(), "expected an array of 3 numbers, got " + describe(j));
    }
    return {read_float(j[0], path), read_float(j[1], path), read_float(j[2], path)};
}

Rgb read_rgb(const Json& j, const KeyPath& path, const Limit& limit) {
    if (j.is_number()) return Rgb(read_float(j, path, limit));
    if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() ||
        !j[2].is_number()) {
        fail(path.str(), "expected a number or an array of 3 numbers, got " + describe(j));
    }
    return {read_float(j[0], path, limit), read_float(j[1], path, limit),
            read_float(j[2], path, limit)};
}

Vec3 read_direction(const Json& j, const KeyPath& path) {
    const Vec3 v = read_vec3(j, path);
    const float len = length(v);
    if (v == Vec3(0.0f)) fail(path.str(), "must not be zero-length, got " + format_vec(v));
    if (!(len > 0) || !std::isfinite(len) || !is_finite(v / len)) {
        fail(path.str(), "cannot be normalised (length out of float range), got " + format_vec(v));
    }
    return v;
}

Section::Section(const Json& j, std::string path, const std::vector<std::string_view>& known,
                 std::string_view pattern, const KeyPath& unknown_scope)
    : j_(j), path_(std::move(path)), pattern_(pattern) {
    if (!j.is_object()) {
        fail(path_, path_.empty() ? "expected a JSON object at the top level, got " + describe(j)
                                  : "expected an object, got " + describe(j));
    }
    // Keys mostly come in the order of `known`: each search starts after the last key found.
    std::size_t next = 0;
    for (const auto& member : j.get_ref<const Json::object_t&>()) {
        const std::string& name = member.first;
        bool found = false;
        for (std::size_t i = 0; i < known.size() && !found; ++i) {
            const std::size_t k = next + i < known.size() ? next + i : next + i - known.size();
            if (known[k] == name) {
                found = true;
                next = k + 1;
            }
        }
        if (!found) {
            fail(key(name), "unknown key (known: " + comma_list(known) + ")", unknown_scope.str());
        }
    }
}

const Limit& Section::limit(std::string_view name, NumberKind kind) const {
    const KeyLimit& row = key_limit(join(std::string(pattern_), name));
    if (row.kind != kind) {
        throw std::logic_error("scene key \"" + row.key + "\" read as another kind of number");
    }
    return row.limit;
}

void Section::number(std::string_view name, float& out) const {
    if (const Json* v = get(name)) out = read_float(*v, at(name), limit(name, NumberKind::real));
}

void Section::integer(std::string_view name, int& out) const {
    if (const Json* v = get(name)) {
        const Limit& l = limit(name, NumberKind::integer);
        out = read_int(*v, at(name), static_cast<long long>(l.lo), static_cast<long long>(l.hi));
    }
}

void Section::rgb(std::string_view name, Rgb& out) const {
    if (const Json* v = get(name)) out = read_rgb(*v, at(name), limit(name, NumberKind::rgb));
}

}  // namespace luz::loader
