// The rules of the ray tree (docs/SCENES.md#ray-tracing, #scene-files), written once for every
// engine: where a secondary or shadow ray starts, where reflected and refracted rays go, which
// secondary rays are traced (max_depth, min_weight) and how a child's colour is weighted into its
// parent's (A).
#pragma once

#include <cmath>

#include "geometry/hit.h"
#include "math/ray.h"
#include "math/vec3.h"
#include "scene/material.h"
#include "scene/scene_desc.h"
#include "shading/shade.h"

namespace luz {

/// Offset of secondary and shadow ray origins along the geometric normal
/// (docs/SCENES.md#ray-tracing: ≤ 1e-4).
inline constexpr float kRayEpsilon = 1e-4f;

/// A ray leaving surface point P in direction `dir`, its origin moved by kRayEpsilon along the
/// geometric normal Ng to the side the ray leaves towards (docs/SCENES.md#ray-tracing), so that a
/// surface never shadows or reflects itself by rounding.
inline Ray spawn_ray(const Vec3& P, const Vec3& Ng, const Vec3& dir) {
    return {P + Ng * (dot(dir, Ng) > 0 ? kRayEpsilon : -kRayEpsilon), dir};
}

/// Mirror direction of unit direction D about unit normal N.
inline Vec3 reflect(const Vec3& D, const Vec3& N) { return D - N * (2 * dot(D, N)); }

/// Refraction of unit direction D at a surface with unit normal N facing D's side
/// (dot(D, N) < 0), from index n1 into n2: n1·sin i = n2·sin r. False on total internal
/// reflection.
bool refract(const Vec3& D, const Vec3& N, float n1, float n2, Vec3& T);

/// The directions of the secondary rays leaving a hit `sp` of a ray in unit direction D
/// (docs/SCENES.md#ray-tracing). `reflected`: the mirror direction about the normal facing D
/// (two-sided). `refracted` (only when m.transparency > 0): by Snell's law, from the medium around
/// (1.0) into m.ior when the ray enters (D against Ng), from m.ior back to 1.0 when it leaves; on
/// total internal reflection (`tir`) the mirror direction.
struct Bounce {
    Vec3 reflected, refracted;
    bool tir = false;
};
Bounce bounce(const Vec3& D, const SurfacePoint& sp, const Material& m);

/// Which secondary rays are traced and how their colours come back (docs/SCENES.md#ray-tracing,
/// #scene-files).
struct TreeRules {
    int max_depth = 0;  ///< 0: no secondary rays (raycast, or raytrace with max_depth 0)
    float min_weight = 0;
    /// A depends on d: `render.tree_attenuation` under a law other than `none` (whose A is 1)
    bool tree_attenuation = false;
    float K = 1;                            ///< attenuation_k
    Attenuation law = Attenuation::linear;  ///< the scene's `attenuation`

    TreeRules() = default;
    /// The rules of a render; `full` false (raycast) allows no secondary ray.
    TreeRules(const Settings& s, bool full)
        : max_depth(full ? s.render.max_depth : 0),
          min_weight(s.render.min_weight),
          tree_attenuation(s.render.tree_attenuation && s.attenuation != Attenuation::none),
          K(s.attenuation_k),
          law(s.attenuation) {}

    /// Whether a hit at ray-tree depth `depth` on material m spawns secondary rays.
    bool descends(int depth, const Material& m) const {
        return depth < max_depth && (m.reflection > 0 || m.transparency > 0);
    }
    /// Whether a secondary ray of weight w (the product of the coefficients that scale it) is
    /// traced: below min_weight it is not, and contributes 0.
    bool traced(float w) const { return !(w < min_weight); }
    /// A for a secondary ray whose segment has length d: 1, or with tree_attenuation 1/(d+K)
    /// (`linear`) or 1/d² (`inverse_square`), 0 for a ray that hits nothing (d = ∞).
    float A(float d) const {
        if (!tree_attenuation) return 1.0f;
        return std::isinf(d) ? 0.0f : 1.0f / distance_divisor(law, d, K);
    }
    /// What a child that returned `c` over a segment of length d brings its parent before its
    /// coefficient: A·c.
    Rgb through(const Rgb& c, float d) const {
        if (!tree_attenuation) return c;
        return std::isinf(d) ? Rgb{0.0f} : c * (1.0f / distance_divisor(law, d, K));
    }
};

}  // namespace luz
