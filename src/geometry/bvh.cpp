// Bvh::build: top-down binned SAH (Wald, "On fast construction of SAH-based bounding volume
// hierarchies", 2007) over primitive boxes and centroids, nodes laid out depth first.
#include "geometry/bvh.h"

#include <algorithm>
#include <cmath>
#include <memory>

namespace luz {

namespace {

/// A primitive while building: its box, centroid and id, moved together by partitioning.
struct Ref {
    Bounds3 box;
    Vec3 c;
    uint32_t id;
};

constexpr int kMaxBins = 64;
constexpr int kMedianDepth = 48;  // deeper nodes split at the median: depth stays < 48 + 32

/// The SAH's measure of a box: its surface area (halved), or for a flat-less box (a segment or
/// a point) its length, so that costs stay comparable where every area is zero.
struct Measure {
    bool by_area;
    float operator()(const Bounds3& b) const {
        if (b.empty()) return 0.0f;
        const Vec3 d = b.extent();
        return by_area ? d.x * d.y + d.y * d.z + d.z * d.x : d.x + d.y + d.z;
    }
};

/// One bin of one axis: the primitives whose centroids fall in it.
struct Bin {
    Bounds3 box, cbox;  // of their boxes, of their centroids
    uint32_t n = 0;
};

class Builder {
  public:
    Builder(std::vector<Ref>& refs, const BvhOptions& options, std::vector<BvhNode>& nodes)
        : refs_(refs),
          options_(options),
          bins_(std::clamp(options.bins, 2, kMaxBins)),
          nodes_(nodes) {}

    /// Builds the subtree of refs [begin, end) (their boxes' bounds `box`, their centroids'
    /// `cbox`) at `depth`; returns its node index.
    uint32_t build(size_t begin, size_t end, const Bounds3& box, const Bounds3& cbox, int depth) {
        const uint32_t index = static_cast<uint32_t>(nodes_.size());
        nodes_.emplace_back();
        for (int a = 0; a < 3; ++a) {
            nodes_[index].lo[a] = box.lo[a];
            nodes_[index].hi[a] = box.hi[a];
        }
        Bounds3 child[4];  // box and cbox of the first and the second child
        const size_t mid = end - begin > 1 ? split(begin, end, depth, box, cbox, child) : begin;
        if (mid == begin) {
            nodes_[index].offset = static_cast<uint32_t>(begin);
            nodes_[index].count = static_cast<uint32_t>(end - begin);
            return index;
        }
        build(begin, mid, child[0], child[1], depth + 1);  // the next node: index + 1
        const uint32_t second = build(mid, end, child[2], child[3], depth + 1);
        nodes_[index].offset = second;
        nodes_[index].count = 0;
        return index;
    }

    /// The bounds of the boxes and of the centroids of refs [begin, end).
    void bounds_of(size_t begin, size_t end, Bounds3& box, Bounds3& cbox) const {
        box = cbox = Bounds3{};
        for (size_t i = begin; i < end; ++i) {
            box.expand(refs_[i].box);
            cbox.expand(refs_[i].c);
        }
    }

  private:
    /// Where to split refs [begin, end) after reordering them, with the children's bounds in
    /// `child`; `begin` means make a leaf.
    size_t split(size_t begin, size_t end, int depth, const Bounds3& box, const Bounds3& cbox,
                 Bounds3* child) {
        const Vec3 ce = cbox.extent();
        const int widest = ce.x >= ce.y ? (ce.x >= ce.z ? 0 : 2) : (ce.y >= ce.z ? 1 : 2);
        if (!(ce[widest] > 0)) return begin;  // every centroid in one point: nothing to split
        if (depth >= kMedianDepth) return median(begin, end, widest, child);

        // Bin every primitive on every axis with a centroid extent, in one pass.
        float scale[3];
        for (int a = 0; a < 3; ++a) {
            scale[a] = ce[a] > 0 ? bins_ / ce[a] : 0.0f;
            for (int k = 0; k < bins_; ++k) bin_[a][k] = Bin{};
        }
        for (size_t i = begin; i < end; ++i) {
            const Ref& r = refs_[i];
            for (int a = 0; a < 3; ++a) {
                Bin& b = bin_[a][bin(r.c[a], cbox.lo[a], scale[a])];
                ++b.n;
                b.box.expand(r.box);
                b.cbox.expand(r.c);
            }
        }

        // The SAH: cost = traversal + (measure(L)·|L| + measure(R)·|R|) / measure(parent).
        const size_t count = end - begin;
        const Vec3 e = box.extent();
        const Measure measure{e.x * e.y + e.y * e.z + e.z * e.x > 0};
        const float parent = measure(box);
        float best_cost = std::numeric_limits<float>::infinity();
        int best_axis = -1, best_bin = 0;
        for (int a = 0; a < 3; ++a) {
            if (!(ce[a] > 0)) continue;
            // right[k]: measure and count of bins k+1 … bins−1
            float right_measure[kMaxBins];
            uint32_t right_count[kMaxBins];
            Bounds3 acc;
            uint32_t c = 0;
            for (int k = bins_ - 1; k > 0; --k) {
                acc.expand(bin_[a][k].box);
                c += bin_[a][k].n;
                right_measure[k - 1] = measure(acc);
                right_count[k - 1] = c;
            }
            acc = Bounds3{};
            c = 0;
            for (int k = 0; k < bins_ - 1; ++k) {
                acc.expand(bin_[a][k].box);
                c += bin_[a][k].n;
                if (c == 0 || right_count[k] == 0) continue;
                const float cost = options_.traversal_cost +
                                   (measure(acc) * c + right_measure[k] * right_count[k]) / parent;
                if (cost < best_cost) {
                    best_cost = cost;
                    best_axis = a;
                    best_bin = k;
                }
            }
        }
        if (best_axis < 0) return median(begin, end, widest, child);
        // A leaf when it costs no more than the split and is small enough.
        if (count <= options_.max_leaf_size && !(best_cost < static_cast<float>(count))) {
            return begin;
        }
        const float lo = cbox.lo[best_axis], s = scale[best_axis];
        const auto it =
            std::partition(refs_.begin() + begin, refs_.begin() + end,
                           [&](const Ref& r) { return bin(r.c[best_axis], lo, s) <= best_bin; });
        const size_t mid = static_cast<size_t>(it - refs_.begin());
        if (mid == begin || mid == end) return median(begin, end, widest, child);
        for (int i = 0; i < 4; ++i) child[i] = Bounds3{};
        for (int k = 0; k < bins_; ++k) {
            const Bin& b = bin_[best_axis][k];
            child[k <= best_bin ? 0 : 2].expand(b.box);
            child[k <= best_bin ? 1 : 3].expand(b.cbox);
        }
        return mid;
    }

    int bin(float c, float lo, float scale) const {
        const int k = static_cast<int>((c - lo) * scale);
        return std::clamp(k, 0, bins_ - 1);
    }

    size_t median(size_t begin, size_t end, int axis, Bounds3* child) {
        const size_t mid = begin + (end - begin) / 2;
        std::nth_element(refs_.begin() + begin, refs_.begin() + mid, refs_.begin() + end,
                         [axis](const Ref& a, const Ref& b) { return a.c[axis] < b.c[axis]; });
        bounds_of(begin, mid, child[0], child[1]);
        bounds_of(mid, end, child[2], child[3]);
        return mid;
    }

    std::vector<Ref>& refs_;
    const BvhOptions& options_;
    int bins_;
    std::vector<BvhNode>& nodes_;
    Bin bin_[3][kMaxBins];  // scratch, reused by every node
};

}  // namespace

Bvh Bvh::build(std::span<const Bounds3> bounds, const BvhOptions& options) {
    Bvh bvh;
    std::vector<Ref> refs;
    refs.reserve(bounds.size());
    for (size_t i = 0; i < bounds.size(); ++i) {
        const Bounds3& b = bounds[i];
        if (b.empty()) continue;
        refs.push_back({b, b.center(), static_cast<uint32_t>(i)});
    }
    if (refs.empty()) return bvh;
    bvh.nodes_.reserve(2 * refs.size());
    auto builder = std::make_unique<Builder>(refs, options, bvh.nodes_);
    Bounds3 box, cbox;
    builder->bounds_of(0, refs.size(), box, cbox);
    builder->build(0, refs.size(), box, cbox, 0);
    bvh.nodes_.shrink_to_fit();
    bvh.order_.resize(refs.size());
    for (size_t i = 0; i < refs.size(); ++i) bvh.order_[i] = refs[i].id;
    return bvh;
}

}  // namespace luz
