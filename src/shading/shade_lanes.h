// shade_lanes(): shade() at eight surface points side by side, no terms asked for: the zbuffer's
// fragments (every light seen) and the ray tracer's camera hits (a visibility per light and
// lane from their shadow rays, traced side by side). Any material: Schlick's reflectance is
// taken in lanes (ShadingLanes::schlick), and a checker's Ka and Kd are the caller's to fill per
// lane (surface_constants()). Each lane computes what shade() computes, with the same
// operations in the same order, so that every lane's colour has shade()'s bits
// (tests/shading/shade_lanes_test.cpp; with shadows, tests/render/ray_tracer_test.cpp); only
// cosα^n is taken lane by lane (phong_power()).
#pragma once

#include "math/lane8.h"
#include "shading/shade.h"

namespace luz {

/// Eight surface points (one per lane) and their materials' constants, by component.
struct ShadingLanes {
    Lane8f P[3];          ///< world position
    Lane8f N[3];          ///< unit shading normal (flipped towards the viewer by shade_lanes())
    Lane8f S[3];          ///< unit vector from P towards the viewer
    Lane8f ka[3], kd[3];  ///< surface_constants() at P: a checker's cell already chosen
    Lane8f ks[3], n;
    Lane8i schlick{};  ///< lanes whose w(θ) is Schlick's curve from Ks (else Ks itself)
};

namespace lanes_detail {
inline Lane8f dot(const Lane8f a[3], const Lane8f b[3]) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
}  // namespace lanes_detail

/// Visibility for shade_lanes() without shadow rays: every light seen in every lane.
struct AllVisibleLanes {
    [[gnu::always_inline]] Lane8f operator()(size_t, const Lane8f*, const Lane8f&, unsigned) const {
        return lanes(1.0f);
    }
};

/// distance_divisor() (shade.h) of eight distances: d + K, 1 or d².
[[gnu::always_inline]] inline Lane8f distance_divisor(Attenuation law, Lane8f d, float K) {
    switch (law) {
        case Attenuation::none:
            return lanes(1.0f);
        case Attenuation::inverse_square:
            return d * d;
        case Attenuation::linear:
            break;
    }
    return d + K;
}

/// shade(p_k, lighting, visibility) in lane k of I, for the lanes of `active` (bit k: lane k).
/// `visibility(j, L, d, lit)` gives vis_j by lane, read in the lanes of `lit` (active, in front
/// of the surface) only, and is not called when there are none.
template <class Visibility = AllVisibleLanes>
[[gnu::always_inline]] inline void shade_lanes(const ShadingLanes& p, const Lighting& lighting,
                                               unsigned active, Lane8f I[3],
                                               Visibility&& visibility = {}) {
    using lanes_detail::dot;
    const Lane8f zero = lanes(0.0f), one = lanes(1.0f);

    // Two-sided normals (docs/SCENES.md#geometry): N faces the viewer.
    const Lane8i flipped = lane_lt(dot(p.N, p.S), zero);
    Lane8f N[3];
    for (int a = 0; a < 3; ++a) N[a] = lane_select(flipped, -p.N[a], p.N[a]);

    const float Ia[3] = {lighting.Ia.x, lighting.Ia.y, lighting.Ia.z};
    for (int a = 0; a < 3; ++a) I[a] = Ia[a] * p.ka[a];  // Ia·Ka
    // max_component(w) > 0: the specular term needs a power
    const auto max_component = [](const Lane8f w[3]) {
        return lane_select(lane_gt(w[0], w[1]), lane_select(lane_gt(w[0], w[2]), w[0], w[2]),
                           lane_select(lane_gt(w[1], w[2]), w[1], w[2]));
    };
    const bool any_schlick = (lane_bits(p.schlick) & active) != 0;
    const Lane8i has_ks = lane_gt(max_component(p.ks), zero);

    for (size_t j = 0; j < lighting.lights.size(); ++j) {
        const Light& light = lighting.lights[j];
        const float Lp[3] = {light.position.x, light.position.y, light.position.z};
        const float Il[3] = {light.intensity.x, light.intensity.y, light.intensity.z};
        Lane8f to_light[3];
        for (int a = 0; a < 3; ++a) to_light[a] = Lp[a] - p.P[a];
        const Lane8f d = lane_sqrt(dot(to_light, to_light));
        const Lane8f inv_d = one / d;
        Lane8f L[3];
        for (int a = 0; a < 3; ++a) L[a] = to_light[a] * inv_d;
        const Lane8f N_dot_L = dot(N, L);
        const Lane8i front = lane_gt(N_dot_L, zero);
        const unsigned front_bits = lane_bits(front) & active;
        if (front_bits == 0) continue;
        const Lane8f cos_theta = N_dot_L;  // cosθ_j = max(0, N·L_j) where lit
        const Lane8f vis = visibility(j, L, d, front_bits);
        const Lane8i lit = front & lane_gt(vis, zero);  // shade() adds nothing where vis_j = 0
        Lane8f diffuse[3], specular[3] = {zero, zero, zero};
        if (lighting.model == Model::lambert) {
            // I += vis_j·Il_j·Kd·cosθ_j
            for (int a = 0; a < 3; ++a) diffuse[a] = (Il[a] * p.kd[a]) * (vis * cos_theta);
        } else {
            // I += vis_j·Il_j/(d_j+K)·(Kd·cosθ_j + Ks·cosα_j^n), d_j+K or the law's divisor
            Lane8f R[3];  // mirror direction of L_j
            const Lane8f two_N_dot_L = 2.0f * N_dot_L;
            for (int a = 0; a < 3; ++a) R[a] = N[a] * two_N_dot_L - L[a];
            const Lane8f R_dot_S = dot(R, p.S);
            const Lane8f cos_alpha = lane_select(lane_gt(R_dot_S, zero), R_dot_S, zero);
            const Lane8f att = vis / distance_divisor(lighting.attenuation, d, lighting.K);
            Lane8f Il_att[3];
            for (int a = 0; a < 3; ++a) {
                Il_att[a] = Il[a] * att;
                diffuse[a] = (Il_att[a] * p.kd[a]) * cos_theta;
            }
            // w(θ_j) (reflectance.h): Ks, or Schlick's Ks + (1 − Ks)·(1 − cosθ_j)^5
            Lane8f w[3] = {p.ks[0], p.ks[1], p.ks[2]};
            Lane8i has_specular = has_ks;
            if (any_schlick) {
                const Lane8f f = one - cos_theta;
                const Lane8f f2 = f * f;
                const Lane8f f5 = f2 * f2 * f;
                for (int a = 0; a < 3; ++a)
                    w[a] = lane_select(p.schlick, p.ks[a] + (one - p.ks[a]) * f5, p.ks[a]);
                has_specular = lane_gt(max_component(w), zero);
            }
            // cosα^n lane by lane, where the light is in front and w > 0 (else no power)
            alignas(32) float cos_a[kPacketLanes], n[kPacketLanes], pow_a[kPacketLanes] = {};
            store_lanes(cos_a, cos_alpha);
            store_lanes(n, p.n);
            for (unsigned m = lane_bits(lit & has_specular) & active; m; m &= m - 1) {
                const int k = __builtin_ctz(m);
                pow_a[k] = phong_power(cos_a[k], n[k]);
            }
            const Lane8f power = load_lanes(pow_a);
            const Lane8i specular_lanes = lit & has_specular;
            for (int a = 0; a < 3; ++a)
                specular[a] = lane_select(specular_lanes, (Il_att[a] * w[a]) * power, zero);
        }
        for (int a = 0; a < 3; ++a)
            I[a] = lane_select(lit, I[a] + (diffuse[a] + specular[a]), I[a]);
    }
}

}  // namespace luz
