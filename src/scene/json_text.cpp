// JSON text parsing for the scene loader: nesting limit, syntax errors with line:column.
#include "scene/json_text.h"

#include <algorithm>
#include <utility>

#include "scene/input_error.h"

namespace luz::loader {
namespace {

/// A SAX pass that only records where and why parsing failed (the DOM parser's exceptions do
/// not all carry the position, e.g. number overflow).
struct ErrorLocator : nlohmann::json_sax<Json> {
    std::size_t position = 0;
    std::string token, message;
    int id = 0;
    bool null() override { return true; }
    bool boolean(bool) override { return true; }
    bool number_integer(number_integer_t) override { return true; }
    bool number_unsigned(number_unsigned_t) override { return true; }
    bool number_float(number_float_t, const string_t&) override { return true; }
    bool string(string_t&) override { return true; }
    bool binary(binary_t&) override { return true; }
    bool start_object(std::size_t) override { return true; }
    bool key(string_t&) override { return true; }
    bool end_object() override { return true; }
    bool start_array(std::size_t) override { return true; }
    bool end_array() override { return true; }
    bool parse_error(std::size_t pos, const std::string& last_token,
                     const nlohmann::detail::exception& ex) override {
        position = pos;
        token = last_token;
        message = ex.what();
        id = ex.id;
        return false;
    }
};

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

Json parse_text(std::string_view text, const std::string& file) {
    if (const std::size_t at = too_deep_at(text); at != std::string_view::npos) {
        const auto [line, column] = line_column(text, at);
        throw InputError(file + ":" + std::to_string(line) + ":" + std::to_string(column) +
                         ": JSON nested deeper than " + std::to_string(kMaxJsonNesting) +
                         " levels");
    }
    try {
        return Json::parse(text);
    } catch (const Json::exception&) {
        ErrorLocator locator;
        Json::sax_parse(text, &locator);
        // The position counts the characters read: the offending one is at position − 1. For a
        // number overflow the position is just past the number: point at its start instead.
        std::size_t offset = locator.position > 0 ? locator.position - 1 : 0;
        std::string what = "JSON syntax error: " + strip_exception_prefix(locator.message);
        if (locator.id == 406) {
            offset = locator.position >= locator.token.size()
                         ? locator.position - locator.token.size()
                         : 0;
            what = "number out of range: " + locator.token + " is not a finite number";
        }
        const auto [line, column] = line_column(text, offset);
        throw InputError(file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " +
                         what);
    }
}

}  // namespace luz::loader
