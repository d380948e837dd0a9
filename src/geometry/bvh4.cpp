// Bvh4 from a binary Bvh: each 4-wide node takes a binary interior node's children and opens
// the largest interior ones among them until it holds four; nodes laid out depth first.
#include "geometry/bvh4.h"

namespace luz {

namespace {

float half_area(const BvhNode& n) {
    const float dx = n.hi[0] - n.lo[0], dy = n.hi[1] - n.lo[1], dz = n.hi[2] - n.lo[2];
    return dx * dy + dy * dz + dz * dx;
}

class Collapser {
  public:
    Collapser(const std::vector<BvhNode>& binary, std::vector<Bvh4Node>& wide)
        : binary_(binary), wide_(wide) {}

    /// The 4-wide node of binary node b (interior, or a leaf at the root); returns its index.
    uint32_t collapse(uint32_t b) {
        const uint32_t index = static_cast<uint32_t>(wide_.size());
        wide_.emplace_back();
        uint32_t kids[4];
        int k = 0;
        if (binary_[b].leaf()) {
            kids[k++] = b;
        } else {
            kids[k++] = b + 1;
            kids[k++] = binary_[b].offset;
            while (k < 4) {  // open the largest interior child
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
        }
        Bvh4Node node{};
        for (int j = 0; j < 4; ++j) {
            for (int a = 0; a < 3; ++a) {
                node.lo[a][j] = std::numeric_limits<float>::infinity();
                node.hi[a][j] = -std::numeric_limits<float>::infinity();
            }
            node.child[j] = Bvh4Node::kUnused;
            node.count[j] = 0;
        }
        for (int j = 0; j < k; ++j) {
            const BvhNode& n = binary_[kids[j]];
            for (int a = 0; a < 3; ++a) {
                node.lo[a][j] = n.lo[a];
                node.hi[a][j] = n.hi[a];
            }
            if (n.leaf()) {
                node.child[j] = n.offset;
                node.count[j] = n.count;
            } else {
                node.child[j] = collapse(kids[j]);  // may move wide_: write the node after
            }
        }
        wide_[index] = node;
        return index;
    }

  private:
    const std::vector<BvhNode>& binary_;
    std::vector<Bvh4Node>& wide_;
};

}  // namespace

Bvh4::Bvh4(Bvh&& binary) : order_(std::move(binary.order_)) {
    if (binary.nodes_.empty()) return;
    nodes_.reserve(binary.nodes_.size() / 4 + 16);
    Collapser(binary.nodes_, nodes_).collapse(0);
    nodes_.shrink_to_fit();
    binary.nodes_ = {};
}

}  // namespace luz
