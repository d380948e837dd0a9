// NFF's statements as text (docs/SCENES.md#nff): their keywords, the lines that hold one, and a
// count of the lines that may start a shape (the NFF reader's estimate of its objects). Used by
// nff_reader.cpp alone.
#pragma once

#include <cstddef>
#include <string_view>

#include "scene/obj_text.h"

namespace luz::loader::nff_text {

/// NFF's statements, by keyword.
enum class Keyword { v, b, l, f, s, c, p, pp, unknown };

inline Keyword keyword_of(std::string_view k) {
    constexpr std::string_view kOneLetter = "vblfscp";  // in the order of Keyword
    if (k == "pp") return Keyword::pp;
    const std::size_t i = k.size() == 1 ? kOneLetter.find(k[0]) : std::string_view::npos;
    return i == std::string_view::npos ? Keyword::unknown : static_cast<Keyword>(i);
}

/// How many lines start with `s` or `c` (spheres, cylinders, cones; a few other lines may
/// too): an estimate of the objects to come.
inline std::size_t shape_lines(std::string_view text) {
    std::size_t n = 0;
    for (std::size_t at = 0; at < text.size();) {
        n += text[at] == 's' || text[at] == 'c';
        const std::size_t end = text.find('\n', at);
        if (end == std::string_view::npos) break;
        at = end + 1;
    }
    return n;
}

/// The lines that hold a statement: text from `#` on and blank lines are skipped.
class Statements {
  public:
    explicit Statements(std::string_view text) : lines_(obj_text::without_bom(text)) {}

    bool next(std::string_view& line) {
        while (lines_.next(line)) {
            if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) {
                line = line.substr(0, hash);
            }
            if (!obj_text::Tokens(line).rest().empty()) return true;
        }
        return false;
    }
    std::size_t line() const { return lines_.number(); }

  private:
    obj_text::Lines lines_;
};

}  // namespace luz::loader::nff_text
