// JSON text parsing for the scene loader: nesting limit, then the document built by
// json_builder.h; every problem named at FILE:LINE:COLUMN.
#include "scene/json_text.h"

#include <algorithm>
#include <utility>

#include "scene/input_error.h"
#include "scene/json_builder.h"
#include "scene/message_text.h"
#include "scene/text_files.h"

namespace luz::loader {
namespace {

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

}  // namespace

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

namespace {

/// "FILE:LINE:COLUMN" of byte `offset`.
std::string at(const std::string& file, std::string_view text, std::size_t offset) {
    const auto [line, column] = line_column(text, offset);
    return printable(file) + ":" + std::to_string(line) + ":" + std::to_string(column);
}

/// nlohmann's syntax error message, its quoted token shortened.
std::string syntax_message(const std::string& nlohmann_message) {
    std::string what = strip_exception_prefix(nlohmann_message);
    // "…; last read: 'TOKEN'": the token may be a whole unterminated string
    const std::string marker = "; last read: '";
    const std::size_t from = what.find(marker);
    if (from != std::string::npos && what.size() > from + marker.size() && what.back() == '\'') {
        const std::size_t token_at = from + marker.size();
        const std::string_view token =
            std::string_view(what).substr(token_at, what.size() - 1 - token_at);
        what = what.substr(0, token_at) + printable(token, kMaxQuotedChars) + "'";
    }
    return what;
}

/// The one-line message for `p`.
std::string problem_message(const JsonProblem& p, const std::string& file, std::string_view text) {
    using Kind = JsonProblem::Kind;
    switch (p.kind) {
        case Kind::syntax:
            return at(file, text, p.offset) + ": JSON syntax error: " + syntax_message(p.what);
        case Kind::range:
            return at(file, text, p.offset) +
                   ": number out of range: " + printable(p.token, kMaxQuotedChars) +
                   " is not a finite number";
        case Kind::duplicate: {
            const auto [line, column] = line_column(text, p.first);
            return at(file, text, p.offset) + ": " + p.what + " (first at " + std::to_string(line) +
                   ":" + std::to_string(column) + "): a key may appear once in an object";
        }
        case Kind::nul:
            return at(file, text, p.offset) + ": " + p.what;
        case Kind::memory:
            return at(file, text, p.offset) + ": the scene needs more memory than the " +
                   bytes_text(memory_limit()) + " limit (--max-memory to change it): its " +
                   bytes_text(text.size()) + " of JSON take more than that once parsed and read";
    }
    return at(file, text, p.offset) + ": cannot parse";
}

}  // namespace

Json parse_text(std::string_view text, const std::string& file) {
    if (const std::size_t at_byte = too_deep_at(text); at_byte != std::string_view::npos) {
        throw InputError(at(file, text, at_byte) + ": JSON nested deeper than " +
                         std::to_string(kMaxJsonNesting) + " levels");
    }
    // The document may take two thirds of what the memory limit leaves besides the text: the
    // scene's description is made while it is held (an object's takes about half its JSON's).
    const uint64_t limit = memory_limit();
    const uint64_t budget = limit > text.size() ? (limit - text.size()) / 3 * 2 : 0;
    Json doc;
    if (const std::optional<JsonProblem> p = build_json(text, doc, budget)) {
        throw InputError(problem_message(*p, file, text));
    }
    return doc;
}

}  // namespace luz::loader
