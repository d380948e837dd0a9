// The tests' reference trees: the binary Bvh with its own nearest and any traversals (near child
// first, SIMD box test equal to the scalar slab test), and Bvh4, a 4-wide collapse; the renderer
// uses neither (it traverses a Bvh8). bench/bvh_vs_embree times the binary traversal too.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <utility>

#include "geometry/bvh.h"
#include "geometry/wide_bvh.h"
#include "math/lanes.h"

namespace luz {

using Bvh4 = WideBvh<4>;
extern template class WideBvh<4>;  // instantiated in bvh_reference.cpp

/// A binary Bvh and its traversals.
class BinaryBvh {
  public:
    BinaryBvh() = default;
    explicit BinaryBvh(Bvh&& tree) : tree_(std::move(tree)) {}
    static BinaryBvh build(std::span<const Bounds3> bounds, const BvhOptions& options = {}) {
        return BinaryBvh(Bvh::build(bounds, options));
    }

    const Bvh& tree() const { return tree_; }
    bool empty() const { return tree_.empty(); }
    const HugeVector<BvhNode>& nodes() const { return tree_.nodes(); }
    const HugeVector<uint32_t>& order() const { return tree_.order(); }
    size_t memory_bytes() const { return tree_.memory_bytes(); }

    /// Nearest-hit traversal of r in (t_min, t_max). test(slot, t_max) is called for every
    /// slot of every leaf whose box r meets before t_max; it tests primitive order()[slot] and
    /// lowers t_max on a hit. Of two children the nearer (by entry distance) is visited first;
    /// a node entered beyond t_max (with a margin of 2^-16·t_max, so that ties are still
    /// found) is skipped. Ray–box tests are added to box_tests.
    template <class Test>
    void nearest(const Ray& r, float t_min, float& t_max, uint64_t& box_tests, Test&& test) const;

    /// Any-hit traversal of r in (t_min, t_max), in no particular order: visit(slot) is called
    /// for every slot of every leaf whose box r meets; it returns true to stop. Returns whether
    /// it was stopped.
    template <class Visit>
    bool any(const Ray& r, float t_min, float t_max, uint64_t& box_tests, Visit&& visit) const;

  private:
    Bvh tree_;
};

namespace bvh_detail {

/// A ray prepared for box tests: origin and 1/direction.
struct BoxRay {
    float o[3], inv[3];
    explicit BoxRay(const Ray& r) {
        for (int a = 0; a < 3; ++a) {
            o[a] = r.origin[a];
            inv[a] = 1.0f / r.direction[a];
        }
    }
};

/// Slab test of node n against r over [t_min, t_max]; the entry distance on a hit. A NaN
/// (origin on a slab plane of a zero direction component) leaves the interval as it is.
inline bool hit_node(const BvhNode& n, const BoxRay& r, float t_min, float t_max, float& entry) {
    for (int a = 0; a < 3; ++a) {
        float t0 = (n.lo[a] - r.o[a]) * r.inv[a];
        float t1 = (n.hi[a] - r.o[a]) * r.inv[a];
        if (t0 > t1) {
            const float s = t0;
            t0 = t1;
            t1 = s;
        }
        t1 *= kExitScale;
        t_min = t0 > t_min ? t0 : t_min;
        t_max = t1 < t_max ? t1 : t_max;
    }
    entry = t_min;
    return t_min <= t_max;
}

/// A ray prepared for box tests on four lanes (x, y, z in lanes 0–2). hit_box() gives the very
/// result of hit_node(): per axis the near plane is lo or hi by the sign of 1/direction, so
/// that t_near ≤ t_far without a swap; a NaN (0·∞) loses against t_min or t_max in max/min,
/// which leaves the interval as it is. Lane 3 of a node (offset, count) is replaced by −∞ and
/// +∞, so it never counts.
struct SimdRay {
    Lane4f o, inv;
    Lane4i sign;
    explicit SimdRay(const Ray& r) {
        o = Lane4f{r.origin.x, r.origin.y, r.origin.z, 0.0f};
        inv = Lane4f{1.0f / r.direction.x, 1.0f / r.direction.y, 1.0f / r.direction.z, 1.0f};
        // all ones where 1/direction is negative (sign bit set, −∞ for a −0 component)
        sign = (Lane4i)inv >> 31;
    }
};

/// hit_node() on four lanes (see SimdRay).
inline bool hit_box(const BvhNode& n, const SimdRay& r, float t_min, float t_max, float& entry) {
    constexpr float inf = std::numeric_limits<float>::infinity();
    const Lane4i xyz{-1, -1, -1, 0};
    const Lane4f lo = (Lane4f)(((Lane4i)load_lanes4(n.lo) & xyz) | (Lane4i)Lane4f{0, 0, 0, -inf});
    const Lane4f hi = (Lane4f)(((Lane4i)load_lanes4(n.hi) & xyz) | (Lane4i)Lane4f{0, 0, 0, inf});
    const Lane4f near_plane = lane_select(r.sign, hi, lo);
    const Lane4f far_plane = lane_select(r.sign, lo, hi);
    Lane4f tn = (near_plane - r.o) * r.inv;
    Lane4f tf = (far_plane - r.o) * r.inv * kExitScale;
    tn = greater_or_second(tn, lanes4(t_min));  // NaN → t_min
    tf = less_or_second(tf, lanes4(t_max));     // NaN → t_max
    tn = greater_or_second(tn, __builtin_shufflevector(tn, tn, 1, 0, 3, 2));
    tf = less_or_second(tf, __builtin_shufflevector(tf, tf, 1, 0, 3, 2));
    tn = greater_or_second(tn, __builtin_shufflevector(tn, tn, 2, 3, 0, 1));
    tf = less_or_second(tf, __builtin_shufflevector(tf, tf, 2, 3, 0, 1));
    entry = tn[0];
    return tn[0] <= tf[0];
}

/// Both children of an interior node: bit 0 set if a is hit, bit 1 if b is; their entry
/// distances in ea, eb (meaningful only when hit).
inline int hit_pair(const BvhNode& a, const BvhNode& b, const SimdRay& r, float t_min, float t_max,
                    float& ea, float& eb) {
    return (hit_box(a, r, t_min, t_max, ea) ? 1 : 0) | (hit_box(b, r, t_min, t_max, eb) ? 2 : 0);
}

}  // namespace bvh_detail

template <class Test>
void BinaryBvh::nearest(const Ray& r, float t_min, float& t_max, uint64_t& box_tests,
                        Test&& test) const {
    using namespace bvh_detail;
    if (tree_.empty()) return;
    const BvhNode* nodes = tree_.nodes().data();
    struct Entry {
        uint32_t node;
        float entry;
    };
    Entry stack[Bvh::kMaxDepth];
    int top = 0;
    const SimdRay sr(r);
    {
        float entry;
        ++box_tests;
        if (!hit_box(nodes[0], sr, t_min, with_margin(t_max), entry)) return;
    }
    uint32_t node = 0;
    for (;;) {
        const BvhNode& n = nodes[node];
        if (n.leaf()) {
            for (uint32_t i = n.offset, end = n.offset + n.count; i < end; ++i) test(i, t_max);
        } else {
            const uint32_t a = node + 1, b = n.offset;
            float ea, eb;
            box_tests += 2;
            const int hit = hit_pair(nodes[a], nodes[b], sr, t_min, with_margin(t_max), ea, eb);
            if (hit == 3) {
                // near child now, the far one later
                const bool b_first = eb < ea;
                stack[top++] = b_first ? Entry{a, ea} : Entry{b, eb};
                node = b_first ? b : a;
                continue;
            }
            if (hit) {
                node = hit == 1 ? a : b;
                continue;
            }
        }
        // next node from the stack, skipping those entered beyond the nearest hit so far
        for (;;) {
            if (top == 0) return;
            const Entry e = stack[--top];
            if (e.entry <= with_margin(t_max)) {
                node = e.node;
                break;
            }
        }
    }
}

template <class Visit>
bool BinaryBvh::any(const Ray& r, float t_min, float t_max, uint64_t& box_tests,
                    Visit&& visit) const {
    using namespace bvh_detail;
    if (tree_.empty()) return false;
    const BvhNode* nodes = tree_.nodes().data();
    uint32_t stack[Bvh::kMaxDepth];
    int top = 0;
    float ea, eb;
    const float limit = with_margin(t_max);
    const SimdRay sr(r);
    ++box_tests;
    if (!hit_box(nodes[0], sr, t_min, limit, ea)) return false;
    uint32_t node = 0;
    for (;;) {
        const BvhNode& n = nodes[node];
        if (n.leaf()) {
            for (uint32_t i = n.offset, end = n.offset + n.count; i < end; ++i)
                if (visit(i)) return true;
        } else {
            const uint32_t a = node + 1, b = n.offset;
            box_tests += 2;
            const int hit = hit_pair(nodes[a], nodes[b], sr, t_min, limit, ea, eb);
            if (hit == 3) {
                stack[top++] = b;
                node = a;
                continue;
            }
            if (hit) {
                node = hit == 1 ? a : b;
                continue;
            }
        }
        if (top == 0) return false;
        node = stack[--top];
    }
}

}  // namespace luz
