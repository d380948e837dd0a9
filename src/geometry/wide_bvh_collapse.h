// WideBvh<W> from a binary Bvh: which binary nodes become wide nodes is chosen by the SAH,
// optimally (dynamic programming over the binary tree); then two passes (subtree sizes, then
// nodes in place), the top levels' subtrees as parallel tasks: the same tree for any threads.
// A header so that a test may instantiate another width (tests/geometry/bvh_reference.cpp).
#pragma once

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include "geometry/wide_bvh.h"

namespace luz {

namespace wide_bvh_detail {

inline float half_area(const BvhNode& n) {
    const float dx = n.hi[0] - n.lo[0], dy = n.hi[1] - n.lo[1], dz = n.hi[2] - n.lo[2];
    return dx * dy + dy * dz + dz * dx;
}

template <int W>
class Collapser {
  public:
    explicit Collapser(const HugeVector<BvhNode>& binary)
        : binary_(binary),
          size_(binary.size(), 0),
          decision_(make_huge_array<uint32_t>(binary.size())),
          parallel_depth_(binary.size() < kParallelFrom ? 0 : kParallelDepth),
          solve_parallel_depth_(binary.size() < kSolveParallelFrom ? 0 : kSolveParallelDepth) {
        static_assert(W <= 8, "decision_ holds 4 bits for each slot count 2 … W");
        solve(0, 0);
    }

    /// The number of wide nodes under (and including) the one of binary node b; remembered.
    uint32_t count(uint32_t b, int depth) {
        uint32_t kids[W];
        const int k = gather(b, kids);
        uint32_t sizes[W] = {};
        const auto one = [&](int j) {
            if (!binary_[kids[j]].leaf()) sizes[j] = count(kids[j], depth + 1);
        };
        if (depth < parallel_depth_) {
            tbb::parallel_for(0, k, one);
        } else {
            for (int j = 0; j < k; ++j) one(j);
        }
        uint32_t total = 1;
        for (int j = 0; j < k; ++j) total += sizes[j];
        size_[b] = total;
        return total;
    }

    /// Writes the wide subtree of binary node b at wide[index …] (depth first).
    void fill(uint32_t b, uint32_t index, int depth, WideBvhNode<W>* wide) const {
        uint32_t kids[W];
        const int k = gather(b, kids);
        WideBvhNode<W>& node = wide[index];
        uint32_t at[W];
        uint32_t next = index + 1;
        for (int j = 0; j < W; ++j) {
            for (int a = 0; a < 3; ++a) {
                node.lo[a][j] = std::numeric_limits<float>::infinity();
                node.hi[a][j] = -std::numeric_limits<float>::infinity();
            }
            node.child[j] = WideBvhNode<W>::kUnused;
            node.count[j] = 0;
            if (j >= k) continue;
            const BvhNode& n = binary_[kids[j]];
            for (int a = 0; a < 3; ++a) {
                node.lo[a][j] = n.lo[a];
                node.hi[a][j] = n.hi[a];
            }
            if (n.leaf()) {
                node.child[j] = n.offset;
                node.count[j] = n.count;
            } else {
                node.child[j] = at[j] = next;
                next += size_[kids[j]];
            }
        }
        const auto one = [&](int j) {
            if (!binary_[kids[j]].leaf()) fill(kids[j], at[j], depth + 1, wide);
        };
        if (depth < parallel_depth_) {
            tbb::parallel_for(0, k, one);
        } else {
            for (int j = 0; j < k; ++j) one(j);
        }
    }

  private:
    static constexpr int kParallelDepth = 2;       // wide levels whose subtrees are separate tasks
    static constexpr size_t kParallelFrom = 1024;  // smaller binary trees: one task
    static constexpr int kSolveParallelDepth = 6;  // binary levels of parallel solve()
    static constexpr size_t kSolveParallelFrom = 65536;  // smaller binary trees: one task

    /// The children of binary node b's wide node (b itself for a leaf root), left to right:
    /// binary nodes below b opened as the SAH-optimal collapse says.
    int gather(uint32_t b, uint32_t* kids) const {
        int k = 0;
        if (binary_[b].leaf()) {
            kids[k++] = b;
        } else {
            open(b, W, kids, k);
        }
        return k;
    }

    // The SAH of a wide BVH over fixed leaves is Σ area(wide node): a ray meets a node's box
    // with a probability proportional to its area and then tests its W child boxes at once.
    // A binary interior node either becomes a wide node or is opened in its wide parent (its
    // two children take its slot and one more). solve(b) gives the least SAH of binary node
    // b's subtree when b may use s slots of its wide parent, s = 1 … W (s = 1: b is a wide
    // node or a leaf; a leaf costs 0, as it costs the same in any collapse), and keeps the
    // choices that reach it in decision_.

    /// Fills decision_ for the subtree of b; returns b's costs (cost[s − 1] for s slots). The
    /// two subtrees are parallel tasks near the root of a large tree (each result depends
    /// only on the subtree: the same for any threads).
    std::array<float, W> solve(uint32_t b, int depth) {
        std::array<float, W> c{};
        const BvhNode& n = binary_[b];
        if (n.leaf()) {
            decision_[b] = 0;
            return c;
        }
        std::array<float, W> l, r;
        if (depth < solve_parallel_depth_) {
            tbb::parallel_invoke([&] { l = solve(b + 1, depth + 1); },
                                 [&] { r = solve(n.offset, depth + 1); });
        } else {
            l = solve(b + 1, depth + 1);
            r = solve(n.offset, depth + 1);
        }
        // d[s]: the least cost of the children sharing s ≥ 2 slots, the first child given
        // left[s] = j of 1 … s − 1 (the fewest among equal costs). Two leaves: 0, j = 1.
        float d[W + 1];
        int left[W + 1];
        const bool two_leaves = binary_[b + 1].leaf() && binary_[n.offset].leaf();
        for (int s = 2; s <= W; ++s) {
            float best = l[0] + r[s - 2];
            int at = 1;
            for (int j = 2; j < s && !two_leaves; ++j) {  // branch-free: costs compare at random
                const float v = l[j - 1] + r[s - j - 1];
                at = v < best ? j : at;
                best = v < best ? v : best;
            }
            d[s] = best;
            left[s] = at;
        }
        const float root = half_area(n) + d[W];
        c[0] = root;
        uint32_t decision = 0;
        for (int s = 2; s <= W; ++s) {
            c[s - 1] = d[s] < root ? d[s] : root;
            // opened if that costs no more than making b a wide node
            const uint32_t open = d[s] <= root ? 8u : 0u;
            decision |= (static_cast<uint32_t>(left[s]) | open) << (4 * (s - 2));
        }
        decision_[b] = decision;
        return c;
    }

    /// decision_[b] for s slots: the first child's slots (bits 0–2) and whether b is opened
    /// when given s slots (bit 3).
    uint32_t decision(uint32_t b, int s) const { return decision_[b] >> (4 * (s - 2)) & 15u; }

    /// Appends to kids the children of interior node b opened with s slots.
    void open(uint32_t b, int s, uint32_t* kids, int& k) const {
        const int j = static_cast<int>(decision(b, s) & 7u);
        place(b + 1, j, kids, k);
        place(binary_[b].offset, s - j, kids, k);
    }

    /// Node c given s slots: opened if that costs no more than making it a wide node.
    void place(uint32_t c, int s, uint32_t* kids, int& k) const {
        if (s >= 2 && !binary_[c].leaf() && (decision(c, s) & 8u)) {
            open(c, s, kids, k);
        } else {
            kids[k++] = c;
        }
    }

    const HugeVector<BvhNode>& binary_;
    HugeVector<uint32_t> size_;     // per binary node that roots a wide node: its subtree's size
    HugeArray<uint32_t> decision_;  // per binary node: split and opened (decision())
    int parallel_depth_;            // wide levels whose subtrees are separate tasks
    int solve_parallel_depth_;      // binary levels whose subtrees are separate solve() tasks
};

}  // namespace wide_bvh_detail

template <int W>
WideBvh<W>::WideBvh(Bvh&& binary) : order_(std::move(binary.order_)) {
    if (binary.nodes_.empty()) return;
    const BvhNode& root = binary.nodes_[0];
    reach_ = 0.0f;
    for (int a = 0; a < 3; ++a)
        reach_ = std::max({reach_, std::fabs(root.lo[a]), std::fabs(root.hi[a])});
    wide_bvh_detail::Collapser<W> collapser(binary.nodes_);
    nodes_.resize(collapser.count(0, 0));
    collapser.fill(0, 0, 0, nodes_.data());
    binary.nodes_ = {};
}

}  // namespace luz
