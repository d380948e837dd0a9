// shade(): the illumination models of docs/SCENES.md#models, the only place they are written.
// Both pipelines build a ShadingPoint and call it; it returns the colour and, on request, its
// terms.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <span>

#include "luz/ray_tree.h"  // LightTerm: what shade() tells of each light
#include "math/vec3.h"
#include "scene/material.h"
#include "scene/scene_desc.h"
#include "shading/reflectance.h"

namespace luz {

/// What the model needs of the scene: the model, Ia, K, the lights and the distance law.
struct Lighting {
    Model model = Model::phong;
    Rgb Ia{1.0f};    ///< ambient light
    float K = 1.0f;  ///< attenuation constant of Il/(d+K)
    std::span<const Light> lights;
    Attenuation attenuation = Attenuation::linear;  ///< the law of phong's light term
};

/// The divisor of phong's light term Il/divisor at distance d (docs/SCENES.md#models
/// `attenuation`): d + K
/// (`linear`), 1 (`none`), d² (`inverse_square`). Also the tree attenuation's 1/A (recursion.h).
inline float distance_divisor(Attenuation law, float d, float K) {
    switch (law) {
        case Attenuation::none:
            return 1.0f;
        case Attenuation::inverse_square:
            return d * d;
        case Attenuation::linear:
            break;
    }
    return d + K;
}

/// A surface point as both pipelines see it.
struct ShadingPoint {
    Vec3 P;   ///< world position
    Vec3 N;   ///< unit shading normal (outward; flipped towards the viewer by shade())
    Vec3 Ng;  ///< unit outward geometric normal (checker cells; two-sided flip test)
    Vec3 S;   ///< unit vector from P towards the viewer
    const Material* material = nullptr;
};

/// The terms that add up to shade()'s colour: ambient + Σ_j (diffuse_j + specular_j).
struct ShadeTerms {
    Rgb ambient;                 ///< Ia·Ka
    std::span<LightTerm> light;  ///< one per light, filled when at least lights.size() long
    bool flipped = false;        ///< N was flipped towards the viewer (two-sided normals)
};

/// cosα^n for cosα in [0, 1] and n > 0, as std::pow gives it, except that a power below
/// 2^-151 (which rounds to 0 in float, after std::pow's slow underflow path) is 0 at once,
/// and so is 0^n.
inline float phong_power(float cos_alpha, float n) {
    if (!(cos_alpha > 0)) return 0.0f;
    // An upper bound of log2 cosα from its bits: cosα = (1 + x)·2^E with x in [0, 1) and
    // log2(1 + x) ≤ x/ln 2 (subnormals: E = −127 overstates them, still a bound).
    const uint32_t bits = std::bit_cast<uint32_t>(cos_alpha);
    const float E = static_cast<float>(static_cast<int>(bits >> 23) - 127);
    const float x = static_cast<float>(bits & 0x7FFFFFu) * 0x1p-23f;
    if (n * (E + 1.4426951f * x) < -151.0f) return 0.0f;  // 2^-151: 0 after rounding
    return std::pow(cos_alpha, n);
}

/// Evaluates the model at p (docs/SCENES.md#models). `visibility(j, P, L_j, d_j)` returns vis_j and
/// is only asked for lights in front of the surface (cosθ_j > 0). Writes the terms when `terms` is
/// set.
template <class Visibility>
inline Rgb shade(const ShadingPoint& p, const Lighting& lighting, Visibility&& visibility,
                 ShadeTerms* terms = nullptr) {
    const Material& m = *p.material;
    const SurfaceConstants c = surface_constants(m, p.P, p.Ng);

    // Two-sided normals (docs/SCENES.md#geometry): N faces the viewer.
    Vec3 N = p.N;
    const bool flipped = dot(N, p.S) < 0;
    if (flipped) N = -N;

    const Rgb ambient = lighting.Ia * c.ka;  // Ia·Ka
    Rgb I = ambient;
    const bool write_terms = terms && terms->light.size() >= lighting.lights.size();
    if (terms) {
        terms->ambient = ambient;
        terms->flipped = flipped;
    }
    for (size_t j = 0; j < lighting.lights.size(); ++j) {
        const Light& light = lighting.lights[j];
        const Vec3 to_light = light.position - p.P;
        const float d = length(to_light);
        const Vec3 L = to_light / d;
        const float N_dot_L = dot(N, L);
        LightTerm t;
        t.distance = d;
        if (N_dot_L > 0) {
            t.cos_theta = N_dot_L;  // cosθ_j = max(0, N·L_j)
            t.visibility = visibility(j, p.P, L, d);
            // Light j's diffuse and specular terms with visibility `vis`.
            auto light_terms = [&](float vis, Rgb& diffuse, Rgb& specular) {
                if (lighting.model == Model::lambert) {
                    // I += vis_j·Il_j·Kd·cosθ_j
                    diffuse = light.intensity * c.kd * (vis * t.cos_theta);
                } else {
                    // I += vis_j·Il_j/(d_j+K)·(Kd·cosθ_j + Ks·cosα_j^n), d_j+K or the
                    // attenuation law's divisor (1, d_j²)
                    const Vec3 R = N * (2 * N_dot_L) - L;  // mirror direction of L_j
                    const float R_dot_S = dot(R, p.S);
                    t.cos_alpha = R_dot_S > 0 ? R_dot_S : 0.0f;
                    const Rgb Il_att =
                        light.intensity *
                        (vis / distance_divisor(lighting.attenuation, d, lighting.K));
                    diffuse = Il_att * c.kd * t.cos_theta;
                    // w(θ_j)·cosα^n, w = Ks or Schlick's curve (docs/SCENES.md#reflectance); w = 0
                    // needs no power
                    const Rgb w = specular_reflectance(m, t.cos_theta);
                    if (max_component(w) > 0) {
                        specular = Il_att * w * phong_power(t.cos_alpha, m.n);
                    }
                }
            };
            if (t.visibility > 0) {
                light_terms(t.visibility, t.diffuse, t.specular);
                I += t.diffuse + t.specular;
            }
            if (write_terms) {  // what the light would add unshadowed (the shadow term)
                if (t.visibility == 1) {
                    t.unshadowed = t.diffuse + t.specular;
                } else {
                    Rgb diffuse, specular;
                    light_terms(1.0f, diffuse, specular);
                    t.unshadowed = diffuse + specular;
                }
            }
        }
        if (write_terms) terms->light[j] = t;
    }
    return I;
}

/// Visibility for pipelines without shadow rays (zbuffer, raycast): every light is seen.
struct AllVisible {
    float operator()(size_t, const Vec3&, const Vec3&, float) const { return 1.0f; }
};

}  // namespace luz
