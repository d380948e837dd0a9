// Typed readers of a scene document's values: numbers (ranges from scene/limits.h), colours,
// vectors, enums, booleans; errors name the key path; Section checks an object's keys.
#pragma once

#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "math/vec3.h"
#include "scene/json_text.h"
#include "scene/limits.h"
#include "scene/message_text.h"

namespace luz::loader {

/// An error found while reading the document: a key path and what is wrong. parse_scene turns
/// it into an InputError naming the file, or the override that put the bad value there.
struct KeyError {
    std::string path;   ///< e.g. "objects.2.radius"; empty for the document itself
    std::string what;   ///< e.g. "must be > 0, got -1"
    std::string scope;  ///< for checks across keys (box min/max…): the object they belong to
};

/// Throws KeyError{path, what, scope}.
[[noreturn]] void fail(std::string path, std::string what, std::string scope = {});

/// "path.key" (just "key" at the top level).
std::string join(const std::string& path, std::string_view key);
/// "path.index".
std::string join(const std::string& path, std::size_t index);

/// A key path for messages, made into a string only when one is needed: `parent`, or
/// join(parent, key). It refers to the strings it was made from: pass it down, do not keep it.
class KeyPath {
  public:
    KeyPath() = default;                                  ///< the document itself ("")
    KeyPath(const std::string& path) : parent_(&path) {}  // NOLINT: any path string converts
    KeyPath(const std::string& parent, std::string_view key)
        : parent_(&parent), key_(key), joined_(true) {}

    std::string str() const {
        if (!parent_) return {};
        return joined_ ? join(*parent_, key_) : *parent_;
    }

  private:
    const std::string* parent_ = nullptr;
    std::string_view key_;
    bool joined_ = false;
};

/// True when key path `path` is `root` or lies inside it ("a.b.c" is under "a.b", not "a.bc").
bool is_under(std::string_view path, std::string_view root);

/// A short description of a JSON value for "got …" in messages.
std::string describe(const Json& j);

/// "a, b, c".
std::string comma_list(const std::vector<std::string_view>& names);

/// A finite number (finite also once converted to float) within `limit`.
double read_number(const Json& j, const KeyPath& path, const Limit& limit = kAnyNumber);
/// read_number as a float.
float read_float(const Json& j, const KeyPath& path, const Limit& limit = kAnyNumber);
/// An integer in [lo, hi] (a float with an integral value, like 800.0, is accepted).
int read_int(const Json& j, const KeyPath& path, long long lo, long long hi);
/// true or false.
bool read_bool(const Json& j, const KeyPath& path);
/// A string.
std::string read_string(const Json& j, const KeyPath& path);
/// A point or direction: an array of 3 finite numbers.
Vec3 read_vec3(const Json& j, const KeyPath& path);
/// A colour constant: a scalar (all channels) or an array of 3 numbers, each within `limit`.
Rgb read_rgb(const Json& j, const KeyPath& path, const Limit& limit);
/// A direction that can be normalised (not zero-length, length within float range).
Vec3 read_direction(const Json& j, const KeyPath& path);

/// One of the strings of `table` (name → value).
template <typename E>
E read_enum(const Json& j, const KeyPath& path,
            std::initializer_list<std::pair<std::string_view, E>> table) {
    std::string allowed;
    for (const auto& [name, value] : table) {
        allowed += (allowed.empty() ? "" : ", ") + std::string(name);
    }
    if (!j.is_string()) fail(path.str(), "expected one of " + allowed + ", got " + describe(j));
    const std::string s = j.get<std::string>();
    for (const auto& [name, value] : table) {
        if (name == s) return value;
    }
    fail(path.str(), "unknown value " + quote(s) + " (allowed: " + allowed + ")");
}

/// An object whose keys must all be among `known`; gives access to the present ones. Its
/// numbers are checked against the limits table (scene/limits.h) under `pattern`: the key path
/// with "*" for array indices and material names ("lights.*", "materials.*.checker").
class Section {
  public:
    /// `unknown_scope`: the key that decides which keys are known, when there is one (an
    /// object's `type`), so that an override changing it is blamed for unknown keys.
    /// `pattern` must outlive the section (a string literal or a static string).
    Section(const Json& j, std::string path, const std::vector<std::string_view>& known,
            std::string_view pattern, const KeyPath& unknown_scope = {});

    /// The value of `name`, or nullptr when absent (the first such key, as Json::find()).
    const Json* get(std::string_view name) const {
        for (const auto& [k, v] : j_.get_ref<const Json::object_t&>()) {
            if (k == name) return &v;
        }
        return nullptr;
    }
    std::string key(std::string_view name) const { return join(path_, name); }
    /// key(name) as a KeyPath: a string only if a message needs it.
    KeyPath at(std::string_view name) const { return {path_, name}; }
    const std::string& path() const { return path_; }

    // Readers that leave `out` at its default when the key is absent. Numbers, integers and
    // colours within the key's row of the limits table.
    void number(std::string_view name, float& out) const;
    void integer(std::string_view name, int& out) const;
    void rgb(std::string_view name, Rgb& out) const;
    void boolean(std::string_view name, bool& out) const {
        if (const Json* v = get(name)) out = read_bool(*v, at(name));
    }
    void vec3(std::string_view name, Vec3& out) const {
        if (const Json* v = get(name)) out = read_vec3(*v, at(name));
    }
    void direction(std::string_view name, Vec3& out) const {
        if (const Json* v = get(name)) out = read_direction(*v, at(name));
    }
    template <typename E>
    void enumeration(std::string_view name, E& out,
                     std::initializer_list<std::pair<std::string_view, E>> table) const {
        if (const Json* v = get(name)) out = read_enum(*v, at(name), table);
    }

    /// The limits table's row for key `name` of this section; its kind must be `kind`.
    const Limit& limit(std::string_view name, NumberKind kind) const;

  private:
    const Json& j_;
    std::string path_;
    std::string_view pattern_;
};

}  // namespace luz::loader
