// Material: the constants of the illumination models (docs/SCENES.md#models, #reflectance,
// #scene-files), and the checker pattern (scene/material.h: the constants it gives at a point).
#pragma once

#include <optional>
#include <string>

#include "luz/vec3.h"

namespace luz {

/// The classic Whitted floor: in odd cells of a 3D checkerboard, ka and kd are replaced.
struct Checker {
    float size = 1.0f;
    Rgb ka{0.02f};
    Rgb kd{0.1f};
};

/// The reflectance curve w(i, λ) of the specular term (docs/SCENES.md#reflectance;
/// shading/reflectance.h).
enum class Reflectance {
    constant,  ///< w = Ks: the models of docs/SCENES.md#models exactly
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

}  // namespace luz
