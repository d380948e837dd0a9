// The nearest hits of a packet of rays by the scene's BVH (render.accel = bvh): one traversal for
// up to eight rays (wide_bvh_packet.h), none for a BVH that is one leaf; at a leaf, each triangle
// against the rays that reach it side by side, or (few rays) each ray against the leaf's blocks
// of four, both with the watertight test's arithmetic lane for lane, and a leaf's spheres four
// rays at a time (query_leaf_packet.cpp); ties resolved per ray by Best. Each ray's answer is
// the one nearest_hit_bvh() gives it.
#include "geometry/query_parts.h"
#include "geometry/ray_packet.h"
#include "geometry/wide_bvh_packet.h"

namespace luz::query {

namespace {

/// The packet's rays prepared for the watertight test, when they share its axes (kx, ky, kz):
/// per ray the shear and the origin in that order.
struct WatertightLanes {
    int kx = 0, ky = 1, kz = 2;
    Lane8f Sx, Sy, Sz, ox, oy, oz;
};

/// Whether the rays of `active` share their axes; if so `out` holds them side by side.
bool shared_axes(const WatertightRay* w, unsigned active, WatertightLanes& out) {
    const int first = __builtin_ctz(active);
    out.kx = w[first].kx;
    out.ky = w[first].ky;
    out.kz = w[first].kz;
    for (int k = 0; k < kPacketLanes; ++k) {
        const WatertightRay& r = w[(active >> k) & 1u ? k : first];
        if (r.kx != out.kx || r.ky != out.ky || r.kz != out.kz) return false;
        out.Sx[k] = r.Sx;
        out.Sy[k] = r.Sy;
        out.Sz[k] = r.Sz;
        out.ox[k] = r.ox;
        out.oy[k] = r.oy;
        out.oz[k] = r.oz;
    }
    return true;
}

/// intersect_triangle() for every ray at once, up to the decision: the rays that hit in
/// (t_min, limit) at t with barycentrics b1, b2, and in `scalar` those whose edge functions
/// need the double path (to be tested one by one).
unsigned triangle_lanes(const WatertightLanes& r, const Vec3& p0, const Vec3& p1, const Vec3& p2,
                        float t_min, Lane8f limit, Lane8f& t, Lane8f& b1, Lane8f& b2,
                        unsigned& scalar) {
    using watertight_detail::at;
    const Lane8f x[3] = {lanes(at(p0, r.kx)), lanes(at(p1, r.kx)), lanes(at(p2, r.kx))};
    const Lane8f y[3] = {lanes(at(p0, r.ky)), lanes(at(p1, r.ky)), lanes(at(p2, r.ky))};
    const Lane8f z[3] = {lanes(at(p0, r.kz)), lanes(at(p1, r.kz)), lanes(at(p2, r.kz))};
    Lane8i defer;
    const Lane8i hit = intersect_triangle_lanes(x, y, z, r.ox, r.oy, r.oz, r.Sx, r.Sy, r.Sz,
                                                lanes(t_min), limit, t, b1, b2, defer);
    scalar = lane_bits(defer);
    return lane_bits(hit) & ~scalar;
}

}  // namespace

void nearest_hits_bvh(const BuiltScene& scene, const Ray* rays, int n, float t_min, float t_max,
                      Hit* hits, bool* found, IntersectCounters& counters) {
    const unsigned all = (1u << n) - 1;
    Best best[kPacketLanes] = {Best(t_max), Best(t_max), Best(t_max), Best(t_max),
                               Best(t_max), Best(t_max), Best(t_max), Best(t_max)};
    WatertightRay w[kPacketLanes];
    const auto answer = [&] {
        for (int k = 0; k < n; ++k) {
            found[k] = best[k].found;
            if (best[k].found) hits[k] = best[k].hit;
        }
    };
    if (scene.root_leaf != 0 && scene.mesh_triangles == 0) {  // one leaf of shapes, and planes
        nearest_hits_leaf(scene, 0, scene.root_leaf, rays, w, all, t_min, best, counters, true);
        return answer();
    }
    for (int k = 0; k < n; ++k) {
        offer_unbounded(scene, rays[k], t_min, best[k], counters);
        if (scene.mesh_triangles) w[k] = prepare_watertight(rays[k]);
    }
    WatertightLanes wl;
    const bool lanes_share_axes = scene.mesh_triangles && shared_axes(w, all, wl);
    float limit[kPacketLanes], node_limit[kPacketLanes];
    for (int k = 0; k < kPacketLanes; ++k) {
        limit[k] = k < n ? best[k].limit() : t_max;
        node_limit[k] = k < n ? best[k].t : t_max;
    }
    const auto update = [&](int k) {
        limit[k] = best[k].limit();
        node_limit[k] = best[k].t;
    };
    // Each of rays `active` against the leaf's blocks, four primitives at a time.
    const auto one_ray_at_a_time = [&](uint32_t first, uint32_t count, unsigned active) {
        for (; active != 0; active &= active - 1) {
            const int k = __builtin_ctz(active);
            for_each_block(scene, first, count, [&](const PrimBlock& b, unsigned lanes) {
                offer_block(scene, b, lanes, rays[k], w[k], t_min, best[k], counters);
                return true;
            });
            update(k);
        }
    };
    // Each of the leaf's primitives against rays `active` side by side (triangles, when the rays
    // share their axes), or one by one.
    const auto one_primitive_at_a_time = [&](uint32_t first, uint32_t count, unsigned active) {
        for (uint32_t slot = first; slot < first + count; ++slot) {
            const BvhPrim p = scene.bvh_prim(slot);
            unsigned one_by_one = active;
            if (p.triangle != BvhPrim::kNotTriangle && lanes_share_axes) {
                Lane8f t, b1, b2;
                unsigned scalar;
                unsigned hit = triangle_lanes(wl, p.p0, p.p1, p.p2, t_min, load_lanes(limit), t, b1,
                                              b2, scalar) &
                               active;
                one_by_one = scalar & active;
                counters.primitive += lane_count(active & ~one_by_one);
                for (; hit != 0; hit &= hit - 1) {
                    const int k = __builtin_ctz(hit);
                    if (!best[k].better(t[k], p.shape, p.triangle)) continue;
                    best[k].take(t[k], p.shape, p.triangle, b1[k], b2[k],
                                 static_cast<int>(p.triangle));
                    update(k);
                }
            }
            for (; one_by_one != 0; one_by_one &= one_by_one - 1) {
                const int k = __builtin_ctz(one_by_one);
                if (p.triangle != BvhPrim::kNotTriangle) {
                    offer_triangle(w[k], p.p0, p.p1, p.p2, p.shape, p.triangle, t_min, best[k],
                                   counters);
                } else {
                    offer_shape(scene, p.shape, rays[k], t_min, best[k], counters);
                }
                update(k);
            }
        }
    };
    const auto leaf = [&](uint32_t first, uint32_t count, unsigned active) {
        // eight lanes for the rays, or four for the primitives: the fewer tests
        const uint32_t rays_in = static_cast<uint32_t>(lane_count(active));
        const uint32_t blocks = (count + PrimBlock::kLanes - 1) / PrimBlock::kLanes;
        // a leaf without triangles: its shapes have no packet test by primitive, but its
        // sphere lanes meet four rays at a time, its axis lanes each ray four at a time
        const auto no_triangles = [&] {
            return for_each_block(scene, first, count, [&](const PrimBlock& b, unsigned l) {
                return (b.triangle_lanes() & l) == 0;
            });
        };
        const auto has_spheres = [&] {
            return !for_each_block(scene, first, count, [&](const PrimBlock& b, unsigned l) {
                return (b.sphere_lanes() & l) == 0;
            });
        };
        if (lanes_share_axes && rays_in * blocks > count && !no_triangles()) {
            one_primitive_at_a_time(first, count, active);
        } else if (rays_in > 1 && has_spheres()) {
            nearest_hits_leaf(scene, first, count, rays, w, active, t_min, best, counters);
            for (unsigned left = active; left != 0; left &= left - 1) update(__builtin_ctz(left));
        } else {
            one_ray_at_a_time(first, count, active);
        }
    };
    if (scene.root_leaf != 0) {
        leaf(0, scene.root_leaf, all);
    } else {
        const RayPacket packet(rays, n);
        nearest_packet(scene.bvh, packet, all, t_min, node_limit, counters.bounds, leaf);
    }
    answer();
}

void transmittances_bvh(const BuiltScene& scene, const Materials& materials, const SegmentLanes& s,
                        unsigned active, float* T, IntersectCounters& counters,
                        ShadowCache& cache) {
    Ray r[kPacketLanes];
    LazyWatertight w[kPacketLanes];
    Crossings crossings[kPacketLanes];
    for (int k = 0; k < kPacketLanes; ++k) r[k] = s.ray(k);  // (lanes not active: never read)
    // As transmittance_bvh(), each segment first against the unbounded shapes.
    unsigned open = 0;  // the segments left for the traversal
    for (unsigned left = active; left != 0; left &= left - 1) {
        const int k = __builtin_ctz(left);
        T[k] = 0.0f;
        const auto crosses_unbounded = [&] {
            for (uint32_t i : scene.unbounded)
                if (!cross_shape(scene, materials, i, r[k], 0.0f, s.t_max[k], crossings[k],
                                 counters))
                    return false;
            return true;
        };
        if (!crosses_unbounded()) continue;
        open |= 1u << k;
    }
    // The segments `lanes` against the leaf of slots first … first + count − 1: those it blocks
    // (the cache then holds the block that blocked the last of them).
    const auto leaf = [&](uint32_t first, uint32_t count, unsigned lanes) {
        unsigned blocked = 0;
        for (; lanes != 0; lanes &= lanes - 1) {
            const int k = __builtin_ctz(lanes);
            for_each_block(scene, first, count, [&](const PrimBlock& b, unsigned l) {
                if (cross_block(scene, materials, b, l, r[k], w[k].for_block(r[k], b, l), 0.0f,
                                s.t_max[k], crossings[k], counters))
                    return true;
                cache.block = static_cast<uint32_t>(&b - scene.bvh_blocks.data());
                cache.lanes = l;
                blocked |= 1u << k;
                return false;
            });
        }
        return blocked;
    };
    const RayPacket packet(r, kPacketLanes);
    const unsigned blocked =
        any_packet(scene.bvh, packet, open, 0.0f, s.t_max, counters.bounds, leaf);
    for (unsigned left = open & ~blocked; left != 0; left &= left - 1) {
        const int k = __builtin_ctz(left);
        T[k] = crossings[k].lost()
                   ? transmittance_all(scene, materials, r[k], 0.0f, s.t_max[k], counters)
                   : crossings[k].product();
    }
}

}  // namespace luz::query
