// The exact SAH split of a small BVH node: its refs ranked by centroid on each axis (all ranks
// counted at once on eight-lane vectors), every split position's cost swept on the three axes.
#include "geometry/bvh_builder.h"

namespace luz::bvh_build {

namespace {

constexpr int kRankVectors = (kSweepBelow - 1 + 7) / 8;  // Lane8fs of keys in the ranking

/// Sorts indices 0 … n−1 (n < kSweepBelow) by key, stably (equal keys keep their order):
/// each index's rank is the number of keys before it, all ranks counted at once on SIMD
/// lanes. `key` holds 8·kRankVectors floats, those past n +∞. False (and `o` unspecified) if
/// a key is NaN.
bool rank_sort(const float* key, int n, int* o) {
    Lane8f k[kRankVectors];
    std::memcpy(k, key, sizeof k);
    Lane8i rank[kRankVectors] = {};
    const int vectors = (n + 7) / 8;  // those that hold keys 0 … n−1
    for (int j = 0; j < n; ++j) {
        const float kj = key[j];
        if (kj != kj) return false;
        const Lane8f kj8 = lanes(kj);
        const Lane8i j8 = lanes_i(j);
        Lane8i lane{0, 1, 2, 3, 4, 5, 6, 7};
        for (int h = 0; h < vectors; ++h, lane += 8) {
            // key j comes before lane i if smaller, or equal with j < i (lanes −1 where true);
            // lane_lt()/lane_eq(): without AVX the operators compile lane by lane
            rank[h] -= lane_lt(kj8, k[h]) | (lane_eq(kj8, k[h]) & lane_lt(j8, lane));
        }
    }
    for (int i = 0; i < n; ++i) o[rank[i >> 3][i & 7]] = i;
    return true;
}

}  // namespace

size_t Builder::sweep(size_t begin, size_t end, const Box& box, Lane4f ce, Box* child) {
    const int n = static_cast<int>(end - begin);
    constexpr int kKeys = 8 * kRankVectors;
    Lane4f c[kSweepBelow];
    float key[3][kKeys];
    for (int i = 0; i < kKeys; ++i) {
        if (i < n) c[i] = refs_[begin + i].centroid();
        for (int a = 0; a < 3; ++a) key[a][i] = i < n ? c[i][a] : kInf;
    }
    const Lane4f e = box.hi - box.lo;
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

}  // namespace luz::bvh_build
