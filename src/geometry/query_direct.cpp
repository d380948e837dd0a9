// BuiltScene queries for a small scene without meshes (BuiltScene::direct: at most 8 shapes, which
// one 8-wide BVH node would hold): its world-form spheres four at a time (sphere_group.h), then
// its world-form planes, then the other shapes behind their boxes. A packet of camera rays
// (nearest_hits_direct) takes the spheres the other way round: four rays at a time against one
// sphere, the same steps lane for lane. The nearest hit is ordered by (t, shape) as everywhere
// (query_parts.h: Best), so the order of the tests changes no answer; nor does it change a
// transmittance (crossings multiply in material order, and an opaque one is 0 wherever it is met).
#include <algorithm>

#include "geometry/query_parts.h"
#include "geometry/sphere_group.h"

namespace luz::query {

namespace {

/// Box tests of one ray, its inverse direction computed at the first.
struct LazyBoxTest {
    const Ray& r;
    Vec3 inv_dir{0.0f};
    bool ready = false;
    bool hit(const Bounds3& b, float t_min, float t_max, IntersectCounters& counters) {
        if (!ready) inv_dir = inverse_direction(r.direction);
        ready = true;
        ++counters.bounds;
        return hit_bounds(b, r, inv_dir, t_min, t_max);
    }
};

/// The tests a SIMD sphere test counts itself among its `lanes` tests: all but the lanes handed
/// to the scalar test (`slow`, rare), which counts its own.
uint64_t tests_besides(int lanes, unsigned slow) {
    return static_cast<uint64_t>(lanes) - (slow != 0 ? lane_count(slow) : 0);
}

/// What follows the spheres in a nearest-hit query: the world-form planes, then the other shapes
/// behind their boxes, offered to `best`. Inlined: every camera and secondary ray passes here.
[[gnu::always_inline]] inline void offer_planes_and_others(const BuiltScene& scene, const Ray& r,
                                                           float t_min, Best& best,
                                                           IntersectCounters& counters) {
    for (const uint32_t i : scene.direct_planes) {
        ++counters.primitive;
        const float t = shapes::plane::world_root(scene.shapes[i], r);  // as intersect() finds it
        if (t > t_min && t < best.limit() && best.better(t, i, 0))
            best.take(t, i, 0, 0.0f, 0.0f, part_side);
    }
    LazyBoxTest boxes{r};
    for (const uint32_t i : scene.direct_others) {
        const Shape& s = scene.shapes[i];
        if (is_bounded(s) &&
            !boxes.hit(scene.bounds[i], t_min, bvh_detail::with_margin(best.limit()), counters))
            continue;
        offer_shape(scene, i, r, t_min, best, counters);
    }
}

}  // namespace

void prepare_direct(BuiltScene& scene) {
    scene.direct = scene.mesh_triangles == 0 && scene.shapes.size() <= BuiltScene::kDirectShapes;
    scene.sphere_groups.clear();
    scene.direct_planes.clear();
    scene.direct_others.clear();
    for (size_t i = 0; i < scene.shapes.size() && scene.direct; ++i) {
        const Shape& s = scene.shapes[i];
        const uint32_t index = static_cast<uint32_t>(i);
        if (s.world_form && s.type == ShapeType::sphere) {
            const int lane = add_to_sphere_groups(scene.sphere_groups, s);
            scene.sphere_groups.back().shape[lane % SphereGroup::kLanes] = index;
        } else if (s.world_form && s.type == ShapeType::plane) {
            scene.direct_planes.push_back(index);
        } else {
            scene.direct_others.push_back(index);
        }
    }
}

bool nearest_hit_direct(const BuiltScene& scene, const Ray& r, float t_min, float t_max, Hit& hit,
                        IntersectCounters& counters) {
    Best best(t_max);
    for (const SphereGroup& g : scene.sphere_groups) {
        const SphereGroupRoots q = sphere_group_roots(g, r, t_min >= 0);
        counters.primitive += tests_besides(g.count, q.slow);
        for (unsigned lanes = q.hit; lanes != 0; lanes &= lanes - 1) {
            const int k = __builtin_ctz(lanes);
            float t;  // the root intersect() would choose
            if (nearest_root(q.t0[k], q.t1[k], t_min, best.limit(), t) &&
                best.better(t, g.shape[k], 0))
                best.take(t, g.shape[k], 0, 0.0f, 0.0f, part_side);
        }
        for (unsigned lanes = q.slow; lanes != 0; lanes &= lanes - 1)
            offer_shape(scene, g.shape[__builtin_ctz(lanes)], r, t_min, best, counters);
    }
    offer_planes_and_others(scene, r, t_min, best, counters);
    if (!best.found) return false;
    hit = best.hit;
    return true;
}

void nearest_hits_direct(const BuiltScene& scene, const Ray* rays, int n, float t_min, float t_max,
                         Hit* hits, bool* found, IntersectCounters& counters) {
    using F = Lane4f;
    constexpr int kLanes = 4;
    for (int first = 0; first < n; first += kLanes) {
        const Ray* r = rays + first;
        const int m = std::min(kLanes, n - first);
        const unsigned used = (1u << m) - 1;
        // Lane l holds ray l (lanes beyond m repeat ray 0 and are never reported), set from
        // registers: lanes stored one float at a time and loaded as a vector would wait for
        // the stores (no store forwarding).
        const Ray& r0 = r[0];
        const Ray& r1 = r[m > 1 ? 1 : 0];
        const Ray& r2 = r[m > 2 ? 2 : 0];
        const Ray& r3 = r[m > 3 ? 3 : 0];
        const auto lanes_of = [&](const Vec3 Ray::*v, int c) {
            return F{(r0.*v)[c], (r1.*v)[c], (r2.*v)[c], (r3.*v)[c]};
        };
        const Lane3<F> org{lanes_of(&Ray::origin, 0), lanes_of(&Ray::origin, 1),
                           lanes_of(&Ray::origin, 2)};
        const Lane3<F> dir{lanes_of(&Ray::direction, 0), lanes_of(&Ray::direction, 1),
                           lanes_of(&Ray::direction, 2)};
        const F a = dot(dir, dir);  // |d|², as world_sphere_roots() rounds it
        // A ray with |d|² below the pre-test's range, 0 or NaN takes world_sphere_roots()'s
        // other paths: such a packet goes ray by ray.
        const unsigned usual = lane_bits(lane_ge(a, lanes4(ray_sphere::kMinPreTestA)));
        if ((usual & used) != used) {
            for (int l = 0; l < m; ++l)
                found[first + l] =
                    nearest_hit_direct(scene, r[l], t_min, t_max, hits[first + l], counters);
            continue;
        }
        const F inv_a = 1.0f / a;
        Best best[kLanes] = {Best(t_max), Best(t_max), Best(t_max), Best(t_max)};
        for (const SphereGroup& g : scene.sphere_groups) {
            for (int s = 0; s < g.count; ++s) {
                // world_sphere_roots()'s steps, a ray in each lane (sphere_group_roots(): a
                // sphere in each lane): the same roots, bit for bit.
                const F rr = lanes4(g.rr[s]);
                const Lane3<F> os{org.x - g.cx[s], org.y - g.cy[s], org.z - g.cz[s]};
                const ray_sphere::Terms<F> k = ray_sphere::terms(os, dir, rr);
                const unsigned near = ~lane_bits(ray_sphere::surely_misses(a, k, rr)) & used;
                unsigned slow = 0;
                if (near != 0) {
                    slow = lane_bits(ray_sphere::needs_double(k.c, k.oo, rr)) & near;
                    const F disc = ray_sphere::discriminant(os, dir, k.b, a, inv_a, rr);
                    const unsigned hit = ~lane_bits(disc < 0.0f) & near & ~slow;
                    if (hit != 0) {
                        F t0, t1;
                        ray_sphere::roots(k.b, k.c, disc, inv_a, t0, t1);
                        alignas(16) float t0s[kLanes], t1s[kLanes];
                        store_lanes4(t0s, t0);
                        store_lanes4(t1s, t1);
                        for (unsigned lanes = hit; lanes != 0; lanes &= lanes - 1) {
                            const int l = __builtin_ctz(lanes);
                            float t;  // the root intersect() would choose
                            if (nearest_root(t0s[l], t1s[l], t_min, best[l].limit(), t) &&
                                best[l].better(t, g.shape[s], 0))
                                best[l].take(t, g.shape[s], 0, 0.0f, 0.0f, part_side);
                        }
                    }
                }
                // one test per ray, a slow one counted by offer_shape()
                counters.primitive += tests_besides(m, slow);
                for (unsigned lanes = slow; lanes != 0; lanes &= lanes - 1) {
                    const int l = __builtin_ctz(lanes);
                    offer_shape(scene, g.shape[s], r[l], t_min, best[l], counters);
                }
            }
        }
        for (int l = 0; l < m; ++l) {
            offer_planes_and_others(scene, r[l], t_min, best[l], counters);
            found[first + l] = best[l].found;
            if (best[l].found) hits[first + l] = best[l].hit;
        }
    }
}

float transmittance_direct(const BuiltScene& scene, const Materials& materials, const Ray& r,
                           float t_min, float t_max, IntersectCounters& counters) {
    Crossings crossings;
    for (const SphereGroup& g : scene.sphere_groups) {
        const SphereGroupRoots q = sphere_group_roots(g, r, t_min >= 0);
        counters.primitive += tests_besides(g.count, q.slow);
        for (unsigned lanes = q.hit; lanes != 0; lanes &= lanes - 1) {
            const int k = __builtin_ctz(lanes);
            const uint32_t n = roots_within(q.t0[k], q.t1[k], t_min, t_max);
            if (n > 0 && !add_crossings(materials, scene.shapes[g.shape[k]].material, n, crossings))
                return 0.0f;
        }
        for (unsigned lanes = q.slow; lanes != 0; lanes &= lanes - 1) {
            if (!cross_shape(scene, materials, g.shape[__builtin_ctz(lanes)], r, t_min, t_max,
                             crossings, counters))
                return 0.0f;
        }
    }
    for (const uint32_t i : scene.direct_planes) {
        ++counters.primitive;
        const float t = shapes::plane::world_root(scene.shapes[i], r);  // one root, or none (NaN)
        if (t > t_min && t < t_max &&
            !add_crossings(materials, scene.shapes[i].material, 1, crossings))
            return 0.0f;
    }
    LazyBoxTest boxes{r};
    for (const uint32_t i : scene.direct_others) {
        const Shape& s = scene.shapes[i];
        if (is_bounded(s) && !boxes.hit(scene.bounds[i], t_min, t_max, counters)) continue;
        if (!cross_shape(scene, materials, i, r, t_min, t_max, crossings, counters)) return 0.0f;
    }
    return crossings.product();
}

void transmittances_direct(const BuiltScene& scene, const Materials& materials,
                           const SegmentLanes& s, unsigned active, float* T,
                           IntersectCounters& counters) {
    // One by one: with shapes other than world-form spheres and planes.
    const auto one_by_one = [&](unsigned lanes) {
        for (; lanes != 0; lanes &= lanes - 1) {
            const int k = __builtin_ctz(lanes);
            T[k] = transmittance_direct(scene, materials, s.ray(k), 0.0f, s.t_max[k], counters);
        }
    };
    if (!scene.direct_others.empty()) return one_by_one(active);
    using F = Lane4f;
    constexpr int kLanes = 4;
    for (int first = 0; first < kMaxPacket; first += kLanes) {
        const unsigned mine = (active >> first) & 0xFu;
        if (mine == 0) continue;
        // Lane l holds segment first + l; the lanes not in `mine` hold whatever the caller put
        // there and are never reported.
        const Lane3<F> dir{load_lanes4(s.dx + first), load_lanes4(s.dy + first),
                           load_lanes4(s.dz + first)};
        const F a = dot(dir, dir);  // |d|², as world_sphere_roots() rounds it
        // |d|² below the pre-test's range, 0 or NaN: world_sphere_roots()'s other paths.
        const unsigned usual = lane_bits(lane_ge(a, lanes4(ray_sphere::kMinPreTestA)));
        one_by_one((mine & ~usual) << first);
        unsigned open = mine & usual;  // not blocked yet
        if (open == 0) continue;
        const F inv_a = 1.0f / a;
        const Lane3<F> o{load_lanes4(s.ox + first), load_lanes4(s.oy + first),
                         load_lanes4(s.oz + first)};
        alignas(16) float t_max[kLanes];
        std::copy(s.t_max + first, s.t_max + first + kLanes, t_max);
        Crossings crossings[kLanes];
        for (const SphereGroup& g : scene.sphere_groups) {
            // transmittance_direct()'s sphere_group_roots() turned round: the four segments
            // against one sphere at a time, the same steps lane for lane (the same roots). By
            // sphere: the segments near it, those needing the double path, those with roots.
            unsigned near[SphereGroup::kLanes], slow[SphereGroup::kLanes], hit[SphereGroup::kLanes];
            alignas(16) float t0s[SphereGroup::kLanes][kLanes], t1s[SphereGroup::kLanes][kLanes];
            unsigned near_any = 0;
            for (int k = 0; k < g.count; ++k) {
                const F rr = lanes4(g.rr[k]);
                const Lane3<F> os{o.x - g.cx[k], o.y - g.cy[k], o.z - g.cz[k]};
                const ray_sphere::Terms<F> q = ray_sphere::terms(os, dir, rr);
                near[k] = ~lane_bits(ray_sphere::surely_misses(a, q, rr)) & open;
                slow[k] = lane_bits(ray_sphere::needs_double(q.c, q.oo, rr)) & open;
                hit[k] = 0;
                near_any |= near[k];
                const unsigned solve = near[k] & ~slow[k];
                if (solve == 0) continue;
                const F disc = ray_sphere::discriminant(os, dir, q.b, a, inv_a, rr);
                hit[k] = ~lane_bits(disc < 0.0f) & solve;
                if (hit[k] == 0) continue;
                F t0, t1;
                ray_sphere::roots(q.b, q.c, disc, inv_a, t0, t1);
                store_lanes4(t0s[k], t0);
                store_lanes4(t1s[k], t1);
            }
            // The segments with a root within (0, t_max) or a sphere to test in double take
            // transmittance_direct()'s steps segment by segment, in its order and with its
            // counts; the others count g.count tests (as it does: a slow sphere is counted
            // only where some sphere of the group is near).
            const F lo = lanes4(0.0f), hi = load_lanes4(t_max);
            unsigned one_by_one_lanes = 0;
            for (int k = 0; k < g.count; ++k) {
                if (hit[k] == 0) continue;
                const F t0 = load_lanes4(t0s[k]), t1 = load_lanes4(t1s[k]);
                const unsigned within = (lane_bits(lo < t0) & lane_bits(t0 < hi)) |
                                        (lane_bits(lo < t1) & lane_bits(t1 < hi));
                one_by_one_lanes |= within & hit[k];
            }
            unsigned any_slow = 0;
            for (int k = 0; k < g.count; ++k) any_slow |= slow[k];
            one_by_one_lanes |= any_slow & near_any;
            counters.primitive +=
                static_cast<uint64_t>(g.count) * lane_count(open & ~one_by_one_lanes);
            for (unsigned lanes = one_by_one_lanes; lanes != 0; lanes &= lanes - 1) {
                const int l = __builtin_ctz(lanes);
                const unsigned bit = 1u << l;
                unsigned slow_spheres = 0;
                if (near_any & bit)
                    for (int k = 0; k < g.count; ++k) slow_spheres |= ((slow[k] & bit) != 0) << k;
                counters.primitive += tests_besides(g.count, slow_spheres);
                bool blocked = false;
                for (int k = 0; k < g.count && !blocked; ++k) {
                    if (!(hit[k] & bit)) continue;
                    const uint32_t n = roots_within(t0s[k][l], t1s[k][l], 0.0f, t_max[l]);
                    blocked = n > 0 && !add_crossings(materials, scene.shapes[g.shape[k]].material,
                                                      n, crossings[l]);
                }
                for (unsigned k = slow_spheres; k != 0 && !blocked; k &= k - 1) {
                    blocked =
                        !cross_shape(scene, materials, g.shape[__builtin_ctz(k)], s.ray(first + l),
                                     0.0f, t_max[l], crossings[l], counters);
                }
                if (blocked) {
                    T[first + l] = 0.0f;
                    open &= ~bit;
                }
            }
        }
        // The planes, four segments at a time: world_root()'s steps lane by lane (n·o in
        // double), a crossing where the root is within (0, t_max).
        for (const uint32_t i : scene.direct_planes) {
            if (open == 0) break;
            counters.primitive += lane_count(open);
            const Shape& plane = scene.shapes[i];
            const Lane2d nx = lanes2d(plane.normal.x), ny = lanes2d(plane.normal.y),
                         nz = lanes2d(plane.normal.z);
            const auto n_o = [&](Lane2d x, Lane2d y, Lane2d z) {  // two lanes, in double
                return nx * x + ny * y + nz * z;
            };
            const Lane2d offset = lanes2d(plane.offset);
            const F num = lanes_float(
                offset - n_o(lanes_low_double(o.x), lanes_low_double(o.y), lanes_low_double(o.z)),
                offset -
                    n_o(lanes_high_double(o.x), lanes_high_double(o.y), lanes_high_double(o.z)));
            const F n_d = plane.normal.x * dir.x + plane.normal.y * dir.y + plane.normal.z * dir.z;
            const F t = num / n_d;
            const unsigned within = lane_bits(0.0f < t) & lane_bits(t < load_lanes4(t_max)) & open;
            for (unsigned lanes = within; lanes != 0; lanes &= lanes - 1) {
                const int l = __builtin_ctz(lanes);
                if (!add_crossings(materials, plane.material, 1, crossings[l])) {
                    T[first + l] = 0.0f;
                    open &= ~(1u << l);
                }
            }
        }
        for (unsigned lanes = open; lanes != 0; lanes &= lanes - 1) {
            const int l = __builtin_ctz(lanes);
            T[first + l] = crossings[l].product();
        }
    }
}

}  // namespace luz::query
