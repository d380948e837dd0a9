// WideBvh<W> (Bvh8; Bvh4 in the tests): the binary Bvh collapsed into W-wide nodes holding their
// child boxes side by side, tested by one SIMD slab test: fewer levels and node visits. Same
// leaves, order() and traversal contract as Bvh (nearest and any with slot callbacks).
//
//     const Bvh8 bvh = Bvh8::build(boxes);  // or Bvh8(Bvh::build(boxes))
//     bvh.nearest(ray, 0.0f, t_max, box_tests, [&](uint32_t slot, float& t_max) { ... });
//
// Bvh8 tests its eight boxes with AVX (else as two halves with SSE2); W = 4 with SSE2.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include "geometry/bvh.h"
#include "math/huge_pages.h"

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

template <int W>
class WideBvh {
    static_assert(W == 4 || W == 8);

  public:
    using Node = WideBvhNode<W>;
    /// The nodes, on huge pages when large (math/huge_pages.h).
    using Nodes = HugeVector<Node>;

    WideBvh() = default;
    /// Collapses a binary BVH (taking its leaf order): each wide node gathers up to W
    /// descendants of a binary node; which binary nodes become wide nodes is the least-SAH
    /// choice (Σ surface area of the wide nodes, found by dynamic programming as in Ylitie et
    /// al., HPG 2017, with the leaves kept); nodes depth first. The tree depends only on the
    /// binary one.
    explicit WideBvh(Bvh&& binary);
    /// WideBvh(Bvh::build(bounds, options)).
    static WideBvh build(std::span<const Bounds3> bounds, const BvhOptions& options = {}) {
        return WideBvh(Bvh::build(bounds, options));
    }

    bool empty() const { return nodes_.empty(); }
    const Nodes& nodes() const { return nodes_; }
    /// Primitive ids in leaf order, as Bvh::order().
    const HugeVector<uint32_t>& order() const { return order_; }
    /// Moves the leaf order out, for an owner that keeps its primitives in leaf order (slot i
    /// is its i-th primitive): order() is empty afterwards; the traversals still work.
    HugeVector<uint32_t> take_order() {
        HugeVector<uint32_t> order;
        order.swap(order_);
        return order;
    }
    /// Bytes held by the nodes and the order.
    size_t memory_bytes() const {
        return nodes_.capacity() * sizeof(Node) + order_.capacity() * sizeof(uint32_t);
    }

    /// As Bvh::nearest(): test(slot, t_max) for every slot of every leaf whose box r meets
    /// before t_max (with the same margin), children visited nearest first; each node visit
    /// adds W to box_tests.
    template <class Test>
    void nearest(const Ray& r, float t_min, float& t_max, uint64_t& box_tests, Test&& test) const {
        nearest_leaves(r, t_min, t_max, box_tests, [&](uint32_t first, uint32_t count, float& t) {
            for (uint32_t i = first, end = first + count; i < end; ++i) test(i, t);
        });
    }
    /// nearest() a leaf at a time: test(first, count, t_max) for the leaf of slots first …
    /// first + count − 1.
    template <class Test>
    void nearest_leaves(const Ray& r, float t_min, float& t_max, uint64_t& box_tests,
                        Test&& test) const;

    /// As Bvh::any(): visit(slot) for every slot of every leaf whose box r meets, until it
    /// returns true; returns whether it did.
    template <class Visit>
    bool any(const Ray& r, float t_min, float t_max, uint64_t& box_tests, Visit&& visit) const {
        return any_leaves(r, t_min, t_max, box_tests, [&](uint32_t first, uint32_t count) {
            for (uint32_t i = first, end = first + count; i < end; ++i)
                if (visit(i)) return true;
            return false;
        });
    }
    /// any() a leaf at a time: visit(first, count) for the leaf of slots first … first +
    /// count − 1, until it returns true.
    template <class Visit>
    bool any_leaves(const Ray& r, float t_min, float t_max, uint64_t& box_tests,
                    Visit&& visit) const;

    /// Moves every leaf: its first slot becomes first(slot, count), called for the leaves in
    /// node order (depth first), for an owner that lays its primitives out anew (the scene's
    /// blocks of four, geometry/prim_block.h). order() no longer applies.
    template <class First>
    void renumber_leaves(First&& first) {
        for (Node& n : nodes_)
            for (int k = 0; k < W; ++k)
                if (n.count[k] > 0) n.child[k] = first(n.child[k], n.count[k]);
    }

  private:
    static constexpr int kStack = (W - 1) * Bvh::kMaxDepth + 4;  // ≤ W − 1 pushes per level
    Nodes nodes_;
    HugeVector<uint32_t> order_;
    float reach_ = std::numeric_limits<float>::infinity();  // max |coordinate| of the boxes
};

using Bvh8 = WideBvh<8>;

namespace bvh_detail {

/// A ray prepared for the wide box test: per axis the origin and 1/direction (SIMD lanes alike)
/// and where in a node its near and far planes are (hi for a negative 1/direction, else lo).
template <int W>
struct WideRay {
#if defined(__AVX__)
    __m256 o[3], inv[3];
#elif defined(__SSE2__)
    __m128 o[3], inv[3];
#endif
    float os[4], invs[4];            // x, y, z (and a fourth lane for SSE stores)
    uint32_t near_at[3], far_at[3];  // byte offsets in WideBvhNode<W>
    /// Every 1/direction finite and t_min ≥ 0: no slab distance is NaN, and the entry (a
    /// maximum with t_min) is ≥ 0, so that maxima and minima of the distances may be taken on
    /// their bits as integers (one cycle instead of four), with the same results (hit_wide()).
    bool as_ints = false;
#if defined(__AVX2__) && defined(__FMA__)
    /// The padded slab test (hit_wide()): t = plane·inv + c, one fused multiply-add, with
    /// c = −o·inv ∓ m per axis (near, far planes), m = 2⁻²¹·(reach + |o|)·|inv|.
    __m256 c_near[3], c_far[3];
    bool padded = false;
#endif

    /// `reach`: the largest |coordinate| of any box the ray will be tested against (the
    /// tree's; +∞ if unknown, which leaves the padded test off). Every ray of a traversal
    /// starts here, so the three axes are prepared side by side in SSE lanes.
    WideRay(const Ray& r, float t_min,
            [[maybe_unused]] float reach = std::numeric_limits<float>::infinity()) {
#if defined(__SSE2__)
        const __m128 o4 = _mm_setr_ps(r.origin.x, r.origin.y, r.origin.z, 0.0f);
        const __m128 inv4 = _mm_div_ps(
            _mm_set1_ps(1.0f), _mm_setr_ps(r.direction.x, r.direction.y, r.direction.z, 1.0f));
        _mm_storeu_ps(os, o4);
        _mm_storeu_ps(invs, inv4);
        const __m128 magnitude = _mm_castsi128_ps(_mm_set1_epi32(0x7FFFFFFF));
        const __m128 infinity = _mm_set1_ps(std::numeric_limits<float>::infinity());
        const int negative = _mm_movemask_ps(inv4);  // sign bits: −∞ for a −0 component
        const bool finite =
            (_mm_movemask_ps(_mm_cmplt_ps(_mm_and_ps(inv4, magnitude), infinity)) & 7) == 7;
#else
        int negative = 0;
        bool finite = true;
        for (int a = 0; a < 3; ++a) {
            os[a] = r.origin[a];
            invs[a] = 1.0f / r.direction[a];
            negative |= std::signbit(invs[a]) << a;
            finite = finite && std::isfinite(invs[a]);
        }
#endif
        as_ints = t_min >= 0.0f && finite;
        for (int a = 0; a < 3; ++a) {
#if defined(__AVX__)
            o[a] = _mm256_broadcast_ss(os + a);
            inv[a] = _mm256_broadcast_ss(invs + a);
#elif defined(__SSE2__)
            o[a] = _mm_set1_ps(os[a]);
            inv[a] = _mm_set1_ps(invs[a]);
#endif
            const uint32_t lo = static_cast<uint32_t>(a * W * 4);
            const uint32_t hi = static_cast<uint32_t>((3 + a) * W * 4);
            const bool flip = (negative >> a) & 1;
            near_at[a] = flip ? hi : lo;
            far_at[a] = flip ? lo : hi;
        }
#if defined(__AVX2__) && defined(__FMA__)
        if constexpr (W == 8) {  // only hit_wide<8>() has the padded test
            // Rounding: plane·inv + c differs from (plane − o)/direction by less than
            // 4·2⁻²⁴·(|plane| + |o|)·|inv| ≤ m/2 (the rounding of 1/direction, of o·inv, of c
            // and of the fused result), so that the near distance is lowered and the far one
            // raised by at least what rounding could move them: the hit children are a superset
            // of the exact test's, each entry at most the exact one. m normal and every c finite
            // keep every distance finite, never NaN nor −0 (see hit_wide()).
            const __m128 m =
                _mm_mul_ps(_mm_mul_ps(_mm_set1_ps(0x1p-21f),
                                      _mm_add_ps(_mm_set1_ps(reach), _mm_and_ps(o4, magnitude))),
                           _mm_and_ps(inv4, magnitude));
            const __m128 c = _mm_sub_ps(_mm_setzero_ps(), _mm_mul_ps(o4, inv4));
            const __m128 cn = _mm_sub_ps(c, m), cf = _mm_add_ps(c, m);
            const __m128 ok = _mm_and_ps(
                _mm_and_ps(_mm_cmpge_ps(m, _mm_set1_ps(std::numeric_limits<float>::min())),
                           _mm_cmplt_ps(m, infinity)),
                _mm_and_ps(_mm_cmplt_ps(_mm_and_ps(cn, magnitude), infinity),
                           _mm_cmplt_ps(_mm_and_ps(cf, magnitude), infinity)));
            padded = as_ints && (_mm_movemask_ps(ok) & 7) == 7;
            alignas(16) float near_c[4], far_c[4];
            _mm_store_ps(near_c, cn);
            _mm_store_ps(far_c, cf);
            for (int a = 0; a < 3; ++a) {
                c_near[a] = _mm256_broadcast_ss(near_c + a);
                c_far[a] = _mm256_broadcast_ss(far_c + a);
            }
        }
#endif
    }
};

#if defined(__SSE2__)
/// Four lanes of the slab test from byte offset `lane` of the planes (see hit_wide()).
template <int W>
inline int hit_lanes4(const char* base, const WideRay<W>& r, float t_min, float t_max, float* entry,
                      int lane) {
#if defined(__AVX__)
    const __m128 o[3] = {_mm256_castps256_ps128(r.o[0]), _mm256_castps256_ps128(r.o[1]),
                         _mm256_castps256_ps128(r.o[2])};
    const __m128 inv[3] = {_mm256_castps256_ps128(r.inv[0]), _mm256_castps256_ps128(r.inv[1]),
                           _mm256_castps256_ps128(r.inv[2])};
#else
    const __m128* o = r.o;
    const __m128* inv = r.inv;
#endif
    __m128 tn = _mm_set1_ps(t_min), tf = _mm_set1_ps(t_max);
    const __m128 scale = _mm_set1_ps(kExitScale);
    for (int a = 0; a < 3; ++a) {
        const __m128 near_plane =
            _mm_load_ps(reinterpret_cast<const float*>(base + r.near_at[a] + lane));
        const __m128 far_plane =
            _mm_load_ps(reinterpret_cast<const float*>(base + r.far_at[a] + lane));
        const __m128 t0 = _mm_mul_ps(_mm_sub_ps(near_plane, o[a]), inv[a]);
        const __m128 t1 = _mm_mul_ps(_mm_mul_ps(_mm_sub_ps(far_plane, o[a]), inv[a]), scale);
        tn = _mm_max_ps(t0, tn);  // NaN → tn
        tf = _mm_min_ps(t1, tf);  // NaN → tf
    }
    _mm_storeu_ps(entry, tn);
    return _mm_movemask_ps(_mm_cmple_ps(tn, tf));
}
#endif

#if defined(__AVX2__)
/// Eight boxes' entry (the largest of the near distances t0 and t_min) and exit (the least of
/// the far ones t1 and t_max), taken on the distances' bits as integers (see hit_wide()).
inline __m256i entry_as_ints(const __m256i (&t0)[3], float t_min) {
    return _mm256_max_epi32(_mm256_max_epi32(t0[0], t0[1]),
                            _mm256_max_epi32(t0[2], _mm256_castps_si256(_mm256_set1_ps(t_min))));
}
inline __m256i exit_as_ints(const __m256i (&t1)[3], float t_max) {
    return _mm256_min_epi32(_mm256_min_epi32(t1[0], t1[1]),
                            _mm256_min_epi32(t1[2], _mm256_castps_si256(_mm256_set1_ps(t_max))));
}
#endif

/// The W boxes of n against r over [t_min, t_max]: bit k set if child k is hit, its entry
/// distance in entry[k]. Per lane the very arithmetic of hit_node(): the same hits and entries
/// (a NaN from 0·∞ loses in max/min against the running interval, which it leaves as it is).
template <int W>
inline int hit_wide(const WideBvhNode<W>& n, const WideRay<W>& r, float t_min, float t_max,
                    float* entry) {
    const char* base = reinterpret_cast<const char*>(&n);
#if defined(__AVX2__) && defined(__FMA__)
    // The padded test (WideRay::padded): t = plane·inv + c in one rounding, the near planes'
    // distances lowered and the far ones' raised past any rounding, so that it hits at least
    // the children the exact test below hits, at entries no later. As there, maxima and
    // minima on the bits as integers; the comparison too: the entry is ≥ 0 and no distance
    // is −0 or NaN (m > 0), so tn > tf as integers exactly when as floats.
    if constexpr (W == 8) {
        if (r.padded) {
            __m256i t0[3], t1[3];
            for (int a = 0; a < 3; ++a) {
                const __m256 near_plane =
                    _mm256_load_ps(reinterpret_cast<const float*>(base + r.near_at[a]));
                const __m256 far_plane =
                    _mm256_load_ps(reinterpret_cast<const float*>(base + r.far_at[a]));
                t0[a] = _mm256_castps_si256(_mm256_fmadd_ps(near_plane, r.inv[a], r.c_near[a]));
                t1[a] = _mm256_castps_si256(_mm256_fmadd_ps(far_plane, r.inv[a], r.c_far[a]));
            }
            const __m256i tn = entry_as_ints(t0, t_min), tf = exit_as_ints(t1, t_max);
            _mm256_storeu_ps(entry, _mm256_castsi256_ps(tn));
            return ~_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpgt_epi32(tn, tf))) & 0xFF;
        }
    }
#endif
#if defined(__AVX2__)
    // No NaN and an entry ≥ 0 (WideRay::as_ints): a float's bits ordered as an integer order
    // non-negative floats as floats do, and put every negative one below them. The entry, a
    // maximum with t_min ≥ 0, is then the float maximum; the exit, a minimum (its −0s made
    // +0 first), is the float minimum whenever that is ≥ 0, else some negative distance: a
    // miss either way in the float comparison that follows.
    if constexpr (W == 8) {
        if (r.as_ints) {
            const __m256 scale = _mm256_set1_ps(kExitScale);
            const __m256i negative_zero = _mm256_set1_epi32(INT32_MIN);
            __m256i t0[3], t1[3];
            for (int a = 0; a < 3; ++a) {
                const __m256 near_plane =
                    _mm256_load_ps(reinterpret_cast<const float*>(base + r.near_at[a]));
                const __m256 far_plane =
                    _mm256_load_ps(reinterpret_cast<const float*>(base + r.far_at[a]));
                t0[a] =
                    _mm256_castps_si256(_mm256_mul_ps(_mm256_sub_ps(near_plane, r.o[a]), r.inv[a]));
                t1[a] = _mm256_castps_si256(_mm256_mul_ps(
                    _mm256_mul_ps(_mm256_sub_ps(far_plane, r.o[a]), r.inv[a]), scale));
                // −0 (the origin on a far plane) is the least integer: make it +0
                t1[a] = _mm256_andnot_si256(_mm256_cmpeq_epi32(t1[a], negative_zero), t1[a]);
            }
            const __m256i tn = entry_as_ints(t0, t_min), tf = exit_as_ints(t1, t_max);
            _mm256_storeu_ps(entry, _mm256_castsi256_ps(tn));
            return _mm256_movemask_ps(
                _mm256_cmp_ps(_mm256_castsi256_ps(tn), _mm256_castsi256_ps(tf), _CMP_LE_OQ));
        }
    }
#endif
#if defined(__AVX__)
    if constexpr (W == 8) {
        __m256 tn = _mm256_set1_ps(t_min), tf = _mm256_set1_ps(t_max);
        const __m256 scale = _mm256_set1_ps(kExitScale);
        for (int a = 0; a < 3; ++a) {
            const __m256 near_plane =
                _mm256_load_ps(reinterpret_cast<const float*>(base + r.near_at[a]));
            const __m256 far_plane =
                _mm256_load_ps(reinterpret_cast<const float*>(base + r.far_at[a]));
            const __m256 t0 = _mm256_mul_ps(_mm256_sub_ps(near_plane, r.o[a]), r.inv[a]);
            const __m256 t1 =
                _mm256_mul_ps(_mm256_mul_ps(_mm256_sub_ps(far_plane, r.o[a]), r.inv[a]), scale);
            tn = _mm256_max_ps(t0, tn);  // NaN → tn
            tf = _mm256_min_ps(t1, tf);  // NaN → tf
        }
        _mm256_storeu_ps(entry, tn);
        return _mm256_movemask_ps(_mm256_cmp_ps(tn, tf, _CMP_LE_OQ));
    }
#endif
#if defined(__SSE2__)
    if constexpr (W == 4) {
        return hit_lanes4(base, r, t_min, t_max, entry, 0);
    } else {
        return hit_lanes4(base, r, t_min, t_max, entry, 0) |
               (hit_lanes4(base, r, t_min, t_max, entry + 4, 16) << 4);
    }
#else
    int mask = 0;
    for (int k = 0; k < W; ++k) {
        float tn = t_min, tf = t_max;
        for (int a = 0; a < 3; ++a) {
            const float near_plane = reinterpret_cast<const float*>(base + r.near_at[a])[k];
            const float far_plane = reinterpret_cast<const float*>(base + r.far_at[a])[k];
            const float t0 = (near_plane - r.os[a]) * r.invs[a];
            const float t1 = (far_plane - r.os[a]) * r.invs[a] * kExitScale;
            tn = t0 > tn ? t0 : tn;
            tf = t1 < tf ? t1 : tf;
        }
        entry[k] = tn;
        if (tn <= tf) mask |= 1 << k;
    }
    return mask;
#endif
}

/// Asks for the cache lines of node n, about to be visited.
template <class Node>
inline void prefetch_node(const Node* n) {
    const char* p = reinterpret_cast<const char*>(n);
    for (size_t line = 0; line < sizeof(Node); line += 64) __builtin_prefetch(p + line);
}

/// Orders m ≤ 8 hit children farthest first (insertion sort by key(child)): the traversals
/// push all but the last and visit the last, the nearest, now.
template <class Entry, class Key>
inline void sort_farthest_first(Entry* h, int m, Key&& key) {
    for (int i = 1; i < m; ++i) {
        for (int j = i; j > 0 && key(h[j - 1]) < key(h[j]); --j) {
            const Entry s = h[j];
            h[j] = h[j - 1];
            h[j - 1] = s;
        }
    }
}

}  // namespace bvh_detail

template <int W>
template <class Test>
void WideBvh<W>::nearest_leaves(const Ray& r, float t_min, float& t_max, uint64_t& box_tests,
                                Test&& test) const {
    using namespace bvh_detail;
    if (nodes_.empty()) return;
    const Node* nodes = nodes_.data();
    struct Entry {
        uint32_t child, count;  // a node (count 0) or a leaf range
        float entry;
    };
    Entry stack[kStack];
    int top = 0;
    const WideRay<W> wr(r, t_min, reach_);
    uint64_t visits = 0;  // counted here, added to box_tests at the end (not through memory)
    Entry cur{0, 0, t_min};
    for (;;) {
        if (cur.count > 0) {
            test(cur.child, cur.count, t_max);
        } else {
            const Node& n = nodes[cur.child];
            float e[W];
            ++visits;
            unsigned mask = static_cast<unsigned>(hit_wide<W>(n, wr, t_min, with_margin(t_max), e));
            if (mask != 0) {
                // one hit: go there; two: the nearer now, the farther later; more: sorted
                const int k0 = __builtin_ctz(mask);
                mask &= mask - 1;
                if (mask == 0) {
                    cur = {n.child[k0], n.count[k0], e[k0]};
                    continue;
                }
                const int k1 = __builtin_ctz(mask);
                mask &= mask - 1;
                if (mask == 0) {
                    const bool swap = e[k1] < e[k0];
                    const int near = swap ? k1 : k0, far = swap ? k0 : k1;
                    stack[top++] = {n.child[far], n.count[far], e[far]};
                    if (n.count[far] == 0) prefetch_node(nodes + n.child[far]);
                    cur = {n.child[near], n.count[near], e[near]};
                    continue;
                }
                Entry h[W];
                h[0] = {n.child[k0], n.count[k0], e[k0]};
                h[1] = {n.child[k1], n.count[k1], e[k1]};
                int m = 2;
                do {
                    const int k = __builtin_ctz(mask);
                    h[m++] = {n.child[k], n.count[k], e[k]};
                    mask &= mask - 1;
                } while (mask != 0);
                // farthest first onto the stack, the nearest now
                sort_farthest_first(h, m, [](const Entry& x) { return x.entry; });
                for (int i = 0; i + 1 < m; ++i) {
                    stack[top++] = h[i];
                    if (h[i].count == 0) prefetch_node(nodes + h[i].child);
                }
                cur = h[m - 1];
                continue;
            }
        }
        // next entry from the stack, skipping those entered beyond the nearest hit so far
        for (;;) {
            if (top == 0) {
                box_tests += W * visits;
                return;
            }
            const Entry& s = stack[--top];
            if (s.entry <= with_margin(t_max)) {
                cur = s;
                break;
            }
        }
    }
}

template <int W>
template <class Visit>
bool WideBvh<W>::any_leaves(const Ray& r, float t_min, float t_max, uint64_t& box_tests,
                            Visit&& visit) const {
    using namespace bvh_detail;
    if (nodes_.empty()) return false;
    const Node* nodes = nodes_.data();
    struct Entry {
        uint32_t child, count;
    };
    Entry stack[kStack];
    int top = 0;
    const WideRay<W> wr(r, t_min, reach_);
    const float limit = with_margin(t_max);
    uint64_t visits = 0;  // as in nearest_leaves()
    Entry cur{0, 0};
    for (;;) {
        if (cur.count > 0) {
            if (visit(cur.child, cur.count)) {
                box_tests += W * visits;
                return true;
            }
        } else {
            const Node& n = nodes[cur.child];
            float e[W];
            ++visits;
            unsigned mask = static_cast<unsigned>(hit_wide<W>(n, wr, t_min, limit, e));
            if (mask != 0) {
                int k = __builtin_ctz(mask);
                cur = {n.child[k], n.count[k]};
                for (mask &= mask - 1; mask != 0; mask &= mask - 1) {
                    k = __builtin_ctz(mask);
                    stack[top++] = {n.child[k], n.count[k]};
                }
                continue;
            }
        }
        if (top == 0) {
            box_tests += W * visits;
            return false;
        }
        cur = stack[--top];
    }
}

extern template class WideBvh<8>;

}  // namespace luz
