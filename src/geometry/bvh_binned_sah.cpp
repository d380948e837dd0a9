// The binned SAH split of a BVH node (Wald 2007): every centroid binned on the three axes (in
// parallel chunks for large nodes), the least-cost plane over the bins' prefix and suffix bounds.
#include <tbb/parallel_for.h>

#include <vector>

#include "geometry/bvh_builder.h"

namespace luz::bvh_build {

void Builder::bin_range(size_t begin, size_t end, Lane4f lo, Lane4f scale, Bins& b) const {
    for (int a = 0; a < 3; ++a)
        for (int k = 0; k < bins_; ++k) b.bin[a][k] = Bin{};
    for (size_t i = begin; i < end; ++i) {
        const Ref& r = refs_[i];
        const Lane4i k = bin_of(r.centroid(), lo, scale, bins_);
        for (int a = 0; a < 3; ++a) {
            Bin& bin = b.bin[a][k[a]];
            bin.box.lo = less_or_second(bin.box.lo, r.lo);
            bin.box.hi = greater_or_second(bin.box.hi, r.hi);
            ++bin.n;
        }
    }
}

size_t Builder::split(size_t begin, size_t end, int depth, const Box& box, const Box& cbox,
                      Box* child, Bins& bins) {
    const Lane4f ce = cbox.hi - cbox.lo;
    const int widest = ce[0] >= ce[1] ? (ce[0] >= ce[2] ? 0 : 2) : (ce[1] >= ce[2] ? 1 : 2);
    if (!(ce[widest] > 0)) return begin;  // every centroid in one point: nothing to split
    if (depth >= kMedianDepth) return median(begin, end, widest, child);
    if (end - begin < kSweepBelow) return sweep(begin, end, box, ce, child);

    // Bin every primitive on every axis with a centroid extent, in one pass (in parallel
    // chunks for large nodes: bounds and counts merge exactly, in any order).
    const size_t count = end - begin;
    Lane4f scale{0, 0, 0, 0};
    for (int a = 0; a < 3; ++a) scale[a] = ce[a] > 0 ? bins_ / ce[a] : 0.0f;
    if (count < 4 * kChunk) {
        bin_range(begin, end, cbox.lo, scale, bins);
    } else {
        const size_t chunks = (count + kChunk - 1) / kChunk;
        std::vector<std::unique_ptr<Bins>> part(chunks);
        tbb::parallel_for(size_t{0}, chunks, [&](size_t c) {
            part[c] = std::make_unique<Bins>();
            bin_range(begin + c * kChunk, std::min(end, begin + (c + 1) * kChunk), cbox.lo, scale,
                      *part[c]);
        });
        for (int a = 0; a < 3; ++a)
            for (int k = 0; k < bins_; ++k) bins.bin[a][k] = Bin{};
        for (const auto& p : part) bins.add(*p, bins_);
    }

    // The SAH: cost = traversal + (measure(L)·|L| + measure(R)·|R|) / measure(parent); the
    // split with the least measure(L)·|L| + measure(R)·|R| is found first.
    const Lane4f e = box.hi - box.lo;
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
            const float sum =
                measure.of_nonempty(acc) * blocks(c) + right_measure[k] * blocks(right_count[k]);
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
    for (int k = 0; k < bins_; ++k) child[k <= best_bin ? 0 : 2].expand(bins.bin[best_axis][k].box);
    const size_t mid =
        count < 4 * kChunk
            ? partition(begin, end, best_axis, best_bin, cbox.lo, scale, child)
            : partition_parallel(begin, end, best_axis, best_bin, cbox.lo, scale, child);
    if (mid == begin || mid == end) return median(begin, end, widest, child);
    clear_lane3(child[0]);
    clear_lane3(child[2]);
    return mid;
}

}  // namespace luz::bvh_build
