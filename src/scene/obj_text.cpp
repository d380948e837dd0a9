// OBJ and MTL text reading: numbers and FILE:LINE errors (see obj_text.h).
#include "scene/obj_text.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>

#include "scene/input_error.h"
#include "scene/message_text.h"

namespace luz::obj_text {

std::string at(const std::string& file, size_t line) {
    return printable(file) + ":" + std::to_string(line) + ": ";
}

[[noreturn]] void fail_at(const std::string& file, size_t line, const std::string& what) {
    throw InputError(at(file, line) + what);
}

std::string_view without_bom(std::string_view text) {
    if (text.size() >= 3 && text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
    return text;
}

namespace {

/// [-]digits[.digits] of at most 15 digits at `p`, as from_chars reads it, or nullptr (then
/// from_chars reads it). The digits as an integer m < 10¹⁵ < 2⁵³ and 10^k (k ≤ 15) are exact
/// doubles, so m / 10^k rounds once: the nearest double, which from_chars gives too (Clinger's
/// fast path, as in fast_float).
const char* read_short_decimal(const char* p, const char* end, double& d) {
    static constexpr double kTen[] = {1e0, 1e1, 1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                      1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};
    const bool minus = p < end && *p == '-';
    p += minus;
    uint64_t m = 0;
    int digits = 0, fraction = -1;  // fraction: digits after the point (−1: no point yet)
    for (; p < end; ++p) {
        if (*p >= '0' && *p <= '9') {
            m = 10 * m + static_cast<uint64_t>(*p - '0');
            ++digits;
            fraction += fraction >= 0;
        } else if (*p == '.' && fraction < 0 && digits > 0) {
            fraction = 0;
        } else {
            break;
        }
    }
    if (digits == 0 || digits > 15 || fraction == 0) return nullptr;  // "1." is from_chars's
    if (p < end && (*p == 'e' || *p == 'E')) return nullptr;          // an exponent
    d = static_cast<double>(m) / kTen[std::max(fraction, 0)];
    if (minus) d = -d;
    return p;
}

}  // namespace

bool Tokens::next_plain_number(float& x) {
    size_t i = 0;
    while (i < rest_.size() && is_blank(rest_[i])) ++i;
    const char *begin = rest_.data() + i, *end = rest_.data() + rest_.size();
    double d = 0;
    // from_chars stops at a blank: ptr at the token's end means the whole token is the number
    const char* const short_end = read_short_decimal(begin, end, d);
    const auto [ptr, ec] =
        short_end ? std::from_chars_result{short_end, std::errc()} : std::from_chars(begin, end, d);
    if (ec != std::errc() || ptr == begin || (ptr != end && !is_blank(*ptr)) ||
        !(std::fabs(d) <= std::numeric_limits<float>::max())) {
        return false;
    }
    x = static_cast<float>(d);
    rest_.remove_prefix(static_cast<size_t>(ptr - rest_.data()));
    return true;
}

float read_number(std::string_view token, const std::string& file, size_t line,
                  std::string_view statement) {
    std::string_view t = token;
    if (!t.empty() && t[0] == '+') t.remove_prefix(1);
    double d = 0;
    const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), d);
    if (ec == std::errc() && ptr == t.data() + t.size() && !t.empty() && t[0] != '+' &&
        std::fabs(d) <= std::numeric_limits<float>::max()) {
        return static_cast<float>(d);  // the usual case, without building any message
    }
    const std::string where = std::string(statement) + ": ";
    if (t.empty() || t[0] == '+' || ptr != t.data() + t.size() ||
        (ec != std::errc() && ec != std::errc::result_out_of_range)) {
        fail_at(file, line, where + "malformed number " + quote(token));
    }
    if (ec == std::errc::result_out_of_range) {
        // from_chars leaves d alone: strtod tells overflow (±HUGE_VAL) from underflow (≈ 0)
        d = std::strtod(std::string(t).c_str(), nullptr);
        if (std::isinf(d)) fail_at(file, line, where + "number out of range " + quote(token));
    }
    if (!std::isfinite(d)) fail_at(file, line, where + "not a finite number " + quote(token));
    if (!(std::fabs(d) <= std::numeric_limits<float>::max())) {
        fail_at(file, line, where + "number out of float range " + quote(token));
    }
    return static_cast<float>(d);
}

int read_numbers(Tokens& tokens, float* out, int min_count, int max_count, const std::string& file,
                 size_t line, std::string_view statement) {
    int n = 0;
    std::string_view token;
    for (;;) {
        if (n < max_count && tokens.next_plain_number(out[n])) {  // the usual case
            ++n;
            continue;
        }
        if (!tokens.next(token)) break;
        if (n == max_count) {
            fail_at(file, line,
                    std::string(statement) + ": expected at most " + std::to_string(max_count) +
                        " numbers, got more (" + quote(token) + ")");
        }
        out[n++] = read_number(token, file, line, statement);
    }
    if (n < min_count) {
        fail_at(file, line,
                std::string(statement) + ": expected " +
                    (min_count == max_count ? "" : "at least ") + std::to_string(min_count) +
                    " number" + (min_count == 1 ? "" : "s") + ", got " + std::to_string(n));
    }
    return n;
}

}  // namespace luz::obj_text
