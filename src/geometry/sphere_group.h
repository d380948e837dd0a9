// Spheres in world form side by side, four to a group, and their roots with one ray for all
// four at once (SSE2): how the scene queries test a small scene's spheres (scene_query.cpp).
// Every lane does the float operations of world_sphere_roots() (intersect.h) in the same
// order, so its roots are the same bits; a lane that needs that function's double path is
// flagged, for the caller to test that sphere alone.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "geometry/intersect.h"
#include "math/ray.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace luz {

/// Up to four spheres in world form (Shape::world_form): centres and squared radii by lane.
/// Unused lanes repeat the sphere added last and are never reported.
struct SphereGroup {
    static constexpr int kLanes = 4;
    float cx[kLanes], cy[kLanes], cz[kLanes];
    float rr[kLanes];  ///< radius · radius, as world_sphere_roots() rounds it
    float radius[kLanes];
    int count = 0;  ///< lanes in use
};

/// One ray against one group: for lane k < count, bit k of `hit` is set where
/// world_sphere_roots() returns true (roots t0[k] ≤ t1[k]); bit k of `slow` where it would
/// take its double path instead (then t0, t1 and the `hit` bit are not set).
struct SphereGroupRoots {
    float t0[SphereGroup::kLanes], t1[SphereGroup::kLanes];
    unsigned hit = 0, slow = 0;
};

/// Adds sphere shape s (in world form) to the last group of `groups`, or to a new one; returns
/// its lane number over all groups (4·group + lane).
inline int add_to_sphere_groups(std::vector<SphereGroup>& groups, const Shape& s) {
    if (groups.empty() || groups.back().count == SphereGroup::kLanes) groups.emplace_back();
    SphereGroup& g = groups.back();
    for (int k = g.count; k < SphereGroup::kLanes; ++k) {  // this lane and the unused ones
        g.cx[k] = s.centre.x;
        g.cy[k] = s.centre.y;
        g.cz[k] = s.centre.z;
        g.rr[k] = s.radius * s.radius;
        g.radius[k] = s.radius;
    }
    const int lane = g.count++;
    return static_cast<int>(groups.size() - 1) * SphereGroup::kLanes + lane;
}

/// sphere_group_roots() lane by lane with world_sphere_roots(), its double path included (no
/// lane is `slow`): the portable version, and the reference of the tests.
inline SphereGroupRoots sphere_group_roots_one_by_one(const SphereGroup& g, const Ray& r) {
    SphereGroupRoots out;
    for (int k = 0; k < g.count; ++k) {
        const Vec3 centre{g.cx[k], g.cy[k], g.cz[k]};
        if (world_sphere_roots(centre, g.radius[k], r, out.t0[k], out.t1[k])) out.hit |= 1u << k;
    }
    return out;
}

/// The roots of r with the group's spheres, four at once with SSE2 (else one by one).
inline SphereGroupRoots sphere_group_roots(const SphereGroup& g, const Ray& r) {
    SphereGroupRoots out;
    const unsigned used = (1u << g.count) - 1;
    const Vec3 d = r.direction;
    const float a = dot(d, d);
    if (!(a > 0)) {  // world_sphere_roots() goes to double for every sphere
        out.slow = used;
        return out;
    }
#if defined(__SSE2__)
    const float inv_a = 1.0f / a;
    const __m128 dx = _mm_set1_ps(d.x), dy = _mm_set1_ps(d.y), dz = _mm_set1_ps(d.z);
    const __m128 ox = _mm_sub_ps(_mm_set1_ps(r.origin.x), _mm_loadu_ps(g.cx));
    const __m128 oy = _mm_sub_ps(_mm_set1_ps(r.origin.y), _mm_loadu_ps(g.cy));
    const __m128 oz = _mm_sub_ps(_mm_set1_ps(r.origin.z), _mm_loadu_ps(g.cz));
    const __m128 rr = _mm_loadu_ps(g.rr);
    auto dot3 = [](__m128 x0, __m128 y0, __m128 z0, __m128 x1, __m128 y1, __m128 z1) {
        return _mm_add_ps(_mm_add_ps(_mm_mul_ps(x0, x1), _mm_mul_ps(y0, y1)), _mm_mul_ps(z0, z1));
    };
    const __m128 b = dot3(ox, oy, oz, dx, dy, dz);
    const __m128 oo = dot3(ox, oy, oz, ox, oy, oz);
    const __m128 c = _mm_sub_ps(oo, rr);
    const __m128 sign = _mm_set1_ps(-0.0f);
    // |c| < 2^-17 · max(|o|², ρ²): the double path (std::max(oo, rr) is _mm_max_ps(rr, oo))
    const __m128 slow =
        _mm_cmplt_ps(_mm_andnot_ps(sign, c), _mm_mul_ps(_mm_set1_ps(0x1p-17f), _mm_max_ps(rr, oo)));
    // l = o − d·(b/a), disc = a·(ρ² − |l|²)
    const __m128 s = _mm_mul_ps(b, _mm_set1_ps(inv_a));
    const __m128 lx = _mm_sub_ps(ox, _mm_mul_ps(dx, s));
    const __m128 ly = _mm_sub_ps(oy, _mm_mul_ps(dy, s));
    const __m128 lz = _mm_sub_ps(oz, _mm_mul_ps(dz, s));
    const __m128 disc = _mm_mul_ps(_mm_set1_ps(a), _mm_sub_ps(rr, dot3(lx, ly, lz, lx, ly, lz)));
    const __m128 hit = _mm_cmpnlt_ps(disc, _mm_setzero_ps());  // !(disc < 0)
    out.slow = static_cast<unsigned>(_mm_movemask_ps(slow)) & used;
    out.hit = static_cast<unsigned>(_mm_movemask_ps(hit)) & used & ~out.slow;
    if (out.hit == 0) return out;  // no root to find: spare the square root and division
    // q = −(b + copysign(√disc, b)); roots c/q and q/a, the smaller first
    const __m128 root = _mm_sqrt_ps(disc);
    const __m128 signed_root = _mm_or_ps(_mm_andnot_ps(sign, root), _mm_and_ps(sign, b));
    const __m128 q = _mm_xor_ps(sign, _mm_add_ps(b, signed_root));
    const __m128 f0 = _mm_div_ps(c, q), f1 = _mm_mul_ps(q, _mm_set1_ps(inv_a));
    _mm_storeu_ps(out.t0, _mm_min_ps(f1, f0));  // std::min(f0, f1): f1 < f0 ? f1 : f0
    _mm_storeu_ps(out.t1, _mm_max_ps(f1, f0));  // std::max(f0, f1): f0 < f1 ? f1 : f0
#else
    out = sphere_group_roots_one_by_one(g, r);
#endif
    return out;
}

}  // namespace luz
