// The wide BVH's node (W child boxes side by side, by axis) and its slab test: a ray prepared
// once (WideRay), then the W boxes of a node tested at once on lanes (hit_wide()) — eight in
// one register with AVX, two halves of four otherwise (math/lanes.h).
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "geometry/bvh.h"
#include "math/lanes.h"
#include "math/ray.h"

namespace luz {

/// W child boxes by axis (lo[axis][child], hi[axis][child]); child k is a node (count[k] = 0,
/// child[k] its index), a leaf (count[k] > 0 primitives from slot child[k] of order()), or
/// unused (count[k] = 0, child[k] = kUnused, an empty box that no ray meets).
template <int W>
struct alignas(64) WideBvhNode {
    float lo[3][W];
    float hi[3][W];
    uint32_t child[W];
    uint32_t count[W];

    static constexpr uint32_t kUnused = 0xFFFFFFFFu;
    WideBvhNode() {}  // left uninitialized: the collapse writes every field
};
static_assert(sizeof(WideBvhNode<4>) == 128 && sizeof(WideBvhNode<8>) == 256);

namespace bvh_detail {

/// The lanes a node of W boxes is tested on: eight where one register holds them, else four
/// (a node of eight then in two halves).
template <int W>
using SlabLanes = std::conditional_t<W == 8 && kLane8InOneRegister, Lane8f, Lane4f>;

/// x in every lane of V.
template <class V>
[[gnu::always_inline]] inline V lanes_of(float x) {
    if constexpr (std::is_same_v<V, Lane8f>) {
        return lanes(x);
    } else {
        return lanes4(x);
    }
}
[[gnu::always_inline]] inline Lane8f load_aligned(const float* p, Lane8f) {
    return load_aligned_lanes(p);
}
[[gnu::always_inline]] inline Lane4f load_aligned(const float* p, Lane4f) {
    return load_aligned_lanes4(p);
}
[[gnu::always_inline]] inline void store(float* p, Lane8f v) { store_lanes(p, v); }
[[gnu::always_inline]] inline void store(float* p, Lane4f v) { store_lanes4(p, v); }

/// A ray prepared for the wide box test: per axis the origin and 1/direction (lanes alike) and
/// where in a node its near and far planes are (hi for a negative 1/direction, else lo).
template <int W>
struct WideRay {
    using V = SlabLanes<W>;
    V o[3], inv[3];
    float os[4], invs[4];            // x, y, z (and a fourth lane for the four-lane stores)
    uint32_t near_at[3], far_at[3];  // byte offsets in WideBvhNode<W>
    /// Every 1/direction finite and t_min ≥ 0: no slab distance is NaN, and the entry (a
    /// maximum with t_min) is ≥ 0, so that maxima and minima of the distances may be taken on
    /// their bits as integers (one cycle instead of four), with the same results (hit_wide()).
    bool as_ints = false;
    /// The padded slab test (hit_wide(), builds with fused multiply-add): t = plane·inv + c,
    /// one fused multiply-add, with c = −o·inv ∓ m per axis (near, far planes),
    /// m = 2⁻²¹·(reach + |o|)·|inv|.
    Lane8f c_near[3], c_far[3];
    bool padded = false;

    /// `reach`: the largest |coordinate| of any box the ray will be tested against (the
    /// tree's; +∞ if unknown, which leaves the padded test off). Every ray of a traversal
    /// starts here, so the three axes are prepared side by side in four lanes.
    WideRay(const Ray& r, float t_min,
            [[maybe_unused]] float reach = std::numeric_limits<float>::infinity()) {
        const Lane4f o4{r.origin.x, r.origin.y, r.origin.z, 0.0f};
        const Lane4f inv4 = 1.0f / Lane4f{r.direction.x, r.direction.y, r.direction.z, 1.0f};
        store_lanes4(os, o4);
        store_lanes4(invs, inv4);
        const Lane4f infinity = lanes4(std::numeric_limits<float>::infinity());
        const unsigned negative = lane_bits((Lane4i)inv4);  // sign bits: −∞ for a −0 component
        const bool finite = (lane_bits(lane_lt(lane_abs(inv4), infinity)) & 7) == 7;
        as_ints = t_min >= 0.0f && finite;
        for (int a = 0; a < 3; ++a) {
            o[a] = lanes_of<V>(os[a]);
            inv[a] = lanes_of<V>(invs[a]);
            const uint32_t lo = static_cast<uint32_t>(a * W * 4);
            const uint32_t hi = static_cast<uint32_t>((3 + a) * W * 4);
            const bool flip = (negative >> a) & 1;
            near_at[a] = flip ? hi : lo;
            far_at[a] = flip ? lo : hi;
        }
        if constexpr (W == 8 && kLaneFusedMultiplyAdd) {  // only hit_wide<8>() has the padded test
            // Rounding: plane·inv + c differs from (plane − o)/direction by less than
            // 4·2⁻²⁴·(|plane| + |o|)·|inv| ≤ m/2 (the rounding of 1/direction, of o·inv, of c
            // and of the fused result), so that the near distance is lowered and the far one
            // raised by at least what rounding could move them: the hit children are a superset
            // of the exact test's, each entry at most the exact one. m normal and every c finite
            // keep every distance finite, never NaN nor −0 (see hit_wide()).
            const Lane4f m = 0x1p-21f * (reach + lane_abs(o4)) * lane_abs(inv4);
            const Lane4f c = 0.0f - o4 * inv4;
            const Lane4f cn = c - m, cf = c + m;
            const Lane4i ok = lane_ge(m, lanes4(std::numeric_limits<float>::min())) &
                              lane_lt(m, infinity) & lane_lt(lane_abs(cn), infinity) &
                              lane_lt(lane_abs(cf), infinity);
            padded = as_ints && (lane_bits(ok) & 7) == 7;
            for (int a = 0; a < 3; ++a) {
                c_near[a] = lanes(cn[a]);
                c_far[a] = lanes(cf[a]);
            }
        }
    }
};

/// One vector V of the slab test from byte offset `lane` of the planes (see hit_wide()).
template <class V, int W>
[[gnu::always_inline]] inline unsigned hit_lanes(const char* base, const WideRay<W>& r, float t_min,
                                                 float t_max, float* entry, int lane) {
    V tn = lanes_of<V>(t_min), tf = lanes_of<V>(t_max);
    const V scale = lanes_of<V>(kExitScale);
    for (int a = 0; a < 3; ++a) {
        const V near_plane =
            load_aligned(reinterpret_cast<const float*>(base + r.near_at[a] + lane), V{});
        const V far_plane =
            load_aligned(reinterpret_cast<const float*>(base + r.far_at[a] + lane), V{});
        const V t0 = (near_plane - r.o[a]) * r.inv[a];
        const V t1 = (far_plane - r.o[a]) * r.inv[a] * scale;
        tn = greater_or_second(t0, tn);  // NaN → tn
        tf = less_or_second(t1, tf);     // NaN → tf
    }
    store(entry, tn);
    return lane_bits(lane_le(tn, tf));
}

/// Eight boxes' entry (the largest of the near distances t0 and t_min) and exit (the least of
/// the far ones t1 and t_max), taken on the distances' bits as integers (see hit_wide()).
[[gnu::always_inline]] inline Lane8i entry_as_ints(const Lane8i (&t0)[3], float t_min) {
    return lane_max(lane_max(t0[0], t0[1]), lane_max(t0[2], (Lane8i)lanes(t_min)));
}
[[gnu::always_inline]] inline Lane8i exit_as_ints(const Lane8i (&t1)[3], float t_max) {
    return lane_min(lane_min(t1[0], t1[1]), lane_min(t1[2], (Lane8i)lanes(t_max)));
}

/// The W boxes of n against r over [t_min, t_max]: bit k set if child k is hit, its entry
/// distance in entry[k]. Per lane the very arithmetic of hit_node(): the same hits and entries
/// (a NaN from 0·∞ loses in max/min against the running interval, which it leaves as it is).
template <int W>
[[gnu::always_inline]] inline int hit_wide(const WideBvhNode<W>& n, const WideRay<W>& r,
                                           float t_min, float t_max, float* entry) {
    const char* base = reinterpret_cast<const char*>(&n);
    const auto plane = [&](uint32_t at) {
        return load_aligned_lanes(reinterpret_cast<const float*>(base + at));
    };
    // The padded test (WideRay::padded): t = plane·inv + c in one rounding, the near planes'
    // distances lowered and the far ones' raised past any rounding, so that it hits at least
    // the children the exact test below hits, at entries no later. As there, maxima and
    // minima on the bits as integers; the comparison too: the entry is ≥ 0 and no distance
    // is −0 or NaN (m > 0), so tn > tf as integers exactly when as floats.
    if constexpr (W == 8 && kLaneFusedMultiplyAdd) {
        if (r.padded) {
            Lane8i t0[3], t1[3];
            for (int a = 0; a < 3; ++a) {
                t0[a] = (Lane8i)lane_fmadd(plane(r.near_at[a]), r.inv[a], r.c_near[a]);
                t1[a] = (Lane8i)lane_fmadd(plane(r.far_at[a]), r.inv[a], r.c_far[a]);
            }
            const Lane8i tn = entry_as_ints(t0, t_min), tf = exit_as_ints(t1, t_max);
            store_lanes(entry, (Lane8f)tn);
            return static_cast<int>(~lane_bits(lane_gt(tn, tf)) & 0xFF);
        }
    }
    // No NaN and an entry ≥ 0 (WideRay::as_ints): a float's bits ordered as an integer order
    // non-negative floats as floats do, and put every negative one below them. The entry, a
    // maximum with t_min ≥ 0, is then the float maximum; the exit, a minimum (its −0s made
    // +0 first), is the float minimum whenever that is ≥ 0, else some negative distance: a
    // miss either way in the float comparison that follows.
    if constexpr (W == 8 && kLane8iInOneRegister) {
        if (r.as_ints) {
            const Lane8f scale = lanes(kExitScale);
            const Lane8i negative_zero = lanes_i(INT32_MIN);
            Lane8i t0[3], t1[3];
            for (int a = 0; a < 3; ++a) {
                t0[a] = (Lane8i)((plane(r.near_at[a]) - r.o[a]) * r.inv[a]);
                t1[a] = (Lane8i)((plane(r.far_at[a]) - r.o[a]) * r.inv[a] * scale);
                // −0 (the origin on a far plane) is the least integer: make it +0
                t1[a] = ~lane_eq(t1[a], negative_zero) & t1[a];
            }
            const Lane8i tn = entry_as_ints(t0, t_min), tf = exit_as_ints(t1, t_max);
            store_lanes(entry, (Lane8f)tn);
            return static_cast<int>(lane_bits(lane_le((Lane8f)tn, (Lane8f)tf)));
        }
    }
    using V = SlabLanes<W>;
    if constexpr (sizeof(V) == W * sizeof(float)) {  // the W boxes in one vector
        return static_cast<int>(hit_lanes<V>(base, r, t_min, t_max, entry, 0));
    } else {  // eight boxes as two halves of four
        return static_cast<int>(hit_lanes<V>(base, r, t_min, t_max, entry, 0) |
                                (hit_lanes<V>(base, r, t_min, t_max, entry + 4, 16) << 4));
    }
}

}  // namespace bvh_detail

}  // namespace luz
