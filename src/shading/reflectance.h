// The reflectance curve w(i, λ) of the specular term (docs/SCENES.md#reflectance): the constant Ks
// of the lecture's practical model, or Schlick's approximation of Fresnel's equation per RGB
// channel. shade() multiplies the specular term by it.
#pragma once

#include "math/vec3.h"
#include "scene/material.h"

namespace luz {

/// Schlick's curve: w(θ) = Ks + (1 − Ks)·(1 − cosθ)^5 per channel (docs/SCENES.md#reflectance), for
/// cosθ in [0, 1]; Ks is the reflectance at normal incidence (cosθ = 1), and w rises to 1 at
/// grazing incidence (cosθ = 0).
inline Rgb schlick_reflectance(const Rgb& Ks, float cos_theta) {
    const float f = 1.0f - cos_theta;
    const float f2 = f * f;
    const float f5 = f2 * f2 * f;  // (1 − cosθ)^5
    return Ks + (Rgb{1.0f} - Ks) * f5;
}

/// w(θ_j) of material m for light j at cosθ_j = max(0, N·L_j) (docs/SCENES.md#reflectance):
/// `constant` gives m.ks itself (the models of docs/SCENES.md#models, bit for bit), `schlick`
/// Schlick's curve from Ks = m.ks.
inline Rgb specular_reflectance(const Material& m, float cos_theta) {
    if (m.reflectance == Reflectance::schlick) return schlick_reflectance(m.ks, cos_theta);
    return m.ks;
}

}  // namespace luz
