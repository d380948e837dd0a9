// Quoting input text in messages (see message_text.h).
#include "scene/message_text.h"

#include <cstdio>

namespace luz {
namespace {

bool is_continuation(unsigned char c) { return (c & 0xC0) == 0x80; }

/// The first `max_chars` characters of `s` with control characters escaped; `cut_from` gets the
/// number of characters of the whole of `s` when it was cut, else 0.
std::string escaped_start(std::string_view s, std::size_t max_chars, std::size_t& cut_from) {
    std::string out;
    std::size_t chars = 0;
    cut_from = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
        const auto c = static_cast<unsigned char>(s[i]);
        if (!is_continuation(c)) {
            if (chars == max_chars) {
                // count the rest without copying it
                std::size_t total = chars;
                for (std::size_t j = i; j < s.size(); ++j) {
                    total += !is_continuation(static_cast<unsigned char>(s[j]));
                }
                cut_from = total;
                return out;
            }
            ++chars;
        }
        if ((c < 0x20 && c != '\t') || c == 0x7F) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04X", c);
            out += buf;
        } else {
            out += static_cast<char>(c);
        }
    }
    return out;
}

}  // namespace

std::string printable(std::string_view s, std::size_t max_chars) {
    std::size_t total = 0;
    std::string out = escaped_start(s, max_chars, total);
    if (total) out += "\xE2\x80\xA6 (" + std::to_string(total) + " characters)";
    return out;
}

std::string quote(std::string_view s, std::size_t max_chars) {
    std::size_t total = 0;
    std::string out = "\"";
    out += escaped_start(s, max_chars, total);
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
