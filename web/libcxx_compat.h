// What Emscripten 3.1.6's libc++ 14 lacks of C++20, for the web build (force-included by
// web/CMakeLists.txt): std::bit_cast, and floating-point std::to_chars (shortest form) and
// std::from_chars ("C" locale), and std::string's operator<=>, with the standard's results
// (printf/strtod, correctly rounded).
#pragma once

#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <compare>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace luz_web {

template <class T>
std::to_chars_result shortest(char* first, char* last, T v) {
    char out[64];
    size_t n = 0;
    if (std::signbit(v) && v == v) out[n++] = '-', v = -v;
    if (std::isinf(v)) {
        std::memcpy(out + n, "inf", 3), n += 3;
    } else if (std::isnan(v)) {
        std::memcpy(out + n, "nan", 3), n += 3;
    } else {
        // The fewest significant digits that read back as v, then f or e, whichever is shorter.
        char e[40];
        for (int p = 1; p <= 17; ++p) {
            std::snprintf(e, sizeof e, "%.*e", p - 1, static_cast<double>(v));
            const T back = sizeof(T) == 4 ? static_cast<T>(std::strtof(e, nullptr))
                                          : static_cast<T>(std::strtod(e, nullptr));
            if (back == v) break;
        }
        std::string digits;
        const char* c = e;
        for (; *c != 'e'; ++c)
            if (*c != '.') digits += *c;
        const int x = std::atoi(c + 1);
        const int nd = static_cast<int>(digits.size());
        std::string sci = digits.substr(0, 1);
        if (nd > 1) sci += "." + digits.substr(1);
        char ex[8];
        std::snprintf(ex, sizeof ex, "e%c%02d", x < 0 ? '-' : '+', x < 0 ? -x : x);
        sci += ex;
        std::string fixed;
        if (x >= nd - 1)
            fixed = digits + std::string(static_cast<size_t>(x - nd + 1), '0');
        else if (x < 0)
            fixed = "0." + std::string(static_cast<size_t>(-x - 1), '0') + digits;
        else
            fixed = digits.substr(0, static_cast<size_t>(x + 1)) + "." +
                    digits.substr(static_cast<size_t>(x + 1));
        const std::string& best = fixed.size() <= sci.size() ? fixed : sci;
        std::memcpy(out + n, best.data(), best.size()), n += best.size();
    }
    if (static_cast<size_t>(last - first) < n) return {last, std::errc::value_too_large};
    std::memcpy(first, out, n);
    return {first + n, std::errc()};
}

inline bool starts_nocase(const char* p, const char* last, const char* word) {
    for (; *word; ++word, ++p)
        if (p == last || (*p | 0x20) != *word) return false;
    return true;
}

template <class T>
std::from_chars_result parse(const char* first, const char* last, T& value) {
    const char* p = first;
    if (p != last && *p == '-') ++p;
    const char* body = p;
    if (starts_nocase(p, last, "inf") || starts_nocase(p, last, "nan")) {
        p += 3;
        if (*body == 'i' || *body == 'I') {
            if (starts_nocase(p, last, "inity")) p += 5;
        } else if (p != last && *p == '(') {
            const char* q = p + 1;
            while (q != last && (std::isalnum(static_cast<unsigned char>(*q)) || *q == '_')) ++q;
            if (q != last && *q == ')') p = q + 1;
        }
    } else {
        int digits = 0;
        while (p != last && *p >= '0' && *p <= '9') ++p, ++digits;
        if (p != last && *p == '.') {
            ++p;
            while (p != last && *p >= '0' && *p <= '9') ++p, ++digits;
        }
        if (digits == 0) return {first, std::errc::invalid_argument};
        if (p != last && (*p == 'e' || *p == 'E')) {
            const char* q = p + 1;
            if (q != last && (*q == '+' || *q == '-')) ++q;
            if (q != last && *q >= '0' && *q <= '9') {
                while (q != last && *q >= '0' && *q <= '9') ++q;
                p = q;
            }
        }
    }
    const std::string text(first, p);
    errno = 0;
    const T v = sizeof(T) == 4 ? static_cast<T>(std::strtof(text.c_str(), nullptr))
                               : static_cast<T>(std::strtod(text.c_str(), nullptr));
    const bool text_inf = starts_nocase(body, last, "inf");
    if (errno == ERANGE && ((std::isinf(v) && !text_inf) || v == 0))
        return {p, std::errc::result_out_of_range};
    value = v;
    return {p, std::errc()};
}

}  // namespace luz_web

namespace std {
#if !defined(__cpp_lib_bit_cast)
template <class To, class From>
constexpr To bit_cast(const From& from) noexcept {
    return __builtin_bit_cast(To, from);
}
#endif
#if defined(_LIBCPP_VERSION) && _LIBCPP_VERSION < 15000
inline strong_ordering operator<=>(const string& a, const string& b) noexcept {
    return a.compare(b) <=> 0;
}
#endif
inline to_chars_result to_chars(char* first, char* last, double v) {
    return luz_web::shortest(first, last, v);
}
inline to_chars_result to_chars(char* first, char* last, float v) {
    return luz_web::shortest(first, last, v);
}
inline from_chars_result from_chars(const char* first, const char* last, double& v) {
    return luz_web::parse(first, last, v);
}
inline from_chars_result from_chars(const char* first, const char* last, float& v) {
    return luz_web::parse(first, last, v);
}
}  // namespace std
