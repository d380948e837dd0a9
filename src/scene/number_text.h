// Numbers and vectors written as in a scene file (shortest form), for error messages.
#pragma once

#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>
#include <type_traits>

#include "math/vec3.h"

namespace luz {

/// A number as it would be written in the scene, in its shortest form: 1, 0.5, 100000 (whole
/// numbers below 10¹⁵ in full), 1e+39. A double that is a float (a value luz read into its
/// floats, e.g. from an NFF file) in the float's shortest form: 0.2, not 0.20000000298023224.
template <typename T>
std::string format_number(T d) {
    if (std::isnan(d)) return "nan";
    if (std::isinf(d)) return d > 0 ? "inf" : "-inf";
    d += T(0);  // -0 → 0
    char buffer[64];
    const auto write = [&](auto x) {
        if (std::fabs(x) < 1e15 && x == std::trunc(x)) {  // exact in a double's %.0f
            std::snprintf(buffer, sizeof buffer, "%.0f", static_cast<double>(x));
            return std::string(buffer);
        }
        const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
        return std::string(buffer, result.ptr);
    };
    if constexpr (std::is_same_v<T, double>) {
        const auto f = static_cast<float>(d);
        if (std::isfinite(f) && static_cast<double>(f) == d) return write(f);
    }
    return write(d);
}

/// A finite double as JSON text that reads back as the same double (the shortest such text).
inline std::string json_number(double d) {
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, d + 0.0);  // -0 → 0
    return std::string(buffer, result.ptr);
}

/// A vector as "[x, y, z]".
inline std::string format_vec(const Vec3& v) {
    std::string s = "[";  // appended piecewise: "[" + std::string&& trips GCC 12's -Wrestrict
    s += format_number(v.x);
    s += ", ";
    s += format_number(v.y);
    s += ", ";
    s += format_number(v.z);
    s += "]";
    return s;
}

}  // namespace luz
