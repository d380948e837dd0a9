// The one ray–sphere routine: the roots of |o + t·d|² = ρ² (o the origin relative to the
// centre), written once over a lane type (math/lanes.h) — float for world-form spheres and light
// spheres, double for object space and the float path's fallback, four floats (Lane4f) for
// sphere lanes — so that every caller computes the very same bits.
#pragma once

#include "math/lanes.h"
#include "math/ray.h"
#include "math/vec3.h"

namespace luz {

/// A point or vector of lanes F (float, double or Lane4f).
template <class F>
struct Lane3 {
    F x, y, z;
};
template <class F>
inline F dot(const Lane3<F>& a, const Lane3<F>& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

/// The steps of the solver, each the same arithmetic whatever F is.
namespace ray_sphere {

/// b = o·d, oo = |o|², c = |o|² − ρ² (the quadratic a·t² + 2b·t + c, a = |d|²).
template <class F>
struct Terms {
    F b, oo, c;
};
template <class F>
inline Terms<F> terms(const Lane3<F>& o, const Lane3<F>& d, F rr) {
    const F b = dot(o, d), oo = dot(o, o);
    return {b, oo, oo - rr};
}

/// Where float cannot be trusted with the sign of c: |error of c| ≤ ~3 ulp of max(|o|², ρ²);
/// beyond 2^-17 of it c's sign is sure and the near root's error stays at the float rounding
/// of the ray itself. Within it (an origin on the surface, as spawned rays have), solve in
/// double.
template <class F>
inline auto needs_double(F c, F oo, F rr) {
    return lane_abs(c) < 0x1p-17f * lane_max(oo, rr);
}

/// A division-free test that the line surely misses, for the many rays that do (every ray
/// tests the light spheres): the textbook discriminant b² − a·c below −2^-12·(b² + a·(|o|² + ρ²)).
/// The rounding errors of that form and of discriminant() (float or double) are each a few
/// tens of ulp of b² + a·(|o|² + ρ²), far below the margin, so discriminant() is then
/// negative too: the pre-test changes no result, it only spares the division. NaN and
/// infinite terms never pass it. Valid for a ≥ kMinPreTestA (no denormal terms).
inline constexpr float kMinPreTestA = 0x1p-64f;
template <class F>
inline auto surely_misses(F a, const Terms<F>& k, F rr) {
    const F bb = k.b * k.b;
    return bb - a * k.c < -0x1p-12f * (bb + a * (k.oo + rr));
}

/// disc = b² − a·c computed as a·(ρ² − |o − d·(b/a)|²): no cancellation for distant origins
/// (Haines et al., "Precision improvements for ray/sphere intersection", Ray Tracing Gems ch. 7).
template <class F>
inline F discriminant(const Lane3<F>& o, const Lane3<F>& d, F b, F a, F inv_a, F rr) {
    const F s = b * inv_a;
    const Lane3<F> l{o.x - d.x * s, o.y - d.y * s, o.z - d.z * s};
    return a * (rr - dot(l, l));
}

/// The roots t0 ≤ t1 for disc ≥ 0, cancellation-free: q = −(b + copysign(√disc, b)), roots
/// c/q and q/a.
template <class F>
inline void roots(F b, F c, F disc, F inv_a, F& t0, F& t1) {
    const F q = -(b + lane_copysign(lane_sqrt(disc), b));
    const F f0 = c / q, f1 = q * inv_a;
    t0 = lane_min(f0, f1);
    t1 = lane_max(f0, f1);
}

/// The whole solver for one scalar lane type: false if the line misses (or d = 0).
template <class F>
inline bool solve(const Lane3<F>& o, const Lane3<F>& d, F rr, F& t0, F& t1) {
    const F a = dot(d, d);
    if (!(a > 0)) return false;
    const F inv_a = F(1) / a;
    const Terms<F> k = terms(o, d, rr);
    const F disc = discriminant(o, d, k.b, a, inv_a, rr);
    if (disc < 0) return false;
    roots(k.b, k.c, disc, inv_a, t0, t1);
    return true;
}

}  // namespace ray_sphere

/// The roots t0 ≤ t1 of ray r with the sphere |p − centre| = radius, in double (ray_sphere.cpp:
/// kept out of line, it is the rare path of world_sphere_roots()); false if it misses.
bool world_sphere_roots_double(const Vec3& centre, float radius, const Ray& r, float& t0,
                               float& t1);

/// The roots t0 ≤ t1 of world ray r with the sphere of `centre` and `radius` (a sphere in world
/// form, Shape::world_form, or a light sphere), false if it misses. A sure miss is told first
/// without a division (ray_sphere::surely_misses); then solved in float, or in double where
/// float cannot be trusted (ray_sphere::needs_double).
inline bool world_sphere_roots(const Vec3& centre, float radius, const Ray& r, float& t0,
                               float& t1) {
    const Lane3<float> o{r.origin.x - centre.x, r.origin.y - centre.y, r.origin.z - centre.z};
    const Lane3<float> d{r.direction.x, r.direction.y, r.direction.z};
    const float rr = radius * radius;
    const float a = dot(d, d);
    const ray_sphere::Terms<float> k = ray_sphere::terms(o, d, rr);
    if (a >= ray_sphere::kMinPreTestA && ray_sphere::surely_misses(a, k, rr)) return false;
    if (ray_sphere::needs_double(k.c, k.oo, rr) || !(a > 0)) {
        return world_sphere_roots_double(centre, radius, r, t0, t1);
    }
    const float inv_a = 1.0f / a;
    const float disc = ray_sphere::discriminant(o, d, k.b, a, inv_a, rr);
    if (disc < 0) return false;
    ray_sphere::roots(k.b, k.c, disc, inv_a, t0, t1);
    return true;
}

}  // namespace luz
