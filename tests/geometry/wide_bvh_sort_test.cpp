// sort_farthest_first() (wide_bvh.h): the hit children of a node ordered farthest first, by the
// networks of compare-exchanges (three, four) and by insertion sort (more), whatever the input
// order and however many keys are equal.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "geometry/wide_bvh.h"

namespace luz {
namespace {

struct Child {
    float entry;
    int id;  // which child: every one must come out once
};

/// Sorts `in` as the traversals do and checks the result: keys in descending order, and each
/// child of `in` once, with its own key.
void expect_farthest_first(std::vector<Child> in) {
    std::vector<Child> out = in;
    bvh_detail::sort_farthest_first(out.data(), static_cast<int>(out.size()),
                                    [](const Child& c) { return c.entry; });
    for (size_t i = 1; i < out.size(); ++i)
        ASSERT_GE(out[i - 1].entry, out[i].entry) << "at " << i << " of " << out.size();
    const auto by_id = [](const Child& a, const Child& b) { return a.id < b.id; };
    std::sort(in.begin(), in.end(), by_id);
    std::sort(out.begin(), out.end(), by_id);
    for (size_t i = 0; i < in.size(); ++i) {
        EXPECT_EQ(out[i].id, in[i].id);
        EXPECT_EQ(out[i].entry, in[i].entry);
    }
}

TEST(SortFarthestFirst, EveryOrderOfDistinctAndEqualKeys) {
    // Every permutation of keys drawn from {0, 1, 2, 3} with repeats, for 1 … 5 children: the
    // networks (3, 4) and the insertion sort (5) alike, ties included.
    for (int m = 1; m <= 5; ++m) {
        std::vector<int> digits(static_cast<size_t>(m), 0);
        for (;;) {
            std::vector<Child> children;
            for (int k = 0; k < m; ++k)
                children.push_back({static_cast<float>(digits[static_cast<size_t>(k)]), k});
            SCOPED_TRACE(m);
            expect_farthest_first(children);
            int k = 0;  // the next tuple of digits, base 4
            while (k < m && ++digits[static_cast<size_t>(k)] == 4)
                digits[static_cast<size_t>(k++)] = 0;
            if (k == m) break;
        }
    }
}

TEST(SortFarthestFirst, RandomDistancesUpToEightChildren) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> distance(0.0f, 100.0f);
    for (int trial = 0; trial < 2000; ++trial) {
        const int m = 1 + trial % 8;
        std::vector<Child> children;
        for (int k = 0; k < m; ++k) children.push_back({distance(rng), k});
        expect_farthest_first(children);
    }
}

}  // namespace
}  // namespace luz
