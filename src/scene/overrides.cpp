// `--set` overrides: PATH=JSON parsing (parse_set) and application to the scene document.
#include "scene/overrides.h"

#include <cctype>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "scene/json_builder.h"
#include "scene/json_readers.h"
#include "scene/message_text.h"

namespace luz {
namespace loader {
namespace {

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

bool is_index(std::string_view s) {
    if (s.empty() || s.size() > 9) return false;
    for (char c : s) {
        if (c < '0' || c > '9') return false;
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
    Json value;
    const std::optional<JsonProblem> p = build_json(o.json, value);
    if (!p) return value;
    switch (p->kind) {
        case JsonProblem::Kind::syntax:
            if (is_bare_word(o.json)) return Json(o.json);
            throw InputError(override_label(o) +
                             ": JSON syntax error: " + printable(strip_exception_prefix(p->what)));
        case JsonProblem::Kind::range:
            throw InputError(override_label(o) + ": number out of range: " +
                             printable(p->token, kMaxQuotedChars) + " is not a finite number");
        default:
            throw InputError(override_label(o) + ": " + p->what);
    }
}

/// The override's key path split at the dots; throws InputError on an empty path or segment.
std::vector<std::string> split_path(const Override& o) {
    std::vector<std::string> segments;
    if (o.path.empty()) throw InputError(override_label(o) + ": empty key path");
    std::size_t start = 0;
    while (true) {
        const std::size_t dot = o.path.find('.', start);
        segments.push_back(o.path.substr(start, dot - start));
        if (segments.back().empty()) {
            throw InputError(override_label(o) + ": empty segment in key path " + quote(o.path));
        }
        if (segments.back().find('\0') != std::string::npos) {
            throw InputError(override_label(o) + ": a NUL character (\\u0000) in key path " +
                             quote(o.path));
        }
        if (dot == std::string::npos) break;
        start = dot + 1;
    }
    return segments;
}

}  // namespace

std::string override_label(const Override& o) {
    if (o.origin == "--set") return "--set " + printable(o.path) + "=" + printable(o.json);
    return o.origin + " " + printable(o.json);
}

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
                                 " is an array: " + quote(seg) + " is not an index");
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
                             describe(*node) + ", not an object or array: cannot set " +
                             quote(seg) + " in it");
        }
        at = here;
    }
    *node = std::move(value);
    return root.empty() ? o.path : root;
}

}  // namespace loader

Override parse_set(const std::string& arg) {
    const std::size_t eq = arg.find('=');
    if (eq == std::string::npos) {
        throw InputError("--set " + arg + ": expected PATH=JSON, e.g. objects.0.radius=2");
    }
    Override o{arg.substr(0, eq), arg.substr(eq + 1), "--set"};
    loader::split_path(o);      // an empty path or segment
    loader::override_value(o);  // a value that is neither JSON nor a bare word
    return o;
}

}  // namespace luz
