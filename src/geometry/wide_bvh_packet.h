// The 8-wide BVH traversed by a packet of up to eight rays at once (WideBvh::nearest() for each
// ray, in lock step): every child box is tested for all the packet's rays side by side, with
// per ray the very arithmetic of hit_wide() (the same boxes hit, at the same entry distances),
// and a child is visited by the rays that hit it. Coherent rays (neighbouring camera rays) share
// most nodes, so a node's fetch, its tests and the stack work serve eight rays. any_packet() is
// the same for shadow rays (WideBvh::any_leaves() in lock step): leaves in any order, a ray
// leaving the packet once something blocks it.
//
//     float t_max[8] = {...};  // per ray, lowered by test() as hits are found
//     nearest_packet(bvh, packet, packet.all(), t_min, t_max, box_tests,
//                    [&](uint32_t first, uint32_t count, unsigned lanes) { ... });  // rays in
//                    `lanes`
#pragma once

#include <cstdint>

#include "geometry/ray_packet.h"
#include "geometry/wide_bvh.h"
#include "math/lane_count.h"

namespace luz {

namespace packet_detail {

/// The packet prepared for box tests: per ray 1/direction and which plane of a slab is near.
struct BoxRays {
    Lane8f o[3], inv[3];
    Lane8i negative[3];  ///< 1/direction < 0 (−∞ for a −0 component): the near plane is hi

    explicit BoxRays(const RayPacket& p) {
        for (int a = 0; a < 3; ++a) {
            o[a] = p.o[a];
            inv[a] = lanes(1.0f) / p.d[a];
            negative[a] = lane_lt(inv[a], lanes(0.0f));
        }
    }
};

/// Child k of n against every ray over [t_min, t_max(lane)]: the rays that hit it, their entry
/// distances in `entry`. Lane for lane the arithmetic of hit_wide().
inline Lane8i hit_child(const Bvh8::Node& n, int k, const BoxRays& r, Lane8f t_min, Lane8f t_max,
                        Lane8f& entry) {
    Lane8f tn = t_min, tf = t_max;
    const Lane8f scale = lanes(bvh_detail::kExitScale);
    for (int a = 0; a < 3; ++a) {
        const Lane8f lo = lanes(n.lo[a][k]), hi = lanes(n.hi[a][k]);
        const Lane8f near_plane = lane_select(r.negative[a], hi, lo);
        const Lane8f far_plane = lane_select(r.negative[a], lo, hi);
        const Lane8f t0 = (near_plane - r.o[a]) * r.inv[a];
        const Lane8f t1 = ((far_plane - r.o[a]) * r.inv[a]) * scale;
        tn = greater_or_second(t0, tn);  // t0 > tn ? t0 : tn (NaN → tn)
        tf = less_or_second(t1, tf);     // t1 < tf ? t1 : tf (NaN → tf)
    }
    entry = tn;
    return lane_le(tn, tf);
}

/// The rays of `in_packet` that meet child k of n (none for an unused child), their entry
/// distances in `entry`.
[[gnu::always_inline]] inline unsigned rays_in_child(const Bvh8::Node& n, int k, const BoxRays& r,
                                                     Lane8f t_min, Lane8f t_max, Lane8i in_packet,
                                                     Lane8f& entry) {
    if (n.count[k] == 0 && n.child[k] == Bvh8::Node::kUnused) return 0;
    return lane_bits(hit_child(n, k, r, t_min, t_max, entry) & in_packet);
}

/// with_margin() lane by lane.
inline Lane8f with_margin(Lane8f t_max) { return t_max + t_max * lanes(0x1p-16f); }

}  // namespace packet_detail

/// For each ray of `active` (bit k: lane k of p), as bvh.nearest_leaves() would for it alone:
/// test(first, count, lanes) for every leaf (slots first … first + count − 1) whose box those
/// rays meet before their t_max (with the same margin); test() lowers t_max[lane] as it finds
/// hits. Children are visited
/// nearest first for the packet (by its rays' smallest entry). Adds 8 per node per ray to
/// box_tests, as the single-ray traversal counts.
template <class Test>
void nearest_packet(const Bvh8& bvh, const RayPacket& p, unsigned active, float t_min, float* t_max,
                    uint64_t& box_tests, Test&& test) {
    using namespace packet_detail;
    const Bvh8::Nodes& nodes = bvh.nodes();
    if (nodes.empty() || active == 0) return;
    const BoxRays rays(p);
    const Lane8f t_min8 = lanes(t_min);
    struct Entry {
        Lane8f entry;  // per ray
        uint32_t child, count, lanes;
        float key;  // the smallest entry among `lanes`: the visiting order
    };
    constexpr int kStack = 7 * Bvh::kMaxDepth + 4;
    Entry stack[kStack];
    int top = 0;
    Entry cur{lanes(t_min), 0, 0, active, t_min};
    for (;;) {
        if (cur.count > 0) {
            test(cur.child, cur.count, cur.lanes);
        } else {
            const Bvh8::Node& n = nodes[cur.child];
            box_tests += 8 * static_cast<uint64_t>(lane_count(cur.lanes));
            const Lane8f limit = with_margin(load_lanes(t_max));
            const Lane8i in_packet = lane_mask(cur.lanes);
            Entry h[8];
            int m = 0;
            for (int k = 0; k < 8; ++k) {
                Lane8f entry;
                const unsigned hit = rays_in_child(n, k, rays, t_min8, limit, in_packet, entry);
                if (hit == 0) continue;
                float key = entry[__builtin_ctz(hit)];
                for (unsigned b = hit & (hit - 1); b != 0; b &= b - 1) {
                    const float e = entry[__builtin_ctz(b)];
                    key = e < key ? e : key;
                }
                h[m++] = {entry, n.child[k], n.count[k], hit, key};
            }
            if (m > 0) {
                // farthest first onto the stack, the nearest now
                bvh_detail::sort_farthest_first(h, m, [](const Entry& x) { return x.key; });
                for (int i = 0; i + 1 < m; ++i) stack[top++] = h[i];
                cur = h[m - 1];
                continue;
            }
        }
        // next entry from the stack, with only its rays that enter it before their nearest hit
        for (;;) {
            if (top == 0) return;
            Entry& s = stack[--top];
            s.lanes &= lane_bits(lane_le(s.entry, with_margin(load_lanes(t_max))));
            if (s.lanes != 0) {
                cur = s;
                break;
            }
        }
    }
}

/// For each ray of `active`, as bvh.any_leaves() would for it alone: visit(first, count, lanes)
/// for every leaf whose box rays `lanes` meet in (t_min, t_max[lane]) (with the same margin),
/// leaves in no particular order, until visit() has settled every ray: it returns the rays it
/// settles (a shadow ray blocked), which leave the packet. Returns the rays settled. Adds 8 per
/// node per ray to box_tests, as the single-ray traversal counts.
template <class Visit>
unsigned any_packet(const Bvh8& bvh, const RayPacket& p, unsigned active, float t_min,
                    const float* t_max, uint64_t& box_tests, Visit&& visit) {
    using namespace packet_detail;
    const Bvh8::Nodes& nodes = bvh.nodes();
    if (nodes.empty() || active == 0) return 0;
    const BoxRays rays(p);
    const Lane8f t_min8 = lanes(t_min);
    const Lane8f limit = with_margin(load_lanes(t_max));
    struct Entry {
        uint32_t child, count, lanes;
    };
    constexpr int kStack = 7 * Bvh::kMaxDepth + 4;
    Entry stack[kStack];
    int top = 0;
    unsigned open = active;  // not settled yet
    Entry cur{0, 0, active};
    for (;;) {
        if (cur.count > 0) {
            open &= ~visit(cur.child, cur.count, cur.lanes);
            if (open == 0) return active;
        } else {
            const Bvh8::Node& n = nodes[cur.child];
            box_tests += 8 * static_cast<uint64_t>(lane_count(cur.lanes));
            const Lane8i in_packet = lane_mask(cur.lanes);
            Entry h[8];
            int m = 0;
            for (int k = 0; k < 8; ++k) {
                Lane8f entry;
                const unsigned hit = rays_in_child(n, k, rays, t_min8, limit, in_packet, entry);
                if (hit != 0) h[m++] = {n.child[k], n.count[k], hit};
            }
            if (m > 0) {
                for (int i = m - 1; i > 0; --i) stack[top++] = h[i];
                cur = h[0];
                continue;
            }
        }
        // next entry from the stack, with only its rays not settled yet
        for (;;) {
            if (top == 0) return active & ~open;
            const Entry& s = stack[--top];
            if ((s.lanes & open) != 0) {
                cur = {s.child, s.count, s.lanes & open};
                break;
            }
        }
    }
}

}  // namespace luz
