// WideBvh<W> from a binary Bvh: a wide node takes a binary node's children, opening the largest
// interior ones until it holds W; depth first. Two passes (subtree sizes, then nodes in place),
// the top levels' subtrees as parallel tasks: the same tree for any number of threads.
#include "geometry/wide_bvh.h"

#include <tbb/parallel_for.h>

namespace luz {

namespace {

float half_area(const BvhNode& n) {
    const float dx = n.hi[0] - n.lo[0], dy = n.hi[1] - n.lo[1], dz = n.hi[2] - n.lo[2];
    return dx * dy + dy * dz + dz * dx;
}

template <int W>
class Collapser {
  public:
    explicit Collapser(const std::vector<BvhNode>& binary)
        : binary_(binary), size_(binary.size(), 0) {}

    /// The number of wide nodes under (and including) the one of binary node b; remembered.
    uint32_t count(uint32_t b, int depth) {
        uint32_t kids[W];
        const int k = gather(b, kids);
        uint32_t sizes[W] = {};
        const auto one = [&](int j) {
            if (!binary_[kids[j]].leaf()) sizes[j] = count(kids[j], depth + 1);
        };
        if (depth < kParallelDepth) {
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
        if (depth < kParallelDepth) {
            tbb::parallel_for(0, k, one);
        } else {
            for (int j = 0; j < k; ++j) one(j);
        }
    }

  private:
    static constexpr int kParallelDepth = 2;  // wide levels whose subtrees are separate tasks

    /// The children of binary node b's wide node (b itself for a leaf root): b's two children,
    /// then the largest interior one (by surface area; the first of equals) opened until W.
    int gather(uint32_t b, uint32_t* kids) const {
        int k = 0;
        if (binary_[b].leaf()) {
            kids[k++] = b;
            return k;
        }
        kids[k++] = b + 1;
        kids[k++] = binary_[b].offset;
        while (k < W) {
            int open = -1;
            float largest = -1.0f;
            for (int i = 0; i < k; ++i) {
                const BvhNode& n = binary_[kids[i]];
                if (!n.leaf() && half_area(n) > largest) {
                    largest = half_area(n);
                    open = i;
                }
            }
            if (open < 0) break;
            const uint32_t c = kids[open];
            for (int i = k; i > open + 1; --i) kids[i] = kids[i - 1];
            kids[open] = c + 1;
            kids[open + 1] = binary_[c].offset;
            ++k;
        }
        return k;
    }

    const std::vector<BvhNode>& binary_;
    std::vector<uint32_t> size_;  // per binary node that roots a wide node: its subtree's size
};

}  // namespace

template <int W>
WideBvh<W>::WideBvh(Bvh&& binary) : order_(std::move(binary.order_)) {
    if (binary.nodes_.empty()) return;
    Collapser<W> collapser(binary.nodes_);
    nodes_.resize(collapser.count(0, 0));
    collapser.fill(0, 0, 0, nodes_.data());
    binary.nodes_ = {};
}

template class WideBvh<4>;
template class WideBvh<8>;

}  // namespace luz
