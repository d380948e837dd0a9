// Spheres in world form side by side, four lanes of them, and their roots with one ray for all
// four at once (Lane4f lanes): how the scene queries test the sphere lanes of the BVH's leaves
// (query_parts.h, query_leaf_packet.cpp). Every lane runs the steps of world_sphere_roots()
// (ray_sphere.h) on Lane4f lanes, the same template code, so its roots are the same bits; a lane
// that needs that function's double path is flagged, for the caller to test that sphere alone.
#pragma once

#include <cstdint>

#include "geometry/ray_sphere.h"
#include "geometry/shape.h"
#include "math/lanes.h"
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
/// lane is `slow`): the reference of the tests.
inline SphereGroupRoots sphere_lanes_roots_one_by_one(const SphereLanes& g, const Ray& r) {
    SphereGroupRoots out;
    for (unsigned lanes = g.used; lanes != 0; lanes &= lanes - 1) {
        const int k = __builtin_ctz(lanes);
        const Vec3 centre{g.cx[k], g.cy[k], g.cz[k]};
        if (world_sphere_roots(centre, g.radius[k], r, out.t0[k], out.t1[k])) out.hit |= 1u << k;
    }
    return out;
}

/// The roots of r with the spheres of lanes g.used, four at once on Lane4f lanes:
/// the steps of world_sphere_roots() with F = Lane4f, a = |d|² and 1/a shared by the lanes.
/// `ahead_only`: for a caller that takes roots at t > 0 only (the scene queries: t_min = 0), a
/// lane whose two roots are both ≤ 0 is not reported either: an origin outside the sphere
/// (c > 0) moving away from its centre (b > 0) gives q = −(b + √disc) < 0, so c/q and q/a are
/// both negative (or −0). Rays spawned on a sphere leave it so; when no other lane is near,
/// their test ends before the square root and division. (The one-by-one version reports such
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
    using F = Lane4f;
    const Lane3<F> d{lanes4(d1.x), lanes4(d1.y), lanes4(d1.z)};
    const Lane3<F> o{lanes4(r.origin.x) - load_lanes4(g.cx), lanes4(r.origin.y) - load_lanes4(g.cy),
                     lanes4(r.origin.z) - load_lanes4(g.cz)};
    const F rr = load_lanes4(g.rr);
    const ray_sphere::Terms<F> k = ray_sphere::terms(o, d, rr);
    // Every lane a sure miss (as world_sphere_roots() tells it): no division at all.
    unsigned near = used;
    if (a >= ray_sphere::kMinPreTestA) {
        near &= ~lane_bits(ray_sphere::surely_misses(lanes4(a), k, rr));
        if (near == 0) return out;
    }
    out.slow = lane_bits(ray_sphere::needs_double(k.c, k.oo, rr)) & used;
    unsigned solve = used & ~out.slow;
    if (ahead_only) {  // both roots ≤ 0: outside (c > 0) and moving away (b > 0)
        solve &= ~(lane_bits(lanes4(0.0f) < k.c) & lane_bits(lanes4(0.0f) < k.b));
        if ((solve & near) == 0) return out;  // only the slow lanes, if any, to test
    }
    const float inv_a = 1.0f / a;
    const F disc = ray_sphere::discriminant(o, d, k.b, lanes4(a), lanes4(inv_a), rr);
    out.hit = ~lane_bits(disc < lanes4(0.0f)) & solve;
    if (out.hit == 0) return out;  // no root to find: spare the square root and division
    F t0, t1;
    ray_sphere::roots(k.b, k.c, disc, lanes4(inv_a), t0, t1);
    store_lanes4(out.t0, t0);
    store_lanes4(out.t1, t1);
    return out;
}

}  // namespace luz
