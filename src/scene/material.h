// Material: the constants of the illumination models (SPEC §1, §1.4, §2), and the checker
// pattern.
#pragma once

#include <cmath>
#include <optional>
#include <string>

#include "math/vec3.h"

namespace luz {

/// The classic Whitted floor: in odd cells of a 3D checkerboard, ka and kd are replaced.
struct Checker {
    float size = 1.0f;
    Rgb ka{0.02f};
    Rgb kd{0.1f};
};

/// The reflectance curve w(i, λ) of the specular term (SPEC §1.4; shading/reflectance.h).
enum class Reflectance {
    constant,  ///< w = Ks: the models of SPEC §1 exactly
    schlick,   ///< w(θ_j) = Ks + (1 − Ks)·(1 − cosθ_j)^5 per channel
};

struct Material {
    std::string name;  ///< the key in `materials`, a preset name, or empty when inline
    Rgb ka{0.1f};      ///< ambient reflection constant Ka (slide's tested value)
    Rgb kd{0.45f};     ///< diffuse reflection constant Kd (slide's tested value)
    Rgb ks{0.3f};      ///< specular reflection constant Ks (schlick: w at normal incidence)
    float n = 20.0f;   ///< specular exponent
    float reflection = 0.0f;
    float transparency = 0.0f;
    float ior = 1.0f;
    Reflectance reflectance = Reflectance::constant;  ///< w(i, λ): Ks, or Schlick's curve
    std::optional<Checker> checker;
};

/// Ka and Kd at a surface point (the checker may replace them).
struct SurfaceConstants {
    Rgb ka, kd;
};

/// The constants at world point P with outward geometric normal Ng (SPEC §2 `checker`):
/// P is moved by 0.001·size against Ng before choosing the cell.
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
