// The parallel BVH build: the same tree (nodes and leaf order, bit for bit) whatever the number
// of threads, on inputs large enough for parallel subtrees, binning and partitioning; and the
// tree stays valid there (every primitive in one leaf, children inside their parents).
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cstring>
#include <random>
#include <stdexcept>
#include <vector>

#include "geometry/bvh.h"

namespace luz {
namespace {

/// n boxes in clusters of very different sizes and densities (uneven splits), a few huge ones,
/// many with coincident centroids.
std::vector<Bounds3> clustered_boxes(int n) {
    std::mt19937 rng(77);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<Bounds3> boxes;
    boxes.reserve(n);
    for (int i = 0; i < n; ++i) {
        const int cluster = i % 7;
        const float spread = cluster == 0 ? 100.0f : (cluster < 3 ? 1.0f : 0.01f);
        const Vec3 c{cluster * 10.0f + spread * u(rng), spread * u(rng), spread * u(rng)};
        const float size = i % 997 == 0 ? 50.0f : 0.05f * u(rng);
        const Vec3 p = i % 5 == 0 ? Vec3{cluster * 10.0f} : c;  // coincident centroids
        boxes.push_back({p - Vec3{size}, p + Vec3{size}});
    }
    return boxes;
}

Bvh build_with_threads(int threads, const std::vector<Bounds3>& boxes,
                       const BvhOptions& options = {}) {
    Bvh bvh;
    tbb::task_arena arena(threads);
    arena.execute([&] { bvh = Bvh::build(boxes, options); });
    return bvh;
}

bool same_tree(const Bvh& a, const Bvh& b) {
    return a.nodes().size() == b.nodes().size() && a.order() == b.order() &&
           std::memcmp(a.nodes().data(), b.nodes().data(), a.nodes().size() * sizeof(BvhNode)) == 0;
}

TEST(BvhBuild, SameTreeForAnyThreadCount) {
    const std::vector<Bounds3> boxes = clustered_boxes(200000);
    const Bvh one = build_with_threads(1, boxes);
    ASSERT_EQ(one.order().size(), boxes.size());
    EXPECT_TRUE(same_tree(one, build_with_threads(2, boxes)));
    EXPECT_TRUE(same_tree(one, build_with_threads(3, boxes)));
    EXPECT_TRUE(same_tree(one, build_with_threads(8, boxes)));
}

TEST(BvhBuild, LargeTreeIsValid) {
    const std::vector<Bounds3> boxes = clustered_boxes(200000);
    const Bvh bvh = build_with_threads(2, boxes);
    const HugeVector<BvhNode>& nodes = bvh.nodes();
    ASSERT_FALSE(nodes.empty());
    EXPECT_LE(nodes.size(), 2 * boxes.size() - 1);
    std::vector<int> seen(boxes.size(), 0);
    const auto inside = [](const float* lo, const float* hi, const BvhNode& n) {
        for (int a = 0; a < 3; ++a)
            if (lo[a] < n.lo[a] || hi[a] > n.hi[a]) return false;
        return true;
    };
    // walk the tree with a stack of (node, depth)
    std::vector<std::pair<uint32_t, int>> stack{{0u, 1}};
    int depth = 0;
    while (!stack.empty()) {
        const auto [i, d] = stack.back();
        stack.pop_back();
        depth = std::max(depth, d);
        const BvhNode& n = nodes[i];
        if (n.leaf()) {
            for (uint32_t s = n.offset; s < n.offset + n.count; ++s) {
                const uint32_t id = bvh.order()[s];
                const float lo[3] = {boxes[id].lo.x, boxes[id].lo.y, boxes[id].lo.z};
                const float hi[3] = {boxes[id].hi.x, boxes[id].hi.y, boxes[id].hi.z};
                EXPECT_TRUE(inside(lo, hi, n));
                ++seen[id];
            }
            continue;
        }
        ASSERT_GT(n.offset, i + 1);
        ASSERT_LT(n.offset, nodes.size());
        for (uint32_t c : {i + 1, n.offset}) {
            EXPECT_TRUE(inside(nodes[c].lo, nodes[c].hi, n));
            stack.push_back({c, d + 1});
        }
    }
    for (size_t id = 0; id < boxes.size(); ++id) ASSERT_EQ(seen[id], 1) << id;
    EXPECT_LT(depth, Bvh::kMaxDepth);
}

// A node too large for one task whose centroids all coincide becomes a leaf there (not in the
// serial builder): one node holding every primitive, whatever the thread count.
TEST(BvhBuild, LargeNodeOfCoincidentCentroidsIsOneLeaf) {
    const std::vector<Bounds3> boxes(5000, Bounds3{{1, 2, 3}, {2, 3, 4}});
    for (int threads : {1, 2, 4}) {
        const Bvh bvh = build_with_threads(threads, boxes);
        ASSERT_EQ(bvh.nodes().size(), 1u) << threads;
        const BvhNode& leaf = bvh.nodes()[0];
        EXPECT_EQ(leaf.offset, 0u);
        EXPECT_EQ(leaf.count, 5000u);
        EXPECT_EQ(leaf.lo[0], 1.0f);
        EXPECT_EQ(leaf.hi[2], 4.0f);
        std::vector<int> seen(boxes.size(), 0);
        for (uint32_t id : bvh.order()) ++seen.at(id);
        for (size_t id = 0; id < boxes.size(); ++id) ASSERT_EQ(seen[id], 1) << id;
    }
}

// With kinds, no leaf holds two: a node the SAH would make a leaf of several is split by kind
// (the least first), down to one leaf per kind where every centroid coincides; the tree is
// still the same for any thread count.
TEST(BvhBuild, LeavesHoldOneKindEach) {
    const std::vector<Bounds3> boxes = clustered_boxes(30000);
    std::vector<uint8_t> kinds(boxes.size());
    for (size_t i = 0; i < kinds.size(); ++i) kinds[i] = static_cast<uint8_t>(i * 7 % 3);
    BvhOptions options;
    options.kinds = kinds;
    const Bvh one = build_with_threads(1, boxes, options);
    int mixed_without = 0;
    const Bvh plain = build_with_threads(1, boxes);
    for (const BvhNode& n : plain.nodes())
        for (uint32_t i = n.offset + 1; n.leaf() && i < n.offset + n.count; ++i)
            mixed_without += kinds[plain.order()[i]] != kinds[plain.order()[n.offset]];
    EXPECT_GT(mixed_without, 100);  // the case arises without kinds
    std::vector<int> seen(boxes.size(), 0);
    for (const BvhNode& n : one.nodes()) {
        if (!n.leaf()) continue;
        for (uint32_t i = n.offset; i < n.offset + n.count; ++i) {
            ++seen[one.order()[i]];
            ASSERT_EQ(kinds[one.order()[i]], kinds[one.order()[n.offset]]) << i;
        }
    }
    for (int s : seen) ASSERT_EQ(s, 1);
    for (int threads : {2, 4})
        EXPECT_TRUE(same_tree(one, build_with_threads(threads, boxes, options)));

    const std::vector<Bounds3> same(5000, Bounds3{{1, 2, 3}, {2, 3, 4}});
    std::vector<uint8_t> two(same.size());
    for (size_t i = 0; i < two.size(); ++i) two[i] = static_cast<uint8_t>(1 + i % 2);
    options.kinds = two;
    const Bvh split = build_with_threads(2, same, options);
    ASSERT_EQ(split.nodes().size(), 3u);  // a root and one leaf per kind, the least first
    EXPECT_EQ(split.nodes()[1].count, 2500u);
    EXPECT_EQ(split.nodes()[2].count, 2500u);
    EXPECT_EQ(two[split.order()[split.nodes()[1].offset]], 1);
    EXPECT_EQ(two[split.order()[split.nodes()[2].offset]], 2);

    // one kind per primitive, or none
    options.kinds = std::span<const uint8_t>(two.data(), two.size() - 1);
    EXPECT_THROW(Bvh::build(same, options), std::invalid_argument);
}

}  // namespace
}  // namespace luz
