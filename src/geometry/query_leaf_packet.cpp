// A BVH leaf against several rays at once: its world-form sphere lanes met by four rays at a
// time (nearest_hits_leaf) or four shadow segments at a time (transmittances_leaf), with
// world_sphere_roots()'s steps lane for lane (ray_sphere.h): the same roots, bit for bit, as the
// one-ray tests of query_parts.h; every other lane one ray at a time by those tests.
#include <algorithm>

#include "geometry/query_parts.h"

namespace luz::query {

namespace {

/// The tests a SIMD sphere test counts itself among its `lanes` tests: all but the lanes handed
/// to the scalar test (`slow`, rare), which counts its own.
uint64_t tests_besides(int lanes, unsigned slow) {
    return static_cast<uint64_t>(lanes) - (slow != 0 ? lane_count(slow) : 0);
}

/// world_root() of the plane in world form for the four rays of lanes (o, d), lane for lane
/// the same steps (n·o in double): the same roots.
[[gnu::always_inline]] inline Lane4f plane_roots4(const Shape& plane, const Lane3<Lane4f>& o,
                                                  const Lane3<Lane4f>& d) {
    using F = Lane4f;
    const Lane2d nx = lanes2d(plane.normal.x), ny = lanes2d(plane.normal.y),
                 nz = lanes2d(plane.normal.z), offset = lanes2d(plane.offset);
    const auto n_o = [&](Lane2d x, Lane2d y, Lane2d z) { return nx * x + ny * y + nz * z; };
    const F num = lanes_float(
        offset - n_o(lanes_low_double(o.x), lanes_low_double(o.y), lanes_low_double(o.z)),
        offset - n_o(lanes_high_double(o.x), lanes_high_double(o.y), lanes_high_double(o.z)));
    const F n_d =
        lanes4(plane.normal.x) * d.x + lanes4(plane.normal.y) * d.y + lanes4(plane.normal.z) * d.z;
    return num / n_d;
}

/// offer_unbounded() for the rays r[l] of lanes `mine` of (o, d), each by best[l]: the planes in
/// world form four rays at a time.
[[gnu::always_inline]] inline void offer_unbounded4(const BuiltScene& scene, const Ray* r,
                                                    unsigned mine, const Lane3<Lane4f>& o,
                                                    const Lane3<Lane4f>& d, float t_min, Best* best,
                                                    IntersectCounters& counters) {
    for (const uint32_t i : scene.unbounded) {
        const Shape& s = scene.shapes[i];
        if (!(s.world_form && s.type == ShapeType::plane)) {
            for (unsigned lanes = mine; lanes != 0; lanes &= lanes - 1) {
                const int l = __builtin_ctz(lanes);
                offer_shape(scene, i, r[l], t_min, best[l], counters);
            }
            continue;
        }
        counters.primitive += lane_count(mine);
        alignas(16) float t[4];
        store_lanes4(t, plane_roots4(s, o, d));
        for (unsigned lanes = mine; lanes != 0; lanes &= lanes - 1) {
            const int l = __builtin_ctz(lanes);
            if (t[l] > t_min && t[l] < best[l].limit() && best[l].better(t[l], i, 0))
                best[l].take(t[l], i, 0, 0.0f, 0.0f, part_side);
        }
    }
}

}  // namespace

void nearest_hits_leaf(const BuiltScene& scene, uint32_t first, uint32_t count, const Ray* rays,
                       const WatertightRay* w, unsigned active, float t_min, Best* best,
                       IntersectCounters& counters, bool unbounded_too) {
    // Each of rays `lanes` against the lanes `prims` of b one ray at a time.
    const auto one_ray_at_a_time = [&](const PrimBlock& b, unsigned prims, unsigned lanes) {
        for (; lanes != 0; lanes &= lanes - 1) {
            const int k = __builtin_ctz(lanes);
            offer_block(scene, b, prims, rays[k], w[k], t_min, best[k], counters);
        }
    };
    using F = Lane4f;
    constexpr int kLanes = 4;
    for (int quad = 0; quad < kMaxPacket; quad += kLanes) {
        const unsigned mine = (active >> quad) & 0xFu;
        if (mine == 0) continue;
        const Ray* r = rays + quad;
        // Lane l holds ray quad + l if it is in `mine`, else the first of `mine` (never
        // reported), set from registers (no store forwarding to wait for).
        const int any = __builtin_ctz(mine);
        const Ray& r0 = r[(mine & 1u) ? 0 : any];
        const Ray& r1 = r[(mine & 2u) ? 1 : any];
        const Ray& r2 = r[(mine & 4u) ? 2 : any];
        const Ray& r3 = r[(mine & 8u) ? 3 : any];
        const auto lanes_of = [&](const Vec3 Ray::*v, int c) {
            return F{(r0.*v)[c], (r1.*v)[c], (r2.*v)[c], (r3.*v)[c]};
        };
        const Lane3<F> org{lanes_of(&Ray::origin, 0), lanes_of(&Ray::origin, 1),
                           lanes_of(&Ray::origin, 2)};
        const Lane3<F> dir{lanes_of(&Ray::direction, 0), lanes_of(&Ray::direction, 1),
                           lanes_of(&Ray::direction, 2)};
        const F a = dot(dir, dir);  // |d|², as world_sphere_roots() rounds it
        // A ray with |d|² below the pre-test's range, 0 or NaN takes world_sphere_roots()'s
        // other paths: such rays go one by one.
        const unsigned usual = lane_bits(lane_ge(a, lanes4(ray_sphere::kMinPreTestA))) & mine;
        const F inv_a = lanes4(1.0f) / a;
        if (unbounded_too) offer_unbounded4(scene, r, mine, org, dir, t_min, best + quad, counters);
        for_each_block(scene, first, count, [&](const PrimBlock& b, unsigned prims) {
            const unsigned spheres = b.sphere_lanes() & prims;
            one_ray_at_a_time(b, prims, (mine & ~usual) << quad);
            if (prims & ~spheres) one_ray_at_a_time(b, prims & ~spheres, usual << quad);
            if (usual == 0) return true;
            for (unsigned left = spheres; left != 0; left &= left - 1) {
                // world_sphere_roots()'s steps with a ray in each lane: the same roots.
                const int s = __builtin_ctz(left);
                const F rr = lanes4(b.v[1][0][s]);
                const Lane3<F> os{org.x - lanes4(b.v[0][0][s]), org.y - lanes4(b.v[0][1][s]),
                                  org.z - lanes4(b.v[0][2][s])};
                const ray_sphere::Terms<F> k = ray_sphere::terms(os, dir, rr);
                const unsigned near = ~lane_bits(ray_sphere::surely_misses(a, k, rr)) & usual;
                unsigned slow = 0;
                if (near != 0) {
                    slow = lane_bits(ray_sphere::needs_double(k.c, k.oo, rr)) & near;
                    // As sphere_lanes_roots() ahead only: outside (c > 0) and moving away
                    // (b > 0), both roots are ≤ 0, never beyond t_min ≥ 0.
                    unsigned solve = near & ~slow;
                    if (t_min >= 0)
                        solve &= ~(lane_bits(lanes4(0.0f) < k.c) & lane_bits(lanes4(0.0f) < k.b));
                    const F disc = solve != 0 ? ray_sphere::discriminant(os, dir, k.b, a, inv_a, rr)
                                              : lanes4(-1.0f);
                    const unsigned hit = ~lane_bits(disc < lanes4(0.0f)) & solve;
                    if (hit != 0) {
                        F t0, t1;
                        ray_sphere::roots(k.b, k.c, disc, inv_a, t0, t1);
                        alignas(16) float t0s[kLanes], t1s[kLanes];
                        store_lanes4(t0s, t0);
                        store_lanes4(t1s, t1);
                        for (unsigned lanes = hit; lanes != 0; lanes &= lanes - 1) {
                            const int l = __builtin_ctz(lanes);
                            Best& to = best[quad + l];
                            float t;  // the root intersect() would choose
                            if (nearest_root(t0s[l], t1s[l], t_min, to.limit(), t) &&
                                to.better(t, b.shape[s], 0))
                                to.take(t, b.shape[s], 0, 0.0f, 0.0f, part_side);
                        }
                    }
                }
                // one test per ray, a slow one counted by offer_shape()
                counters.primitive += tests_besides(lane_count(usual), slow);
                for (unsigned lanes = slow; lanes != 0; lanes &= lanes - 1) {
                    const int l = __builtin_ctz(lanes);
                    offer_shape(scene, b.shape[s], r[l], t_min, best[quad + l], counters);
                }
            }
            return true;
        });
    }
}

void transmittances_leaf(const BuiltScene& scene, const Materials& materials, uint32_t first,
                         uint32_t count, const SegmentLanes& s, unsigned active, float* T,
                         IntersectCounters& counters) {
    // One by one: a segment outside the packet test's range.
    const auto one_by_one = [&](unsigned lanes) {
        for (; lanes != 0; lanes &= lanes - 1) {
            const int k = __builtin_ctz(lanes);
            T[k] = transmittance_bvh(scene, materials, s.ray(k), 0.0f, s.t_max[k], counters);
        }
    };
    using F = Lane4f;
    constexpr int kLanes = 4;
    for (int quad = 0; quad < kMaxPacket; quad += kLanes) {
        const unsigned mine = (active >> quad) & 0xFu;
        if (mine == 0) continue;
        // Lane l holds segment quad + l; the lanes not in `mine` hold whatever the caller put
        // there and are never reported.
        const Lane3<F> dir{load_lanes4(s.dx + quad), load_lanes4(s.dy + quad),
                           load_lanes4(s.dz + quad)};
        const F a = dot(dir, dir);  // |d|², as world_sphere_roots() rounds it
        // |d|² below the pre-test's range, 0 or NaN: world_sphere_roots()'s other paths.
        const unsigned usual = lane_bits(lane_ge(a, lanes4(ray_sphere::kMinPreTestA)));
        one_by_one((mine & ~usual) << quad);
        unsigned open = mine & usual;  // not blocked yet
        if (open == 0) continue;
        const F inv_a = lanes4(1.0f) / a;
        const Lane3<F> o{load_lanes4(s.ox + quad), load_lanes4(s.oy + quad),
                         load_lanes4(s.oz + quad)};
        alignas(16) float t_max[kLanes];
        std::copy(s.t_max + quad, s.t_max + quad + kLanes, t_max);
        Crossings crossings[kLanes];
        const auto block = [&](unsigned l) {
            T[quad + l] = 0.0f;
            open &= ~(1u << l);
        };
        // As transmittance_bvh(): first the unbounded shapes, planes in world form four
        // segments at a time (world_root()'s steps lane by lane, n·o in double), the others one
        // segment at a time; then the leaf's blocks.
        for (const uint32_t i : scene.unbounded) {
            if (open == 0) break;
            const Shape& plane = scene.shapes[i];
            if (!(plane.world_form && plane.type == ShapeType::plane)) {
                for (unsigned lanes = open; lanes != 0; lanes &= lanes - 1) {
                    const int l = __builtin_ctz(lanes);
                    if (!cross_shape(scene, materials, i, s.ray(quad + l), 0.0f, t_max[l],
                                     crossings[l], counters))
                        block(l);
                }
                continue;
            }
            counters.primitive += lane_count(open);
            const F t = plane_roots4(plane, o, dir);
            const unsigned within =
                lane_bits(lanes4(0.0f) < t) & lane_bits(t < load_lanes4(t_max)) & open;
            for (unsigned lanes = within; lanes != 0; lanes &= lanes - 1) {
                const int l = __builtin_ctz(lanes);
                if (!add_crossings(materials, plane.material, 1, crossings[l])) block(l);
            }
        }
        const PrimBlock* blocks = &scene.bvh_blocks[first / PrimBlock::kLanes];
        for (uint32_t left = count; left > 0 && open != 0; ++blocks) {  // as for_each_block()
            const PrimBlock& b = *blocks;
            const int used = static_cast<int>(std::min<uint32_t>(left, PrimBlock::kLanes));
            const unsigned prims = (1u << used) - 1;  // lanes 0 … used − 1
            left -= static_cast<uint32_t>(used);
            const unsigned spheres = b.sphere_lanes() & prims;
            if (spheres != prims) {  // a block of other shapes too: one segment at a time
                for (unsigned lanes = open; lanes != 0; lanes &= lanes - 1) {
                    const int l = __builtin_ctz(lanes);
                    const Ray r = s.ray(quad + l);
                    const WatertightRay w =
                        scene.mesh_triangles ? prepare_watertight(r) : WatertightRay{};
                    if (!cross_block(scene, materials, b, prims, r, w, 0.0f, t_max[l], crossings[l],
                                     counters))
                        block(l);
                }
                continue;
            }
            // The one-ray test of the block's spheres turned round: the four segments against
            // one sphere at a time, the same steps lane for lane (the same roots). By sphere:
            // the segments near it, those needing the double path, those with roots.
            const int n = used;  // the block holds spheres only
            unsigned near[kLanes], slow[kLanes], hit[kLanes];
            alignas(16) float t0s[kLanes][kLanes], t1s[kLanes][kLanes];
            unsigned near_any = 0;
            for (int k = 0; k < n; ++k) {
                const F rr = lanes4(b.v[1][0][k]);
                const Lane3<F> os{o.x - lanes4(b.v[0][0][k]), o.y - lanes4(b.v[0][1][k]),
                                  o.z - lanes4(b.v[0][2][k])};
                const ray_sphere::Terms<F> q = ray_sphere::terms(os, dir, rr);
                near[k] = ~lane_bits(ray_sphere::surely_misses(a, q, rr)) & open;
                slow[k] = lane_bits(ray_sphere::needs_double(q.c, q.oo, rr)) & open;
                hit[k] = 0;
                near_any |= near[k];
                const unsigned solve = near[k] & ~slow[k];
                if (solve == 0) continue;
                const F disc = ray_sphere::discriminant(os, dir, q.b, a, inv_a, rr);
                hit[k] = ~lane_bits(disc < lanes4(0.0f)) & solve;
                if (hit[k] == 0) continue;
                F t0, t1;
                ray_sphere::roots(q.b, q.c, disc, inv_a, t0, t1);
                store_lanes4(t0s[k], t0);
                store_lanes4(t1s[k], t1);
            }
            // The segments with a root within (0, t_max) or a sphere to test in double take the
            // one-ray steps segment by segment, with its counts; the others count one test per
            // sphere (as it does: a slow sphere is counted only where some sphere is near).
            const F lo = lanes4(0.0f), hi = load_lanes4(t_max);
            unsigned one_by_one_lanes = 0, any_slow = 0;
            for (int k = 0; k < n; ++k) {
                any_slow |= slow[k];
                if (hit[k] == 0) continue;
                const F t0 = load_lanes4(t0s[k]), t1 = load_lanes4(t1s[k]);
                const unsigned within = (lane_bits(lo < t0) & lane_bits(t0 < hi)) |
                                        (lane_bits(lo < t1) & lane_bits(t1 < hi));
                one_by_one_lanes |= within & hit[k];
            }
            one_by_one_lanes |= any_slow & near_any;
            counters.primitive += static_cast<uint64_t>(n) * lane_count(open & ~one_by_one_lanes);
            for (unsigned lanes = one_by_one_lanes; lanes != 0; lanes &= lanes - 1) {
                const int l = __builtin_ctz(lanes);
                const unsigned bit = 1u << l;
                unsigned slow_spheres = 0;
                if (near_any & bit)
                    for (int k = 0; k < n; ++k) slow_spheres |= ((slow[k] & bit) != 0) << k;
                counters.primitive += tests_besides(n, slow_spheres);
                bool blocked = false;
                for (int k = 0; k < n && !blocked; ++k) {
                    if (!(hit[k] & bit)) continue;
                    const uint32_t m = roots_within(t0s[k][l], t1s[k][l], 0.0f, t_max[l]);
                    blocked = m > 0 && !add_crossings(materials, scene.shapes[b.shape[k]].material,
                                                      m, crossings[l]);
                }
                for (unsigned k = slow_spheres; k != 0 && !blocked; k &= k - 1) {
                    blocked = !cross_shape(scene, materials, b.shape[__builtin_ctz(k)],
                                           s.ray(quad + l), 0.0f, t_max[l], crossings[l], counters);
                }
                if (blocked) block(l);
            }
        }
        for (unsigned lanes = open; lanes != 0; lanes &= lanes - 1) {
            const int l = __builtin_ctz(lanes);
            T[quad + l] = crossings[l].lost() ? transmittance_all(scene, materials, s.ray(quad + l),
                                                                  0.0f, t_max[l], counters)
                                              : crossings[l].product();
        }
    }
}

}  // namespace luz::query
