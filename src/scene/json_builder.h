// JSON text → document through nlohmann's SAX parser, refusing what a scene must not hold and
// the DOM parser accepts: a key twice in one object, a NUL character, a document larger than
// the memory allows. Keys are appended without ordered_map's linear search for duplicates.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "scene/json_text.h"

namespace luz::loader {

/// What stopped a parse: where (a byte offset in the text) and why.
struct JsonProblem {
    enum class Kind {
        syntax,     ///< not JSON: `what` is nlohmann's message without its prefix
        range,      ///< a number out of range: `token` is the number as written
        duplicate,  ///< a key twice in one object: `first` is the first one's offset
        nul,        ///< a NUL character in a key or string
        memory,     ///< the document would need more than the budget
    };
    Kind kind = Kind::syntax;
    std::size_t offset = 0;
    std::size_t first = 0;
    std::string what;   ///< the problem, without the place
    std::string token;  ///< range: the number's text
};

/// Parses `text` (one JSON value, nothing after it) into `out`. Returns the problem that
/// stopped it, or nullopt. `memory_budget`: the bytes the document may take (an estimate kept
/// as it grows: the parse stops as soon as it is passed).
std::optional<JsonProblem> build_json(std::string_view text, Json& out,
                                      uint64_t memory_budget = UINT64_MAX);

}  // namespace luz::loader
