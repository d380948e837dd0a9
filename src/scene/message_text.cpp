// Quoting input text in messages (see message_text.h).
#include "scene/message_text.h"

#include <cstdio>

namespace luz {
namespace {

bool is_continuation(unsigned char c) { return (c & 0xC0) == 0x80; }

/// The length of the well-formed UTF-8 character at s[i] (1–4 bytes), or 0 if the bytes there
/// are not one (a stray continuation byte, a bad or cut sequence, an overlong form, a
/// surrogate, beyond U+10FFFF).
std::size_t utf8_length(std::string_view s, std::size_t i) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c < 0x80) return 1;
    const std::size_t n = c >= 0xC2 && c <= 0xDF   ? 2
                          : c >= 0xE0 && c <= 0xEF ? 3
                          : c >= 0xF0 && c <= 0xF4 ? 4
                                                   : 0;
    if (n == 0 || i + n > s.size()) return 0;
    for (std::size_t k = 1; k < n; ++k)
        if (!is_continuation(static_cast<unsigned char>(s[i + k]))) return 0;
    const auto c1 = static_cast<unsigned char>(s[i + 1]);
    if ((c == 0xE0 && c1 < 0xA0) || (c == 0xED && c1 > 0x9F) || (c == 0xF0 && c1 < 0x90) ||
        (c == 0xF4 && c1 > 0x8F))
        return 0;
    return n;
}

/// The first `max_chars` characters of `s` with control characters as \uXXXX, bytes that are
/// not UTF-8 as \xXX and, when `quoted`, " and \ behind a backslash; `cut_from` gets the
/// number of characters of the whole of `s` when it was cut, else 0.
std::string escaped_start(std::string_view s, std::size_t max_chars, bool quoted,
                          std::size_t& cut_from) {
    std::string out;
    std::size_t chars = 0;
    cut_from = 0;
    for (std::size_t i = 0; i < s.size();) {
        const std::size_t n = utf8_length(s, i);
        if (chars == max_chars) {  // count the rest without copying it
            std::size_t total = chars;
            for (std::size_t j = i; j < s.size(); ++total) {
                const std::size_t m = utf8_length(s, j);
                j += m == 0 ? 1 : m;
            }
            cut_from = total;
            return out;
        }
        ++chars;
        const auto c = static_cast<unsigned char>(s[i]);
        char buf[8];
        if (n == 0) {
            std::snprintf(buf, sizeof buf, "\\x%02X", c);
            out += buf;
            ++i;
            continue;
        }
        if ((c < 0x20 && c != '\t') || c == 0x7F) {
            std::snprintf(buf, sizeof buf, "\\u%04X", c);
            out += buf;
        } else {
            if (quoted && (c == '"' || c == '\\')) out += '\\';
            out.append(s.substr(i, n));
        }
        i += n;
    }
    return out;
}

}  // namespace

std::string printable(std::string_view s, std::size_t max_chars) {
    std::size_t total = 0;
    std::string out = escaped_start(s, max_chars, false, total);
    if (total) out += "\xE2\x80\xA6 (" + std::to_string(total) + " characters)";
    return out;
}

std::string quote(std::string_view s, std::size_t max_chars) {
    std::size_t total = 0;
    std::string out = "\"";
    out += escaped_start(s, max_chars, true, total);
    out += total ? "\xE2\x80\xA6\" (" + std::to_string(total) + " characters)" : "\"";
    return out;
}

std::string bytes_text(uint64_t bytes) {
    char buf[48];
    if (bytes >= (uint64_t{1} << 30)) {
        std::snprintf(buf, sizeof buf, "%.1f GiB", bytes / double(uint64_t{1} << 30));
    } else if (bytes >= (uint64_t{1} << 20)) {
        std::snprintf(buf, sizeof buf, "%.1f MiB", bytes / double(uint64_t{1} << 20));
    } else {
        std::snprintf(buf, sizeof buf, "%llu bytes", static_cast<unsigned long long>(bytes));
    }
    return buf;
}

}  // namespace luz
