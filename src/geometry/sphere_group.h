// Spheres in world form side by side, four lanes of them, and their roots with one ray for all
// four at once (SSE2): how the scene queries test the sphere lanes of the BVH's leaves
// (query_parts.h).
// Every lane runs the steps of world_sphere_roots() (ray_sphere.h) on Float4 lanes, the same
// template code, so its roots are the same bits; a lane that needs that function's double path
// is flagged, for the caller to test that sphere alone.
#pragma once

#include <cstdint>

#include "geometry/ray_sphere.h"
#include "geometry/shape.h"
#include "math/ray.h"

namespace luz {

/// One ray against four sphere lanes: for each lane k used, bit k of `hit` is set where
/// world_sphere_roots() returns true (roots t0[k] ≤ t1[k]); bit k of `slow` where it would
/// take its double path instead (then t0, t1 and the `hit` bit are not set).
struct SphereGroupRoots {
    float t0[4], t1[4];
    unsigned hit = 0, slow = 0;
};

/// Four spheres in world form by lane, wherever they are stored (the sphere lanes of a BVH
/// block, prim_block.h): centres, radius · radius and radius; `used` the lanes
/// to test (the others may hold anything).
struct SphereLanes {
    const float *cx, *cy, *cz, *rr, *radius;
    unsigned used;
};

/// sphere_lanes_roots() lane by lane with world_sphere_roots(), its double path included (no
/// lane is `slow`): the portable version, and the reference of the tests.
inline SphereGroupRoots sphere_lanes_roots_one_by_one(const SphereLanes& g, const Ray& r) {
    SphereGroupRoots out;
    for (unsigned lanes = g.used; lanes != 0; lanes &= lanes - 1) {
        const int k = __builtin_ctz(lanes);
        const Vec3 centre{g.cx[k], g.cy[k], g.cz[k]};
        if (world_sphere_roots(centre, g.radius[k], r, out.t0[k], out.t1[k])) out.hit |= 1u << k;
    }
    return out;
}

/// The roots of r with the spheres of lanes g.used, four at once with SSE2 (else one by one):
/// the steps of world_sphere_roots() with F = Float4, a = |d|² and 1/a shared by the lanes.
/// `ahead_only`: for a caller that takes roots at t > 0 only (the scene queries: t_min = 0), a
/// lane whose two roots are both ≤ 0 is not reported either: an origin outside the sphere
/// (c > 0) moving away from its centre (b > 0) gives q = −(b + √disc) < 0, so c/q and q/a are
/// both negative (or −0). Rays spawned on a sphere leave it so; when no other lane is near,
/// their test ends before the square root and division. (The portable version reports such
/// lanes all the same: the caller's t_min discards their roots alike.)
[[gnu::always_inline]] inline SphereGroupRoots sphere_lanes_roots(const SphereLanes& g,
                                                                  const Ray& r,
                                                                  bool ahead_only = false) {
    SphereGroupRoots out;
    const unsigned used = g.used;
    const Lane3<float> d1{r.direction.x, r.direction.y, r.direction.z};
    const float a = dot(d1, d1);
    if (!(a > 0)) {  // world_sphere_roots() goes to double for every sphere
        out.slow = used;
        return out;
    }
#if defined(__SSE2__)
    using F = Float4;
    const Lane3<F> d{F(d1.x), F(d1.y), F(d1.z)};
    const Lane3<F> o{F(r.origin.x) - F::load(g.cx), F(r.origin.y) - F::load(g.cy),
                     F(r.origin.z) - F::load(g.cz)};
    const F rr = F::load(g.rr);
    const ray_sphere::Terms<F> k = ray_sphere::terms(o, d, rr);
    // Every lane a sure miss (as world_sphere_roots() tells it): no division at all.
    unsigned near = used;
    if (a >= ray_sphere::kMinPreTestA) {
        near &= ~ray_sphere::surely_misses(F(a), k, rr).bits();
        if (near == 0) return out;
    }
    out.slow = ray_sphere::needs_double(k.c, k.oo, rr).bits() & used;
    unsigned solve = used & ~out.slow;
    if (ahead_only) {  // both roots ≤ 0: outside (c > 0) and moving away (b > 0)
        solve &= ~((F(0.0f) < k.c).bits() & (F(0.0f) < k.b).bits());
        if ((solve & near) == 0) return out;  // only the slow lanes, if any, to test
    }
    const float inv_a = 1.0f / a;
    const F disc = ray_sphere::discriminant(o, d, k.b, F(a), F(inv_a), rr);
    out.hit = ~(disc < F(0.0f)).bits() & solve;
    if (out.hit == 0) return out;  // no root to find: spare the square root and division
    F t0, t1;
    ray_sphere::roots(k.b, k.c, disc, F(inv_a), t0, t1);
    t0.store(out.t0);
    t1.store(out.t1);
#else
    (void)ahead_only;
    out = sphere_lanes_roots_one_by_one(g, r);
#endif
    return out;
}

}  // namespace luz
