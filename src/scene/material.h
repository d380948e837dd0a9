// Material is a public type (include/luz/material.h); here, what the layers make of it: the
// constants at a surface point, where the checker may replace them.
#pragma once

#include <cmath>

#include "luz/material.h"

namespace luz {

/// Ka and Kd at a surface point (the checker may replace them).
struct SurfaceConstants {
    Rgb ka, kd;
};

/// The constants at world point P with outward geometric normal Ng (docs/SCENES.md#scene-files
/// `checker`): P is moved by 0.001·size against Ng before choosing the cell.
inline SurfaceConstants surface_constants(const Material& m, const Vec3& P, const Vec3& Ng) {
    if (!m.checker) return {m.ka, m.kd};
    const Checker& c = *m.checker;
    const Vec3 p = P - Ng * (0.001f * c.size);
    const long long cell = static_cast<long long>(std::floor(p.x / c.size)) +
                           static_cast<long long>(std::floor(p.y / c.size)) +
                           static_cast<long long>(std::floor(p.z / c.size));
    if (cell & 1) return {c.ka, c.kd};
    return {m.ka, m.kd};
}

}  // namespace luz
