// WideBvh<W> (Bvh8; Bvh4 in the tests): the binary Bvh collapsed into W-wide nodes holding their
// child boxes side by side, tested by one SIMD slab test: fewer levels and node visits. Same
// leaves, order() and traversal contract as Bvh (nearest and any with slot callbacks).
//
//     const Bvh8 bvh = Bvh8::build(boxes);  // or Bvh8(Bvh::build(boxes))
//     bvh.nearest(ray, 0.0f, t_max, box_tests, [&](uint32_t slot, float& t_max) { ... });
//
// The node and its slab test: wide_bvh_node.h (eight boxes at once with AVX, else two halves).
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "geometry/bvh.h"
#include "geometry/wide_bvh_node.h"
#include "math/huge_pages.h"

namespace luz {

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
    /// blocks of four, geometry/prim_block.h); `count` is passed by reference, for an owner
    /// that leaves some out (never all). order() no longer applies.
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

/// Asks for the cache lines of node n, about to be visited.
template <class Node>
inline void prefetch_node(const Node* n) {
    const char* p = reinterpret_cast<const char*>(n);
    for (size_t line = 0; line < sizeof(Node); line += 64) __builtin_prefetch(p + line);
}

/// Orders a and b farther first: swaps them when a's key is lower than b's. Without a branch:
/// which of two neighbouring children is farther is a coin toss to a branch predictor.
template <class Entry, class Key>
[[gnu::always_inline]] inline void farther_first(Entry& a, Entry& b, Key&& key) {
    const bool swap = key(a) < key(b);
    const Entry x = swap ? b : a, y = swap ? a : b;
    a = x;
    b = y;
}

/// Orders m ≤ 8 hit children farthest first (by key(child)): three or four by a network of
/// compare-exchanges, more by insertion sort. The traversals push all but the last and visit
/// the last, the nearest, now.
template <class Entry, class Key>
inline void sort_farthest_first(Entry* h, int m, Key&& key) {
    if (m == 3) {
        farther_first(h[0], h[1], key);
        farther_first(h[1], h[2], key);
        farther_first(h[0], h[1], key);
        return;
    }
    if (m == 4) {
        farther_first(h[0], h[1], key);
        farther_first(h[2], h[3], key);
        farther_first(h[0], h[2], key);
        farther_first(h[1], h[3], key);
        farther_first(h[1], h[2], key);
        return;
    }
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
