// The nearest hits of a packet of rays by the scene's BVH (render.accel = bvh, more than a direct
// scene): one traversal for up to eight rays (wide_bvh_packet.h), a leaf's triangles tested
// against all its rays side by side with the watertight test's arithmetic lane for lane, ties
// resolved per ray by Best. Each ray's answer is the one nearest_hit_bvh() gives it.
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
    const Lane8f Az = lanes(at(p0, r.kz)) - r.oz, Bz = lanes(at(p1, r.kz)) - r.oz,
                 Cz = lanes(at(p2, r.kz)) - r.oz;
    const Lane8f Ax = (lanes(at(p0, r.kx)) - r.ox) - r.Sx * Az;
    const Lane8f Ay = (lanes(at(p0, r.ky)) - r.oy) - r.Sy * Az;
    const Lane8f Bx = (lanes(at(p1, r.kx)) - r.ox) - r.Sx * Bz;
    const Lane8f By = (lanes(at(p1, r.ky)) - r.oy) - r.Sy * Bz;
    const Lane8f Cx = (lanes(at(p2, r.kx)) - r.ox) - r.Sx * Cz;
    const Lane8f Cy = (lanes(at(p2, r.ky)) - r.oy) - r.Sy * Cz;
    const Lane8f U = Cx * By - Cy * Bx, V = Ax * Cy - Ay * Cx, W = Bx * Ay - By * Ax;
    const Lane8f zero = lanes(0.0f);
    scalar = lane_bits((U == zero) | (V == zero) | (W == zero));
    const Lane8i outside =
        ((U < zero) | (V < zero) | (W < zero)) & ((U > zero) | (V > zero) | (W > zero));
    const Lane8f det = U + V + W;
    const Lane8f T = U * (r.Sz * Az) + V * (r.Sz * Bz) + W * (r.Sz * Cz);
    const Lane8f inv_det = lanes(1.0f) / det;
    t = T * inv_det;
    b1 = V * inv_det;
    b2 = W * inv_det;
    const Lane8i hit = ~outside & (det != zero) & (t > lanes(t_min)) & (t < limit);
    return lane_bits(hit) & ~scalar;
}

}  // namespace

void nearest_hits_bvh(const BuiltScene& scene, const Ray* rays, int n, float t_min, float t_max,
                      Hit* hits, bool* found, IntersectCounters& counters) {
    const RayPacket packet(rays, n);
    const unsigned all = packet.all();
    Best best[kPacketLanes] = {Best(t_max), Best(t_max), Best(t_max), Best(t_max),
                               Best(t_max), Best(t_max), Best(t_max), Best(t_max)};
    WatertightRay w[kPacketLanes];
    for (int k = 0; k < n; ++k) {
        for (uint32_t i : scene.unbounded) offer_shape(scene, i, rays[k], t_min, best[k], counters);
        if (scene.mesh_triangles) w[k] = prepare_watertight(rays[k]);
    }
    WatertightLanes wl;
    const bool lanes_share_axes = scene.mesh_triangles && shared_axes(w, all, wl);
    float limit[kPacketLanes], node_limit[kPacketLanes];
    for (int k = 0; k < kPacketLanes; ++k) {
        limit[k] = k < n ? best[k].limit() : t_max;
        node_limit[k] = k < n ? best[k].t : t_max;
    }
    nearest_packet(scene.bvh, packet, all, t_min, node_limit, counters.bounds,
                   [&](uint32_t slot, unsigned active) {
                       const BvhPrim& p = scene.bvh_prims[slot];
                       unsigned one_by_one = active;
                       if (p.triangle != BvhPrim::kNotTriangle && lanes_share_axes) {
                           Lane8f t, b1, b2;
                           unsigned scalar;
                           unsigned hit = triangle_lanes(wl, p.p0, p.p1, p.p2, t_min,
                                                         load_lanes(limit), t, b1, b2, scalar) &
                                          active;
                           one_by_one = scalar & active;
                           counters.primitive += __builtin_popcount(active & ~one_by_one);
                           for (; hit != 0; hit &= hit - 1) {
                               const int k = __builtin_ctz(hit);
                               if (!best[k].better(t[k], p.shape, p.triangle)) continue;
                               best[k].take(t[k], p.shape, p.triangle, b1[k], b2[k],
                                            static_cast<int>(p.triangle));
                               limit[k] = best[k].limit();
                               node_limit[k] = best[k].t;
                           }
                       }
                       for (; one_by_one != 0; one_by_one &= one_by_one - 1) {
                           const int k = __builtin_ctz(one_by_one);
                           if (p.triangle != BvhPrim::kNotTriangle) {
                               offer_triangle(w[k], p.p0, p.p1, p.p2, p.shape, p.triangle, t_min,
                                              best[k], counters);
                           } else {
                               offer_shape(scene, p.shape, rays[k], t_min, best[k], counters);
                           }
                           limit[k] = best[k].limit();
                           node_limit[k] = best[k].t;
                       }
                   });
    for (int k = 0; k < n; ++k) {
        found[k] = best[k].found;
        if (best[k].found) hits[k] = best[k].hit;
    }
}

}  // namespace luz::query
