// Bvh: a binary BVH over any primitives' bounds — parallel binned SAH build, 32-byte nodes depth
// first — which the renderer collapses to a WideBvh (wide_bvh.h) and traverses only there. Slot i
// of a leaf holds primitive order()[i]; the scene's BVH (geometry/scene.h, a Bvh8) keeps its
// primitives in blocks of four, leaf by leaf (geometry/prim_block.h), so slot i is lane i % 4 of
// block i / 4. The binary tree's own traversals are the tests' reference (tests/geometry/
// bvh_reference.h).
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "math/bounds.h"
#include "math/huge_pages.h"
#include "math/ray.h"

namespace luz {

/// 32 bytes: the box, and either a leaf's primitive range or an interior node's second child
/// (the first child is the next node). Aligned so that no node straddles two cache lines.
struct alignas(32) BvhNode {
    float lo[3];
    uint32_t offset;  ///< leaf: first slot in Bvh::order(); interior: index of the second child
    float hi[3];
    uint32_t count;  ///< leaf: number of primitives (> 0); interior: 0

    bool leaf() const { return count > 0; }
};
static_assert(sizeof(BvhNode) == 32);

/// Build settings: SAH costs (a node visit costs `traversal_cost` primitive tests), bins per
/// axis, and the leaf size above which a node is always split (if its primitives can be).
/// With leaf_block > 1 the SAH counts a leaf's primitives in blocks of that many, tested at
/// once (a node visit then costs `traversal_cost` block tests).
struct BvhOptions {
    int bins = 16;
    float traversal_cost = 1.0f;
    uint32_t max_leaf_size = 8;
    uint32_t leaf_block = 1;
    /// When not empty (then one per primitive), kinds[i] is primitive i's kind, and a leaf holds
    /// one kind only: a node the SAH would make a leaf of several kinds is split by kind, those
    /// up to the middle of its kinds' range first (two kinds: one level; at most 8 for 256).
    std::span<const uint8_t> kinds;
};

class Bvh {
  public:
    /// Builds over primitives 0 … bounds.size()−1. Primitives with empty bounds cannot be hit
    /// and are left out. Split by binned SAH over the centroids on all three axes; a node whose
    /// centroids all coincide becomes a leaf (one per kind, with kinds); beyond depth 48 nodes
    /// split at the median. Throws std::invalid_argument if kinds is neither empty nor of
    /// bounds' size.
    static Bvh build(std::span<const Bounds3> bounds, const BvhOptions& options = {});

    bool empty() const { return nodes_.empty(); }
    const HugeVector<BvhNode>& nodes() const { return nodes_; }
    /// Primitive ids in leaf order: a leaf holds order()[offset … offset + count − 1].
    const HugeVector<uint32_t>& order() const { return order_; }
    /// Bytes held by the nodes and the order.
    size_t memory_bytes() const {
        return nodes_.capacity() * sizeof(BvhNode) + order_.capacity() * sizeof(uint32_t);
    }

    static constexpr int kMaxDepth = 96;  ///< traversal stack size (build depth stays below)

  private:
    template <int W>
    friend class WideBvh;        // takes the order when collapsing (wide_bvh.h)
    HugeVector<BvhNode> nodes_;  // on huge pages when large (math/huge_pages.h)
    HugeVector<uint32_t> order_;
};

namespace bvh_detail {

/// 1 + 2γ₃ (γₙ = nε/(1 − nε), ε = 2⁻²⁴): scaling a slab's exit distance by it makes the test
/// conservative despite rounding (Ize, "Robust BVH Ray Traversal", JCGT 2013; pbrt).
inline constexpr float kExitScale = 1.0f + 2.0f * (3.0f * 0x1p-24f) / (1.0f - 3.0f * 0x1p-24f);

/// t_max with the margin within which nodes are still visited (ties between primitives).
inline float with_margin(float t_max) { return t_max + t_max * 0x1p-16f; }

}  // namespace bvh_detail

}  // namespace luz
