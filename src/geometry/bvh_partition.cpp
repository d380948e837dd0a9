// Moving a BVH node's refs to the side of their split: in place from both ends, stably in
// parallel chunks for large nodes (the same order for any thread count), at the median, or by
// kind (a would-be leaf of several kinds, BvhOptions::kinds).
#include <tbb/parallel_for.h>

#include <algorithm>
#include <vector>

#include "geometry/bvh_builder.h"

namespace luz::bvh_build {

size_t Builder::partition(size_t begin, size_t end, int axis, int last, Lane4f lo, Lane4f scale,
                          Box* child) {
    size_t i = begin, j = end;
    Box left, right;
    for (;;) {
        for (;;) {  // skip refs that belong on the left
            if (i == j) goto done;
            const Lane4f c = refs_[i].centroid();
            if (bin_of(c, lo, scale, bins_)[axis] > last) {
                right.expand(c);
                break;
            }
            left.expand(c);
            ++i;
        }
        for (;;) {  // skip refs that belong on the right
            if (i == --j) goto done;
            const Lane4f c = refs_[j].centroid();
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

size_t Builder::partition_parallel(size_t begin, size_t end, int axis, int last, Lane4f lo,
                                   Lane4f scale, Box* child) {
    const size_t count = end - begin, chunks = (count + kChunk - 1) / kChunk;
    std::vector<size_t> n_left(chunks);
    std::vector<Box> c_left(chunks), c_right(chunks);
    uint8_t* const side = side_.get() + begin;
    tbb::parallel_for(size_t{0}, chunks, [&](size_t c) {
        size_t n = 0;
        for (size_t i = begin + c * kChunk, e = std::min(end, i + kChunk); i < e; ++i) {
            const Lane4f p = refs_[i].centroid();
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

size_t Builder::median(size_t begin, size_t end, int axis, Box* child) {
    const size_t mid = begin + (end - begin) / 2;
    std::nth_element(
        refs_.begin() + begin, refs_.begin() + mid, refs_.begin() + end,
        [axis](const Ref& a, const Ref& b) { return a.centroid()[axis] < b.centroid()[axis]; });
    bounds_of(begin, mid, child[0], child[1]);
    bounds_of(mid, end, child[2], child[3]);
    return mid;
}

size_t Builder::split_kinds(size_t begin, size_t end, Box* child) {
    const std::span<const uint8_t> kinds = options_.kinds;
    if (kinds.empty()) return begin;
    uint8_t least = kinds[refs_[begin].id()], most = least;
    for (size_t i = begin + 1; i < end; ++i) {
        least = std::min(least, kinds[refs_[i].id()]);
        most = std::max(most, kinds[refs_[i].id()]);
    }
    if (least == most) return begin;
    // halving the range of kinds: a would-be leaf of K kinds becomes ≤ log2(K) levels deeper
    const uint8_t middle = static_cast<uint8_t>((least + most) / 2);
    const auto mid = std::stable_partition(refs_.begin() + begin, refs_.begin() + end,
                                           [&](const Ref& r) { return kinds[r.id()] <= middle; });
    const size_t m = static_cast<size_t>(mid - refs_.begin());
    bounds_of(begin, m, child[0], child[1]);
    bounds_of(m, end, child[2], child[3]);
    return m;
}

}  // namespace luz::bvh_build
