// Bvh4: the binary Bvh (bvh.h) collapsed into a 4-wide tree whose nodes hold their four child
// boxes side by side (structure of arrays), so that one SIMD slab test checks all four: half
// the depth, a quarter of the node visits, and every box of a visit in two cache lines. Same
// leaves, same order(), same traversal contract as Bvh (nearest and any with slot callbacks).
//
//     const Bvh4 bvh = Bvh4::build(boxes);  // or Bvh4(Bvh::build(boxes))
//     bvh.nearest(ray, 0.0f, t_max, box_tests, [&](uint32_t slot, float& t_max) { ... });
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "geometry/bvh.h"

namespace luz {

/// 128 bytes: four child boxes by axis (lo[axis][child], hi[axis][child]); child k is a node
/// (count[k] = 0, child[k] its index), a leaf (count[k] > 0 primitives from slot child[k] of
/// order()), or unused (count[k] = 0, child[k] = kUnused, an empty box that no ray meets).
struct alignas(64) Bvh4Node {
    float lo[3][4];
    float hi[3][4];
    uint32_t child[4];
    uint32_t count[4];

    static constexpr uint32_t kUnused = 0xFFFFFFFFu;
};
static_assert(sizeof(Bvh4Node) == 128);

class Bvh4 {
  public:
    Bvh4() = default;
    /// Collapses a binary BVH (taking its leaf order): each 4-wide node gathers up to four
    /// descendants of a binary node, opening the largest (by surface area) interior one first.
    explicit Bvh4(Bvh&& binary);
    /// Bvh4(Bvh::build(bounds, options)).
    static Bvh4 build(std::span<const Bounds3> bounds, const BvhOptions& options = {}) {
        return Bvh4(Bvh::build(bounds, options));
    }

    bool empty() const { return nodes_.empty(); }
    const std::vector<Bvh4Node>& nodes() const { return nodes_; }
    /// Primitive ids in leaf order, as Bvh::order().
    const std::vector<uint32_t>& order() const { return order_; }
    /// Bytes held by the nodes and the order.
    size_t memory_bytes() const {
        return nodes_.capacity() * sizeof(Bvh4Node) + order_.capacity() * sizeof(uint32_t);
    }

    /// As Bvh::nearest(): test(slot, t_max) for every slot of every leaf whose box r meets
    /// before t_max (with the same margin), children visited nearest first; each node visit
    /// adds 4 to box_tests.
    template <class Test>
    void nearest(const Ray& r, float t_min, float& t_max, uint64_t& box_tests, Test&& test) const;

    /// As Bvh::any(): visit(slot) for every slot of every leaf whose box r meets, until it
    /// returns true; returns whether it did.
    template <class Visit>
    bool any(const Ray& r, float t_min, float t_max, uint64_t& box_tests, Visit&& visit) const;

  private:
    static constexpr int kStack = 3 * Bvh::kMaxDepth + 4;  // ≤ 3 pushes per level
    std::vector<Bvh4Node> nodes_;
    std::vector<uint32_t> order_;
};

namespace bvh_detail {

/// A ray prepared for the four-box test: per axis the origin, 1/direction (SIMD lanes alike)
/// and where in a node its near and far planes are (hi for a negative 1/direction, else lo).
struct WideRay {
#if defined(__SSE2__)
    __m128 o[3], inv[3];
#else
    float o[3], inv[3];
#endif
    uint32_t near_at[3], far_at[3];  // byte offsets in Bvh4Node

    explicit WideRay(const Ray& r) {
        for (int a = 0; a < 3; ++a) {
            const float inv_a = 1.0f / r.direction[a];
#if defined(__SSE2__)
            o[a] = _mm_set1_ps(r.origin[a]);
            inv[a] = _mm_set1_ps(inv_a);
#else
            o[a] = r.origin[a];
            inv[a] = inv_a;
#endif
            const uint32_t lo = static_cast<uint32_t>(a * 16);
            const uint32_t hi = static_cast<uint32_t>(48 + a * 16);
            const bool negative = std::signbit(inv_a);  // −∞ for a −0 component
            near_at[a] = negative ? hi : lo;
            far_at[a] = negative ? lo : hi;
        }
    }
};

/// The four boxes of n against r over [t_min, t_max]: bit k set if child k is hit, its entry
/// distance in entry[k]. Per lane the very arithmetic of hit_node(): the same hits and entries
/// (a NaN from 0·∞ loses in max/min against the running interval, which it leaves as it is).
inline int hit_four(const Bvh4Node& n, const WideRay& r, float t_min, float t_max, float* entry) {
    const char* base = reinterpret_cast<const char*>(&n);
#if defined(__SSE2__)
    __m128 tn = _mm_set1_ps(t_min), tf = _mm_set1_ps(t_max);
    const __m128 scale = _mm_set1_ps(kExitScale);
    for (int a = 0; a < 3; ++a) {
        const __m128 near_plane = _mm_load_ps(reinterpret_cast<const float*>(base + r.near_at[a]));
        const __m128 far_plane = _mm_load_ps(reinterpret_cast<const float*>(base + r.far_at[a]));
        const __m128 t0 = _mm_mul_ps(_mm_sub_ps(near_plane, r.o[a]), r.inv[a]);
        const __m128 t1 = _mm_mul_ps(_mm_mul_ps(_mm_sub_ps(far_plane, r.o[a]), r.inv[a]), scale);
        tn = _mm_max_ps(t0, tn);  // NaN → tn
        tf = _mm_min_ps(t1, tf);  // NaN → tf
    }
    _mm_storeu_ps(entry, tn);
    return _mm_movemask_ps(_mm_cmple_ps(tn, tf));
#else
    int mask = 0;
    for (int k = 0; k < 4; ++k) {
        float tn = t_min, tf = t_max;
        for (int a = 0; a < 3; ++a) {
            const float near_plane = reinterpret_cast<const float*>(base + r.near_at[a])[k];
            const float far_plane = reinterpret_cast<const float*>(base + r.far_at[a])[k];
            const float t0 = (near_plane - r.o[a]) * r.inv[a];
            const float t1 = (far_plane - r.o[a]) * r.inv[a] * kExitScale;
            tn = t0 > tn ? t0 : tn;
            tf = t1 < tf ? t1 : tf;
        }
        entry[k] = tn;
        if (tn <= tf) mask |= 1 << k;
    }
    return mask;
#endif
}

}  // namespace bvh_detail

template <class Test>
void Bvh4::nearest(const Ray& r, float t_min, float& t_max, uint64_t& box_tests,
                   Test&& test) const {
    using namespace bvh_detail;
    if (nodes_.empty()) return;
    const Bvh4Node* nodes = nodes_.data();
    struct Entry {
        uint32_t child, count;  // a node (count 0) or a leaf range
        float entry;
    };
    Entry stack[kStack];
    int top = 0;
    const WideRay wr(r);
    Entry cur{0, 0, t_min};
    for (;;) {
        if (cur.count > 0) {
            for (uint32_t i = cur.child, end = cur.child + cur.count; i < end; ++i) test(i, t_max);
        } else {
            const Bvh4Node& n = nodes[cur.child];
            float e[4];
            box_tests += 4;
            int mask = hit_four(n, wr, t_min, with_margin(t_max), e);
            if (mask != 0) {
                // one hit: go there; two: the nearer now, the farther later; more: sorted
                const int k0 = __builtin_ctz(static_cast<unsigned>(mask));
                mask &= mask - 1;
                if (mask == 0) {
                    cur = {n.child[k0], n.count[k0], e[k0]};
                    continue;
                }
                const int k1 = __builtin_ctz(static_cast<unsigned>(mask));
                mask &= mask - 1;
                if (mask == 0) {
                    const bool swap = e[k1] < e[k0];
                    const int near = swap ? k1 : k0, far = swap ? k0 : k1;
                    stack[top++] = {n.child[far], n.count[far], e[far]};
                    cur = {n.child[near], n.count[near], e[near]};
                    continue;
                }
                Entry h[4] = {{n.child[k0], n.count[k0], e[k0]}, {n.child[k1], n.count[k1], e[k1]}};
                int m = 2;
                do {
                    const int k = __builtin_ctz(static_cast<unsigned>(mask));
                    h[m++] = {n.child[k], n.count[k], e[k]};
                    mask &= mask - 1;
                } while (mask != 0);
                // farthest first onto the stack (insertion sort, m ≤ 4), the nearest now
                for (int i = 1; i < m; ++i) {
                    for (int j = i; j > 0 && h[j - 1].entry < h[j].entry; --j) {
                        const Entry t = h[j];
                        h[j] = h[j - 1];
                        h[j - 1] = t;
                    }
                }
                for (int i = 0; i + 1 < m; ++i) stack[top++] = h[i];
                cur = h[m - 1];
                continue;
            }
        }
        // next entry from the stack, skipping those entered beyond the nearest hit so far
        for (;;) {
            if (top == 0) return;
            const Entry& s = stack[--top];
            if (s.entry <= with_margin(t_max)) {
                cur = s;
                break;
            }
        }
    }
}

template <class Visit>
bool Bvh4::any(const Ray& r, float t_min, float t_max, uint64_t& box_tests, Visit&& visit) const {
    using namespace bvh_detail;
    if (nodes_.empty()) return false;
    const Bvh4Node* nodes = nodes_.data();
    struct Entry {
        uint32_t child, count;
    };
    Entry stack[kStack];
    int top = 0;
    const WideRay wr(r);
    const float limit = with_margin(t_max);
    Entry cur{0, 0};
    for (;;) {
        if (cur.count > 0) {
            for (uint32_t i = cur.child, end = cur.child + cur.count; i < end; ++i)
                if (visit(i)) return true;
        } else {
            const Bvh4Node& n = nodes[cur.child];
            float e[4];
            box_tests += 4;
            int mask = hit_four(n, wr, t_min, limit, e);
            if (mask != 0) {
                int k = __builtin_ctz(static_cast<unsigned>(mask));
                cur = {n.child[k], n.count[k]};
                for (mask &= mask - 1; mask != 0; mask &= mask - 1) {
                    k = __builtin_ctz(static_cast<unsigned>(mask));
                    stack[top++] = {n.child[k], n.count[k]};
                }
                continue;
            }
        }
        if (top == 0) return false;
        cur = stack[--top];
    }
}

}  // namespace luz
