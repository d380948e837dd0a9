// Bvh::build: top-down binned SAH (Wald 2007) over primitive boxes and centroids, exact SAH for
// small nodes, depth-first nodes; large nodes binned, partitioned and split in parallel (oneTBB)
// by decisions that never depend on the thread count, so the tree is the same for any.
#include "geometry/bvh.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#include "math/huge_pages.h"
#include "scene/cancel.h"

namespace luz {

namespace {

// Four floats in one SIMD register (GCC/Clang vector extension): x, y, z and a spare lane.
typedef float V4 __attribute__((vector_size(16)));
typedef int32_t I4 __attribute__((vector_size(16)));

V4 vmin(V4 a, V4 b) { return a < b ? a : b; }
V4 vmax(V4 a, V4 b) { return a > b ? a : b; }

constexpr float kInf = std::numeric_limits<float>::infinity();

/// An axis-aligned box as two V4s (lane 3 unused).
struct Box {
    V4 lo{kInf, kInf, kInf, 0}, hi{-kInf, -kInf, -kInf, 0};

    void expand(const Box& b) {
        lo = vmin(lo, b.lo);
        hi = vmax(hi, b.hi);
    }
    void expand(V4 p) {
        lo = vmin(lo, p);
        hi = vmax(hi, p);
    }
    bool empty() const { return lo[0] > hi[0] || lo[1] > hi[1] || lo[2] > hi[2]; }
};

/// A primitive while building: its box (lane 3 zero) and id, 32 bytes, moved by partitioning.
struct alignas(16) Ref {
    V4 lo, hi;

    uint32_t id() const {
        uint32_t i;
        std::memcpy(&i, &reinterpret_cast<const float*>(&lo)[3], 4);
        return i;
    }
    /// The centroid (lo + hi)/2, as Bounds3::center() computes it (lane 3 zero).
    V4 centroid() const {
        const I4 xyz{-1, -1, -1, 0};  // lane 3 holds the id: keep it out of the arithmetic
        const V4 l = V4(I4(lo) & xyz), h = V4(I4(hi) & xyz);
        return (l + h) * 0.5f;
    }
};

/// The refs of a build: hundreds of megabytes for millions of primitives, on huge pages (each
/// 4 KiB page faulted in costs a kernel entry; a 2 MiB one covers 512 of them).
using Refs = HugeVector<Ref>;

constexpr int kMaxBins = 64;
constexpr int kMedianDepth = 48;        // deeper nodes split at the median: depth stays < 48 + 32
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
        const V4 d = b.hi - b.lo;
        return by_area ? d[0] * d[1] + d[1] * d[2] + d[2] * d[0] : d[0] + d[1] + d[2];
    }
};

// Eight floats or ints in one (AVX) register, or two SSE ones: the sweep's ranking.
typedef float V8 __attribute__((vector_size(32)));
typedef int32_t I8 __attribute__((vector_size(32)));

constexpr int kRankVectors = (kSweepBelow - 1 + 7) / 8;  // V8s of keys in the sweep's ranking

/// Sorts indices 0 … n−1 (n < kSweepBelow) by key, stably (equal keys keep their order):
/// each index's rank is the number of keys before it, all ranks counted at once on SIMD
/// lanes. `key` holds 8·kRankVectors floats, those past n +∞. False (and `o` unspecified) if
/// a key is NaN.
bool rank_sort(const float* key, int n, int* o) {
    V8 k[kRankVectors];
    std::memcpy(k, key, sizeof k);
    I8 rank[kRankVectors] = {};
    for (int j = 0; j < n; ++j) {
        const float kj = key[j];
        if (kj != kj) return false;
        I8 lane{0, 1, 2, 3, 4, 5, 6, 7};
        for (int h = 0; h < kRankVectors; ++h, lane += 8) {
            // key j comes before lane i if smaller, or equal with j < i (lanes −1 where true)
            rank[h] -= (kj < k[h]) | ((kj == k[h]) & (j < lane));
        }
    }
    for (int i = 0; i < n; ++i) o[rank[i >> 3][i & 7]] = i;
    return true;
}

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
I4 bin_of(V4 c, V4 lo, V4 scale, int bins) {
    I4 k = __builtin_convertvector((c - lo) * scale, I4);
    const I4 zero{0, 0, 0, 0}, top{bins - 1, bins - 1, bins - 1, bins - 1};
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

BvhNode make_node(const Box& box) {
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
                                        int depth) {
        auto sub = std::make_unique<Subtree>();
        const auto scratch = std::make_unique<Bins>();
        const auto leaf = [&] {  // a flat subtree of one node
            sub->root = make_node(box);
            sub->root.offset = static_cast<uint32_t>(begin);
            sub->root.count = static_cast<uint32_t>(end - begin);
            flat_[2 * begin] = sub->root;
            sub->nodes = flat_.get() + 2 * begin;
            sub->size = 1;
            return std::move(sub);
        };
        if (cancel_requested(cancel_)) return leaf();  // cancelled: thrown away by build()
        if (end - begin < serial_below_) {
            FlatNodes flat{flat_.get() + 2 * begin};
            build_serial(flat, begin, end, box, cbox, depth, *scratch);
            sub->nodes = flat.at;
            sub->size = flat.size;
            return sub;
        }
        Box child[4];
        const size_t mid = split(begin, end, depth, box, cbox, child, *scratch);
        sub->root = make_node(box);
        if (mid == begin) return leaf();
        tbb::parallel_invoke(
            [&] { sub->left = build_task(begin, mid, child[0], child[1], depth + 1); },
            [&] { sub->right = build_task(mid, end, child[2], child[3], depth + 1); });
        sub->size = 1 + sub->left->size + sub->right->size;
        return sub;
    }

    /// Writes subtree s at out[base …] with absolute node indices.
    static void flatten(const Subtree& s, BvhNode* out, uint32_t base) {
        if (!s.left) {
            for (size_t i = 0; i < s.size; ++i) {
                BvhNode n = s.nodes[i];
                if (!n.leaf()) n.offset += base;
                out[base + i] = n;
            }
            return;
        }
        BvhNode root = s.root;
        const uint32_t second = base + 1 + static_cast<uint32_t>(s.left->size);
        root.offset = second;
        root.count = 0;
        out[base] = root;
        tbb::parallel_invoke([&] { flatten(*s.left, out, base + 1); },
                             [&] { flatten(*s.right, out, second); });
    }

  private:
    static void clear_lane3(Box& b) {
        b.lo[3] = 0;
        b.hi[3] = 0;
    }

    /// Builds the subtree of refs [begin, end) into `nodes` (depth first, offsets relative to
    /// the first node of `nodes`); returns its root's index.
    uint32_t build_serial(FlatNodes& nodes, size_t begin, size_t end, const Box& box,
                          const Box& cbox, int depth, Bins& scratch) {
        const uint32_t index = nodes.push(make_node(box));
        Box child[4];  // box and cbox of the first and the second child
        const size_t mid =
            end - begin > 1 ? split(begin, end, depth, box, cbox, child, scratch) : begin;
        if (mid == begin) {
            nodes.at[index].offset = static_cast<uint32_t>(begin);
            nodes.at[index].count = static_cast<uint32_t>(end - begin);
            return index;
        }
        build_serial(nodes, begin, mid, child[0], child[1], depth + 1, scratch);  // the next node
        const uint32_t second =
            build_serial(nodes, mid, end, child[2], child[3], depth + 1, scratch);
        nodes.at[index].offset = second;
        nodes.at[index].count = 0;
        return index;
    }

    /// Bins refs [begin, end) into `b` (cleared first).
    void bin_range(size_t begin, size_t end, V4 lo, V4 scale, Bins& b) const {
        for (int a = 0; a < 3; ++a)
            for (int k = 0; k < bins_; ++k) b.bin[a][k] = Bin{};
        for (size_t i = begin; i < end; ++i) {
            const Ref& r = refs_[i];
            const I4 k = bin_of(r.centroid(), lo, scale, bins_);
            for (int a = 0; a < 3; ++a) {
                Bin& bin = b.bin[a][k[a]];
                bin.box.lo = vmin(bin.box.lo, r.lo);
                bin.box.hi = vmax(bin.box.hi, r.hi);
                ++bin.n;
            }
        }
    }

    /// Where to split refs [begin, end) after reordering them, with the children's box and
    /// centroid bounds in `child`; `begin` means make a leaf. `bins`: scratch.
    size_t split(size_t begin, size_t end, int depth, const Box& box, const Box& cbox, Box* child,
                 Bins& bins) {
        const V4 ce = cbox.hi - cbox.lo;
        const int widest = ce[0] >= ce[1] ? (ce[0] >= ce[2] ? 0 : 2) : (ce[1] >= ce[2] ? 1 : 2);
        if (!(ce[widest] > 0)) return begin;  // every centroid in one point: nothing to split
        if (depth >= kMedianDepth) return median(begin, end, widest, child);
        if (end - begin < kSweepBelow) return sweep(begin, end, box, ce, child);

        // Bin every primitive on every axis with a centroid extent, in one pass (in parallel
        // chunks for large nodes: bounds and counts merge exactly, in any order).
        const size_t count = end - begin;
        V4 scale{0, 0, 0, 0};
        for (int a = 0; a < 3; ++a) scale[a] = ce[a] > 0 ? bins_ / ce[a] : 0.0f;
        if (count < 4 * kChunk) {
            bin_range(begin, end, cbox.lo, scale, bins);
        } else {
            const size_t chunks = (count + kChunk - 1) / kChunk;
            std::vector<std::unique_ptr<Bins>> part(chunks);
            tbb::parallel_for(size_t{0}, chunks, [&](size_t c) {
                part[c] = std::make_unique<Bins>();
                bin_range(begin + c * kChunk, std::min(end, begin + (c + 1) * kChunk), cbox.lo,
                          scale, *part[c]);
            });
            for (int a = 0; a < 3; ++a)
                for (int k = 0; k < bins_; ++k) bins.bin[a][k] = Bin{};
            for (const auto& p : part) bins.add(*p, bins_);
        }

        // The SAH: cost = traversal + (measure(L)·|L| + measure(R)·|R|) / measure(parent); the
        // split with the least measure(L)·|L| + measure(R)·|R| is found first.
        const V4 e = box.hi - box.lo;
        const Measure measure{e[0] * e[1] + e[1] * e[2] + e[2] * e[0] > 0};
        float best_sum = std::numeric_limits<float>::infinity();
        int best_axis = -1, best_bin = 0;
        for (int a = 0; a < 3; ++a) {
            if (!(ce[a] > 0)) continue;
            // right[k]: measure and count of bins k+1 … bins−1
            float right_measure[kMaxBins];
            uint32_t right_count[kMaxBins];
            Box acc;
            uint32_t c = 0;
            for (int k = bins_ - 1; k > 0; --k) {
                acc.expand(bins.bin[a][k].box);
                c += bins.bin[a][k].n;
                right_measure[k - 1] = measure.of_nonempty(acc);  // used only if c > 0
                right_count[k - 1] = c;
            }
            acc = Box{};
            c = 0;
            for (int k = 0; k < bins_ - 1; ++k) {
                acc.expand(bins.bin[a][k].box);
                c += bins.bin[a][k].n;
                if (c == 0 || right_count[k] == 0) continue;
                const float sum = measure.of_nonempty(acc) * blocks(c) +
                                  right_measure[k] * blocks(right_count[k]);
                if (sum < best_sum) {
                    best_sum = sum;
                    best_axis = a;
                    best_bin = k;
                }
            }
        }
        if (best_axis < 0) return median(begin, end, widest, child);
        const float best_cost = options_.traversal_cost + best_sum / measure(box);
        // A leaf when it costs no more than the split and is small enough.
        if (count <= options_.max_leaf_size && !(best_cost < blocks(count))) {
            return begin;
        }

        // The children's boxes from the bins; their centroid bounds while partitioning.
        for (int i = 0; i < 4; ++i) child[i] = Box{};
        for (int k = 0; k < bins_; ++k)
            child[k <= best_bin ? 0 : 2].expand(bins.bin[best_axis][k].box);
        const size_t mid =
            count < 4 * kChunk
                ? partition(begin, end, best_axis, best_bin, cbox.lo, scale, child)
                : partition_parallel(begin, end, best_axis, best_bin, cbox.lo, scale, child);
        if (mid == begin || mid == end) return median(begin, end, widest, child);
        clear_lane3(child[0]);
        clear_lane3(child[2]);
        return mid;
    }

    /// Moves the refs of [begin, end) whose bin on `axis` is ≤ `last` to the front (in place,
    /// from both ends); their centroid bounds go to child[1], the others' to child[3].
    size_t partition(size_t begin, size_t end, int axis, int last, V4 lo, V4 scale, Box* child) {
        size_t i = begin, j = end;
        Box left, right;
        for (;;) {
            for (;;) {  // skip refs that belong on the left
                if (i == j) goto done;
                const V4 c = refs_[i].centroid();
                if (bin_of(c, lo, scale, bins_)[axis] > last) {
                    right.expand(c);
                    break;
                }
                left.expand(c);
                ++i;
            }
            for (;;) {  // skip refs that belong on the right
                if (i == --j) goto done;
                const V4 c = refs_[j].centroid();
                if (bin_of(c, lo, scale, bins_)[axis] <= last) {
                    left.expand(c);
                    break;
                }
                right.expand(c);
            }
            std::swap(refs_[i], refs_[j]);
            ++i;
        }
    done:
        child[1] = left;
        child[3] = right;
        return i;
    }

    /// partition() for large ranges: a stable partition in fixed chunks (count, then scatter
    /// into a scratch array and copy back), so that the order does not depend on threads.
    size_t partition_parallel(size_t begin, size_t end, int axis, int last, V4 lo, V4 scale,
                              Box* child) {
        const size_t count = end - begin, chunks = (count + kChunk - 1) / kChunk;
        std::vector<size_t> n_left(chunks);
        std::vector<Box> c_left(chunks), c_right(chunks);
        uint8_t* const side = side_.get() + begin;
        tbb::parallel_for(size_t{0}, chunks, [&](size_t c) {
            size_t n = 0;
            for (size_t i = begin + c * kChunk, e = std::min(end, i + kChunk); i < e; ++i) {
                const V4 p = refs_[i].centroid();
                const bool is_left = bin_of(p, lo, scale, bins_)[axis] <= last;
                side[i - begin] = is_left;
                (is_left ? c_left[c] : c_right[c]).expand(p);
                n += is_left;
            }
            n_left[c] = n;
        });
        std::vector<size_t> at_left(chunks), at_right(chunks);
        size_t total_left = 0;
        for (size_t c = 0; c < chunks; ++c) {
            at_left[c] = total_left;
            total_left += n_left[c];
        }
        size_t r = total_left;
        for (size_t c = 0; c < chunks; ++c) {
            at_right[c] = r;
            r += std::min(kChunk, count - c * kChunk) - n_left[c];
        }
        Ref* const scratch = scratch_.get() + begin;
        tbb::parallel_for(size_t{0}, chunks, [&](size_t c) {
            size_t l = at_left[c], rr = at_right[c];
            for (size_t i = begin + c * kChunk, e = std::min(end, i + kChunk); i < e; ++i)
                scratch[side[i - begin] ? l++ : rr++] = refs_[i];
        });
        tbb::parallel_for(size_t{0}, chunks, [&](size_t c) {
            const size_t i = c * kChunk, e = std::min(count, i + kChunk);
            std::copy(scratch + i, scratch + e, refs_.begin() + begin + i);
        });
        child[1] = child[3] = Box{};
        for (size_t c = 0; c < chunks; ++c) {
            child[1].expand(c_left[c]);
            child[3].expand(c_right[c]);
        }
        return begin + total_left;
    }

    /// split() for a small node: the exact SAH over every split of the refs sorted by centroid
    /// on each axis (cheaper here than clearing and sweeping the bins, and no worse). The three
    /// axes are swept side by side (independent chains of box unions).
    size_t sweep(size_t begin, size_t end, const Box& box, V4 ce, Box* child) {
        const int n = static_cast<int>(end - begin);
        constexpr int kKeys = 8 * kRankVectors;
        V4 c[kSweepBelow];
        float key[3][kKeys];
        for (int i = 0; i < kKeys; ++i) {
            if (i < n) c[i] = refs_[begin + i].centroid();
            for (int a = 0; a < 3; ++a) key[a][i] = i < n ? c[i][a] : kInf;
        }
        const V4 e = box.hi - box.lo;
        const Measure measure{e[0] * e[1] + e[1] * e[2] + e[2] * e[0] > 0};
        // refs by centroid on each axis (stable: equal centroids keep their order)
        int order[3][kSweepBelow];
        for (int a = 0; a < 3; ++a) {
            int* o = order[a];
            if (!rank_sort(key[a], n, o)) {  // a NaN centroid: insertion sort, as ever
                for (int i = 0; i < n; ++i) {
                    int j = i;
                    for (; j > 0 && c[o[j - 1]][a] > c[i][a]; --j) o[j] = o[j - 1];
                    o[j] = i;
                }
            }
        }
        // right_measure[a][k]: the refs after position k on axis a
        float right_measure[3][kSweepBelow];
        Box acc[3];
        for (int k = n - 1; k > 0; --k) {
            for (int a = 0; a < 3; ++a) {
                const Ref& r = refs_[begin + order[a][k]];
                acc[a].expand(Box{r.lo, r.hi});
                right_measure[a][k - 1] = measure.of_nonempty(acc[a]);
            }
        }
        // per axis the first least sum; then the first axis with the least (as one sweep of
        // the axes in turn would pick)
        float axis_sum[3] = {kInf, kInf, kInf};
        int axis_k[3] = {0, 0, 0};
        for (int a = 0; a < 3; ++a) acc[a] = Box{};
        for (int k = 0; k < n - 1; ++k) {
            for (int a = 0; a < 3; ++a) {
                const Ref& r = refs_[begin + order[a][k]];
                acc[a].expand(Box{r.lo, r.hi});
                const float sum = measure.of_nonempty(acc[a]) * blocks(k + 1) +
                                  right_measure[a][k] * blocks(n - k - 1);
                if (sum < axis_sum[a]) {
                    axis_sum[a] = sum;
                    axis_k[a] = k;
                }
            }
        }
        float best_sum = kInf;
        int best_axis = -1, best_k = 0;
        for (int a = 0; a < 3; ++a) {
            if (ce[a] > 0 && axis_sum[a] < best_sum) {
                best_sum = axis_sum[a];
                best_axis = a;
                best_k = axis_k[a];
            }
        }
        if (best_axis < 0) return median(begin, end, 0, child);
        const float best_cost = options_.traversal_cost + best_sum / measure(box);
        if (static_cast<uint32_t>(n) <= options_.max_leaf_size && !(best_cost < blocks(n))) {
            return begin;  // a leaf when it costs no more than the split and is small enough
        }
        // reorder by the best axis; the children's bounds
        Ref sorted[kSweepBelow];
        for (int i = 0; i < n; ++i) sorted[i] = refs_[begin + order[best_axis][i]];
        for (int i = 0; i < 4; ++i) child[i] = Box{};
        for (int i = 0; i < n; ++i) {
            refs_[begin + i] = sorted[i];
            const int side = i <= best_k ? 0 : 2;
            child[side].expand(Box{sorted[i].lo, sorted[i].hi});
            child[side + 1].expand(c[order[best_axis][i]]);
        }
        clear_lane3(child[0]);
        clear_lane3(child[2]);
        return begin + static_cast<size_t>(best_k) + 1;
    }

    size_t median(size_t begin, size_t end, int axis, Box* child) {
        const size_t mid = begin + (end - begin) / 2;
        std::nth_element(
            refs_.begin() + begin, refs_.begin() + mid, refs_.begin() + end,
            [axis](const Ref& a, const Ref& b) { return a.centroid()[axis] < b.centroid()[axis]; });
        bounds_of(begin, mid, child[0], child[1]);
        bounds_of(mid, end, child[2], child[3]);
        return mid;
    }

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

}  // namespace

Bvh Bvh::build(std::span<const Bounds3> bounds, const BvhOptions& options) {
    Bvh bvh;
    Refs refs;
    refs.reserve(bounds.size());
    for (size_t i = 0; i < bounds.size(); ++i) {
        const Bounds3& b = bounds[i];
        if (b.empty()) continue;
        Ref r;
        const uint32_t id = static_cast<uint32_t>(i);
        float id_bits;
        std::memcpy(&id_bits, &id, 4);
        r.lo = V4{b.lo.x, b.lo.y, b.lo.z, id_bits};
        r.hi = V4{b.hi.x, b.hi.y, b.hi.z, 0.0f};
        refs.push_back(r);
    }
    if (refs.empty()) return bvh;
    Builder builder(refs, options);
    Box box, cbox;
    builder.bounds_of(0, refs.size(), box, cbox);
    const std::unique_ptr<Subtree> tree = builder.build_task(0, refs.size(), box, cbox, 0);
    check_cancel();
    bvh.nodes_.resize(tree->size);
    Builder::flatten(*tree, bvh.nodes_.data(), 0);
    bvh.order_.resize(refs.size());
    const auto take_ids = [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) bvh.order_[i] = refs[i].id();
    };
    if (refs.size() < 4 * kChunk) {
        take_ids(0, refs.size());
    } else {
        tbb::parallel_for(
            tbb::blocked_range<size_t>(0, refs.size(), kChunk),
            [&](const tbb::blocked_range<size_t>& r) { take_ids(r.begin(), r.end()); });
    }
    return bvh;
}

}  // namespace luz
