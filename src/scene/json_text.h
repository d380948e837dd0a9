// JSON text → document, with errors at FILE:LINE:COLUMN (the scene loader's first step).
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "luz/json.h"

namespace luz::loader {

// ordered_json keeps the file's key order: materials keep their order and the first unknown
// key reported is the first one in the file.
using Json = nlohmann::ordered_json;

// kMaxJsonNesting (luz/json.h): deeper text is refused before parsing, as nlohmann's dump()
// recurses and "got …" messages dump values.

/// Byte offset of the first '[' or '{' nested deeper than kMaxJsonNesting outside strings, or
/// npos.
std::size_t too_deep_at(std::string_view text);

/// nlohmann's message without its "[json.exception…] parse error at line…:" prefix.
std::string strip_exception_prefix(std::string s);

/// Parses JSON text; on failure throws InputError "FILE:LINE:COL: …": a syntax error, a number
/// out of range, a key twice in one object (naming both places), a NUL character in a key or
/// string, or a document that would take more than memory_limit() (scene/text_files.h) with the
/// text.
Json parse_text(std::string_view text, const std::string& file);

}  // namespace luz::loader
