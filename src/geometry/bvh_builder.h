// The binary BVH's builder (Bvh::build), shared by its parts: the build's boxes and refs on
// Lane4f lanes, and the Builder — the tree's assembly in bvh.cpp, the binned SAH in
// bvh_binned_sah.cpp, the exact SAH of small nodes in bvh_sweep.cpp, partitions in
// bvh_partition.cpp.
#pragma once

#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>

#include "geometry/bvh.h"
#include "math/huge_pages.h"
#include "math/lanes.h"
#include "scene/cancel.h"

namespace luz::bvh_build {

constexpr float kInf = std::numeric_limits<float>::infinity();

/// An axis-aligned box as two Lane4fs (lane 3 unused).
struct Box {
    Lane4f lo{kInf, kInf, kInf, 0}, hi{-kInf, -kInf, -kInf, 0};

    void expand(const Box& b) {
        lo = less_or_second(lo, b.lo);
        hi = greater_or_second(hi, b.hi);
    }
    void expand(Lane4f p) {
        lo = less_or_second(lo, p);
        hi = greater_or_second(hi, p);
    }
    bool empty() const { return lo[0] > hi[0] || lo[1] > hi[1] || lo[2] > hi[2]; }
};

/// A primitive while building: its box (lane 3 zero) and id, 32 bytes, moved by partitioning.
struct alignas(16) Ref {
    Lane4f lo, hi;

    uint32_t id() const {
        uint32_t i;
        std::memcpy(&i, &reinterpret_cast<const float*>(&lo)[3], 4);
        return i;
    }
    /// The centroid (lo + hi)/2, as Bounds3::centre() computes it (lane 3 zero).
    Lane4f centroid() const {
        const Lane4i xyz{-1, -1, -1, 0};  // lane 3 holds the id: keep it out of the arithmetic
        const Lane4f l = Lane4f(Lane4i(lo) & xyz), h = Lane4f(Lane4i(hi) & xyz);
        return (l + h) * 0.5f;
    }
};

/// The refs of a build: hundreds of megabytes for millions of primitives, on huge pages (each
/// 4 KiB page faulted in costs a kernel entry; a 2 MiB one covers 512 of them).
using Refs = HugeVector<Ref>;

constexpr int kMaxBins = 64;
constexpr int kMedianDepth = 48;  // deeper nodes split at the median: depth < 48 + 32 (+8 by kind)
constexpr size_t kSerialBelow = 1024;   // smaller subtrees are built by one task (2+ threads)
constexpr size_t kSerialBelow1 = 4096;  // the same on one thread (fewer tasks, less copying)
constexpr size_t kChunk = 16384;        // refs per chunk of parallel binning and partitioning
constexpr size_t kSweepBelow = 17;      // smaller nodes: exact SAH over sorted centroids

/// The SAH's measure of a box: its surface area (halved), or for a flat-less box (a segment or
/// a point) its length, so that costs stay comparable where every area is zero.
struct Measure {
    bool by_area;
    float operator()(const Box& b) const { return b.empty() ? 0.0f : of_nonempty(b); }
    /// The measure of a box known to hold something (no emptiness test).
    float of_nonempty(const Box& b) const {
        const Lane4f d = b.hi - b.lo;
        return by_area ? d[0] * d[1] + d[1] * d[2] + d[2] * d[0] : d[0] + d[1] + d[2];
    }
};

/// One bin of one axis: the bounds of the boxes whose centroids fall in it, and their number.
struct Bin {
    Box box;
    uint32_t n = 0;
};

/// The bins of a node on all three axes.
struct Bins {
    Bin bin[3][kMaxBins];

    void add(const Bins& o, int bins) {
        for (int a = 0; a < 3; ++a) {
            for (int k = 0; k < bins; ++k) {
                bin[a][k].box.expand(o.bin[a][k].box);
                bin[a][k].n += o.bin[a][k].n;
            }
        }
    }
};

/// Bin indices of centroid c on the three axes: clamp(⌊(c − lo)·scale⌋, 0, bins − 1).
inline Lane4i bin_of(Lane4f c, Lane4f lo, Lane4f scale, int bins) {
    Lane4i k = __builtin_convertvector((c - lo) * scale, Lane4i);
    const Lane4i zero{0, 0, 0, 0}, top{bins - 1, bins - 1, bins - 1, bins - 1};
    k = k < zero ? zero : k;
    return k > top ? top : k;
}

/// A built subtree: a flat array of `size` nodes (root first, second-child offsets relative to
/// it), or a root whose two subtrees were built as separate tasks.
struct Subtree {
    const BvhNode* nodes = nullptr;
    BvhNode root{};
    std::unique_ptr<Subtree> left, right;
    size_t size = 0;  // nodes in the subtree
};

/// Nodes appended one after another to a flat array: a serial subtree's.
struct FlatNodes {
    BvhNode* at;
    uint32_t size = 0;
    uint32_t push(const BvhNode& n) {
        at[size] = n;
        return size++;
    }
};

inline BvhNode make_node(const Box& box) {
    BvhNode n{};
    for (int a = 0; a < 3; ++a) {
        n.lo[a] = box.lo[a];
        n.hi[a] = box.hi[a];
    }
    return n;
}

class Builder {
  public:
    Builder(Refs& refs, const BvhOptions& options)
        : refs_(refs),
          flat_(make_huge_array<BvhNode>(2 * refs.size())),
          options_(options),
          bins_(std::clamp(options.bins, 2, kMaxBins)),
          block_(std::max<size_t>(options.leaf_block, 1)),
          serial_below_(tbb::this_task_arena::max_concurrency() > 1 ? kSerialBelow
                                                                    : kSerialBelow1) {
        if (refs.size() >= 4 * kChunk) {  // partition_parallel()'s scratch, for every node
            scratch_ = make_huge_array<Ref>(refs.size());
            side_ = make_huge_array<uint8_t>(refs.size());
        }
    }

    /// The bounds of the boxes and of the centroids of refs [begin, end).
    void bounds_of(size_t begin, size_t end, Box& box, Box& cbox) const {
        box = cbox = Box{};
        for (size_t i = begin; i < end; ++i) {
            box.expand(Box{refs_[i].lo, refs_[i].hi});
            cbox.expand(refs_[i].centroid());
        }
        clear_lane3(box);
    }

    /// Builds the subtree of refs [begin, end) (their boxes' bounds `box`, their centroids'
    /// `cbox`) at `depth`, in parallel tasks while it is large.
    std::unique_ptr<Subtree> build_task(size_t begin, size_t end, const Box& box, const Box& cbox,
                                        int depth);

    /// Writes subtree s at out[base …] with absolute node indices.
    static void flatten(const Subtree& s, BvhNode* out, uint32_t base);

  private:
    static void clear_lane3(Box& b) {
        b.lo[3] = 0;
        b.hi[3] = 0;
    }

    /// Builds the subtree of refs [begin, end) into `nodes` (depth first, offsets relative to
    /// the first node of `nodes`); returns its root's index.
    uint32_t build_serial(FlatNodes& nodes, size_t begin, size_t end, const Box& box,
                          const Box& cbox, int depth, Bins& scratch);

    /// Bins refs [begin, end) into `b` (cleared first).
    void bin_range(size_t begin, size_t end, Lane4f lo, Lane4f scale, Bins& b) const;

    /// Where to split refs [begin, end) after reordering them, with the children's box and
    /// centroid bounds in `child`; `begin` means make a leaf. `bins`: scratch.
    size_t split(size_t begin, size_t end, int depth, const Box& box, const Box& cbox, Box* child,
                 Bins& bins);

    /// Moves the refs of [begin, end) whose bin on `axis` is ≤ `last` to the front (in place,
    /// from both ends); their centroid bounds go to child[1], the others' to child[3].
    size_t partition(size_t begin, size_t end, int axis, int last, Lane4f lo, Lane4f scale,
                     Box* child);

    /// partition() for large ranges: a stable partition in fixed chunks (count, then scatter
    /// into a scratch array and copy back), so that the order does not depend on threads.
    size_t partition_parallel(size_t begin, size_t end, int axis, int last, Lane4f lo, Lane4f scale,
                              Box* child);

    /// split() for a small node: the exact SAH over every split of the refs sorted by centroid
    /// on each axis (cheaper here than clearing and sweeping the bins, and no worse). The three
    /// axes are swept side by side (independent chains of box unions).
    size_t sweep(size_t begin, size_t end, const Box& box, Lane4f ce, Box* child);

    size_t median(size_t begin, size_t end, int axis, Box* child);

    /// For refs [begin, end) that split() made a leaf: `begin` if they are of one kind
    /// (options_.kinds), else where those of kinds up to the middle of their range end after
    /// moving them to the front (in their order), with the children's bounds in `child`.
    size_t split_kinds(size_t begin, size_t end, Box* child);

    /// n primitives as the SAH counts them: the blocks of options_.leaf_block they fill.
    float blocks(size_t n) const { return static_cast<float>((n + block_ - 1) / block_); }

    Refs& refs_;
    // partition_parallel()'s scratch: refs [begin, end) go through scratch_[begin, end) and
    // their sides through side_[begin, end), so that concurrent partitions of disjoint ranges
    // share one allocation, made once per build instead of once per large node.
    HugeArray<Ref> scratch_;
    HugeArray<uint8_t> side_;
    // The serial subtrees' nodes: the subtree of refs [begin, end) has at most 2·(end − begin)
    // nodes, written at flat_[2·begin …], so that subtrees built side by side never overlap.
    HugeArray<BvhNode> flat_;
    const BvhOptions& options_;
    int bins_;
    size_t block_;
    size_t serial_below_;  // smaller subtrees are built by one task
    // The building thread's cancel flag (scene/cancel.h), checked by every task of a large node
    const std::atomic<bool>* cancel_ = cancel_flag();
};

}  // namespace luz::bvh_build
