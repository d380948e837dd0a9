// Numbers and vectors written as in a scene file (shortest form), for error messages.
#pragma once

#include <charconv>
#include <cmath>
#include <string>

#include "math/vec3.h"

namespace luz {

/// A number as it would be written in the scene (shortest form: 1, 0.5, 1e+39).
template <typename T>
std::string format_number(T d) {
    if (std::isnan(d)) return "nan";
    if (std::isinf(d)) return d > 0 ? "inf" : "-inf";
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, d + T(0));  // -0 → 0
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
