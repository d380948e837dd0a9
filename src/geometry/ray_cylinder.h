// The one ray–cylinder routine for an open round cylinder in world form (Shape::world_form: base
// B, unit axis w, radius ρ, height h): the roots of |e⊥ + t·d⊥|² = ρ² whose point lies on the
// cylinder (0 ≤ e·w + t·d·w ≤ h; e = o − B, ⊥ the part across the axis). Written once over a
// lane type as ray_sphere.h is — float for one cylinder (shapes/cylinder.h), Lane4f for the
// cylinder lanes of a BVH block (query_parts.h) — so that both compute the very same bits; where
// float cannot be trusted, both leave the cylinder to its object-space test in double.
#pragma once

#include <limits>

#include "geometry/ray_sphere.h"
#include "math/lanes.h"
#include "math/ray.h"

namespace luz {

namespace ray_cylinder {

/// The side's quadratic a·t² + 2b·t + c across the axis: e⊥ = e − (e·w)·w, d⊥ = d − (d·w)·w,
/// a = |d⊥|², b = e⊥·d⊥, c = |e⊥|² − ρ²; the axial coordinate of the point at t is ez + t·dz
/// (ez = e·w, dz = d·w); ee = |e|² and dd = |d|² size the rounding.
template <class F>
struct Terms {
    Lane3<F> ep, dp;
    F ez, dz, a, b, pp, c, ee, dd;
};
template <class F>
inline Terms<F> terms(const Lane3<F>& e, const Lane3<F>& d, const Lane3<F>& w, F rr) {
    Terms<F> k;
    k.ez = dot(e, w);
    k.dz = dot(d, w);
    k.ep = {e.x - w.x * k.ez, e.y - w.y * k.ez, e.z - w.z * k.ez};
    k.dp = {d.x - w.x * k.dz, d.y - w.y * k.dz, d.z - w.z * k.dz};
    k.a = dot(k.dp, k.dp);
    k.b = dot(k.ep, k.dp);
    k.pp = dot(k.ep, k.ep);
    k.c = k.pp - rr;
    k.ee = dot(e, e);
    k.dd = dot(d, d);
    return k;
}

/// Where float is not trusted: a ray within ~2⁻¹⁰ rad of the axis (a tiny, its roots far and
/// ill-conditioned; a = 0 or NaN included), or the sign of c unsure. e⊥ carries a few ulp of |e|,
/// so c's error is some 20 ulp of max(|e|·|e⊥|, ρ²); within 2⁻¹⁷ of that (compared squared, no
/// root taken) — an origin on the side, as spawned rays have — the double test decides.
inline bool needs_double(const Terms<float>& k, float rr) {
    return !(k.a >= 0x1p-20f * k.dd) || k.c * k.c < 0x1p-34f * lane_max(k.ee * k.pp, rr * rr);
}
[[gnu::always_inline]] inline Lane4i needs_double(const Terms<Lane4f>& k, Lane4f rr) {
    return ~lane_ge(k.a, 0x1p-20f * k.dd) |
           lane_lt(k.c * k.c, 0x1p-34f * lane_max(k.ee * k.pp, rr * rr));
}

/// Root t if its point lies on the cylinder (0 ≤ ez + t·dz ≤ h), else NaN.
inline float on_side(float t, const Terms<float>& k, float h) {
    const float z = k.ez + t * k.dz;
    return z >= 0.0f && z <= h ? t : std::numeric_limits<float>::quiet_NaN();
}
[[gnu::always_inline]] inline Lane4f on_side(Lane4f t, const Terms<Lane4f>& k, Lane4f h) {
    const Lane4f z = k.ez + t * k.dz;
    return lane_select(lane_ge(z, lanes4(0.0f)) & lane_le(z, h), t,
                       lanes4(std::numeric_limits<float>::quiet_NaN()));
}

}  // namespace ray_cylinder

/// What world_cylinder_roots() found: no root, roots (each NaN where its point is off the
/// cylinder), or a ray float cannot be trusted with (test the cylinder in object space).
enum class CylinderRoots { miss, met, slow };

/// The roots t0 ≤ t1 of world ray r with the open cylinder of `base`, unit `axis`, radius² rr
/// and `height` (Shape::world_form), each NaN where its point lies beyond the ends.
inline CylinderRoots world_cylinder_roots(const Vec3& base, const Vec3& axis, float rr,
                                          float height, const Ray& r, float& t0, float& t1) {
    const Lane3<float> e{r.origin.x - base.x, r.origin.y - base.y, r.origin.z - base.z};
    const Lane3<float> d{r.direction.x, r.direction.y, r.direction.z};
    const Lane3<float> w{axis.x, axis.y, axis.z};
    const ray_cylinder::Terms<float> k = ray_cylinder::terms(e, d, w, rr);
    if (ray_cylinder::needs_double(k, rr)) return CylinderRoots::slow;
    const float inv_a = 1.0f / k.a;
    const float disc = ray_sphere::discriminant(k.ep, k.dp, k.b, k.a, inv_a, rr);
    if (disc < 0) return CylinderRoots::miss;
    ray_sphere::roots(k.b, k.c, disc, inv_a, t0, t1);
    t0 = ray_cylinder::on_side(t0, k, height);
    t1 = ray_cylinder::on_side(t1, k, height);
    return CylinderRoots::met;
}

/// Four open cylinders in world form by lane (the cylinder lanes of a BVH block, prim_block.h):
/// bases, unit axes, radius² and heights; `used` the lanes to test.
struct CylinderLanes {
    const float *bx, *by, *bz, *wx, *wy, *wz, *rr, *height;
    unsigned used;
};

/// One ray against four cylinder lanes: bit k of `hit` where world_cylinder_roots() returns
/// `met` (roots t0[k] ≤ t1[k], NaN off the cylinder), bit k of `slow` where it returns `slow`.
struct CylinderGroupRoots {
    float t0[4], t1[4];
    unsigned hit = 0, slow = 0;
};

/// world_cylinder_roots() of the lanes g.used on Lane4f lanes, the same steps. `ahead_only`: for
/// a caller that takes roots at t > 0 only, a lane outside (c > 0) moving away from the axis
/// (b > 0) — every ray leaving the side outwards — is not reported: its roots c/q and q/a are
/// both negative (q = −(b + √disc) < 0).
[[gnu::always_inline]] inline CylinderGroupRoots cylinder_lanes_roots(const CylinderLanes& g,
                                                                      const Ray& r,
                                                                      bool ahead_only) {
    using F = Lane4f;
    CylinderGroupRoots out;
    const Lane3<F> e{lanes4(r.origin.x) - load_lanes4(g.bx), lanes4(r.origin.y) - load_lanes4(g.by),
                     lanes4(r.origin.z) - load_lanes4(g.bz)};
    const Lane3<F> d{lanes4(r.direction.x), lanes4(r.direction.y), lanes4(r.direction.z)};
    const Lane3<F> w{load_lanes4(g.wx), load_lanes4(g.wy), load_lanes4(g.wz)};
    const F rr = load_lanes4(g.rr);
    const ray_cylinder::Terms<F> k = ray_cylinder::terms(e, d, w, rr);
    out.slow = lane_bits(ray_cylinder::needs_double(k, rr)) & g.used;
    unsigned solve = g.used & ~out.slow;
    if (ahead_only) solve &= ~lane_bits(lane_gt(k.c, lanes4(0.0f)) & lane_gt(k.b, lanes4(0.0f)));
    if (solve == 0) return out;
    const F inv_a = lanes4(1.0f) / k.a;
    const F disc = ray_sphere::discriminant(k.ep, k.dp, k.b, k.a, inv_a, rr);
    out.hit = ~lane_bits(lane_lt(disc, lanes4(0.0f))) & solve;
    if (out.hit == 0) return out;
    F t0, t1;
    ray_sphere::roots(k.b, k.c, disc, inv_a, t0, t1);
    const F h = load_lanes4(g.height);
    store_lanes4(out.t0, ray_cylinder::on_side(t0, k, h));
    store_lanes4(out.t1, ray_cylinder::on_side(t1, k, h));
    return out;
}

}  // namespace luz
