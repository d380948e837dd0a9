// The structure of the BVH itself (children inside parents, each primitive in one leaf, SAH
// leaves, depth, traversal order), the scene's leaf blocks and its mesh and BVH memory.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <random>

#include "bvh_fixtures.h"
#include "bvh_reference.h"
#include "geometry/bvh.h"
#include "geometry/prim_block.h"
#include "geometry/scene.h"
#include "geometry/scene_query.h"
#include "geometry_fixtures.h"
#include "math/lane_count.h"

namespace luz {
namespace {

using test::box;
using test::mesh_object;
using test::random_direction;
using test::random_point;
using test::random_soup;
using test::Rng;
using test::scene_with;
using test::sphere;
using test::uniform;

bool contains(const BvhNode& n, const Bounds3& b) {
    for (int a = 0; a < 3; ++a)
        if (b.lo[a] < n.lo[a] || b.hi[a] > n.hi[a]) return false;
    return true;
}

/// Checks every node: children inside parents, primitives inside their leaf, each primitive in
/// exactly one leaf; returns the depth.
int check_tree(const Bvh& bvh, const std::vector<Bounds3>& boxes, uint32_t node,
               std::vector<int>& seen) {
    const BvhNode& n = bvh.nodes()[node];
    if (n.leaf()) {
        for (uint32_t i = n.offset; i < n.offset + n.count; ++i) {
            const uint32_t id = bvh.order()[i];
            EXPECT_TRUE(contains(n, boxes[id]));
            ++seen[id];
        }
        return 1;
    }
    const uint32_t a = node + 1, b = n.offset;
    EXPECT_GT(b, a);
    Bounds3 ba, bb;
    for (int k = 0; k < 3; ++k) {
        ba.lo[k] = bvh.nodes()[a].lo[k];
        ba.hi[k] = bvh.nodes()[a].hi[k];
        bb.lo[k] = bvh.nodes()[b].lo[k];
        bb.hi[k] = bvh.nodes()[b].hi[k];
    }
    EXPECT_TRUE(contains(n, ba));
    EXPECT_TRUE(contains(n, bb));
    return 1 + std::max(check_tree(bvh, boxes, a, seen), check_tree(bvh, boxes, b, seen));
}

TEST(Bvh, EveryPrimitiveInOneLeafInsideEveryAncestor) {
    Rng rng(4);
    std::vector<Bounds3> boxes;
    for (int i = 0; i < 5000; ++i) {
        const Vec3 c = random_point(rng, -10, 10), e = random_point(rng, 0, 0.5f);
        boxes.push_back({c - e, c + e});
    }
    boxes.push_back(Bounds3{});  // empty: left out
    const Bvh bvh = Bvh::build(boxes);
    std::vector<int> seen(boxes.size(), 0);
    const int depth = check_tree(bvh, boxes, 0, seen);
    for (size_t i = 0; i + 1 < boxes.size(); ++i) EXPECT_EQ(seen[i], 1) << i;
    EXPECT_EQ(seen.back(), 0);
    EXPECT_EQ(bvh.order().size(), boxes.size() - 1);
    EXPECT_LT(depth, 40);
    // SAH leaves are small; nodes: at most 2n − 1
    EXPECT_LE(bvh.nodes().size(), 2 * bvh.order().size() - 1);
    for (const BvhNode& n : bvh.nodes()) {
        if (n.leaf()) {
            EXPECT_LE(n.count, BvhOptions{}.max_leaf_size);
        }
    }
    EXPECT_EQ(bvh.memory_bytes(),
              bvh.nodes().capacity() * sizeof(BvhNode) + bvh.order().capacity() * 4);
}

/// A bumpy sphere of n segments and n/2 rings (as scripts/make_big_mesh.py makes, smaller).
ObjectDesc bumpy_sphere(int n) {
    std::vector<Vec3> p;
    std::vector<uint32_t> idx;
    const int rings = n / 2;
    const float pi = 3.14159265f;
    const auto r = [](float th, float ph) {
        return 1 + 0.04f * std::sin(12 * th) * std::sin(15 * ph);
    };
    p.push_back({0, r(0, 0), 0});
    for (int j = 1; j < rings; ++j) {
        const float th = pi * j / rings;
        for (int i = 0; i < n; ++i) {
            const float ph = 2 * pi * i / n, rr = r(th, ph);
            p.push_back({rr * std::sin(th) * std::cos(ph), rr * std::cos(th),
                         rr * std::sin(th) * std::sin(ph)});
        }
    }
    p.push_back({0, -r(pi, 0), 0});
    const auto at = [n](int j, int i) { return static_cast<uint32_t>(1 + (j - 1) * n + i % n); };
    const uint32_t south = static_cast<uint32_t>(p.size() - 1);
    for (int i = 0; i < n; ++i) {
        idx.insert(idx.end(), {0u, at(1, i + 1), at(1, i)});
        idx.insert(idx.end(), {south, at(rings - 1, i), at(rings - 1, i + 1)});
        for (int j = 1; j + 1 < rings; ++j) {
            idx.insert(idx.end(), {at(j, i), at(j, i + 1), at(j + 1, i + 1)});
            idx.insert(idx.end(), {at(j, i), at(j + 1, i + 1), at(j + 1, i)});
        }
    }
    return mesh_object(p, idx, 0);
}

// The scene keeps its primitives in blocks of four, leaf by leaf, and not the order itself: a
// mesh and its BVH (nodes and blocks with the vertices) take under 100 bytes per triangle.
TEST(Bvh, SceneMeshAndBvhUnder100BytesPerTriangle) {
    for (int n : {64, 180}) {
        const BuiltScene scene = build_scene(scene_with({bumpy_sphere(n)}));
        ASSERT_TRUE(scene.has_bvh);
        EXPECT_TRUE(scene.bvh.order().empty());
        const Mesh& m = *scene.shapes[0].mesh;
        const size_t triangles = m.triangle_count();
        EXPECT_GE(scene.bvh_blocks.size() * PrimBlock::kLanes, triangles);
        EXPECT_EQ(scene.bvh_bytes(), scene.bvh.nodes().capacity() * sizeof(Bvh8::Node) +
                                         scene.bvh_blocks.capacity() * sizeof(PrimBlock));
        const size_t bytes = scene.bvh_bytes() + m.positions.capacity() * sizeof(Vec3) +
                             m.indices.capacity() * sizeof(uint32_t);
        EXPECT_LT(static_cast<double>(bytes) / static_cast<double>(triangles), 100.0) << n;
    }
}

// Each leaf of the scene's BVH starts a block and holds at most two; every triangle and shape
// is in exactly one leaf lane, with its own vertices; the lanes after a leaf's end are padding
// (no shape, NaN vertices), and no block is shared by two leaves.
TEST(Bvh, SceneLeavesStartBlocksAndHoldEachPrimitiveOnce) {
    Rng rng(7);
    const ObjectDesc soup = random_soup(rng, 2000, 0);
    const BuiltScene scene =
        build_scene(scene_with({soup, sphere({0, 0, 0}, 0.5f, 0), bumpy_sphere(40),
                                sphere({1, 1, 1}, 0.5f, 1), box({2, 2, 2}, {3, 3, 3}, 0)}));
    ASSERT_TRUE(scene.has_bvh);
    ASSERT_EQ(scene.root_leaf, 0u);
    std::vector<std::vector<int>> seen(scene.shapes.size());
    for (size_t i = 0; i < scene.shapes.size(); ++i) {
        const auto& mesh = scene.shapes[i].mesh;
        seen[i].assign(mesh ? mesh->triangle_count() : 1, 0);
    }
    std::vector<int> block_used(scene.bvh_blocks.size(), 0);
    for (const Bvh8::Node& node : scene.bvh.nodes()) {
        for (int k = 0; k < 8; ++k) {
            const uint32_t first = node.child[k], count = node.count[k];
            if (count == 0) continue;
            ASSERT_EQ(first % PrimBlock::kLanes, 0u);
            ASSERT_LE(count, 8u);
            const uint32_t blocks = (count + 3) / 4;
            ASSERT_LE(first / 4 + blocks, scene.bvh_blocks.size());
            for (uint32_t b = first / 4; b < first / 4 + blocks; ++b) ++block_used[b];
            int triangles = 0;  // mesh triangles and other shapes never share a leaf
            for (uint32_t slot = first; slot < first + count; ++slot)
                triangles += scene.bvh_prim(slot).triangle != BvhPrim::kNotTriangle;
            EXPECT_TRUE(triangles == 0 || triangles == static_cast<int>(count)) << first;
            for (uint32_t slot = first; slot < first + count; ++slot) {
                const BvhPrim p = scene.bvh_prim(slot);
                ASSERT_LT(p.shape, scene.shapes.size());
                const auto& mesh = scene.shapes[p.shape].mesh;
                if (p.triangle == BvhPrim::kNotTriangle) {
                    EXPECT_FALSE(mesh);
                    ++seen[p.shape][0];
                    // a world-form sphere is a sphere lane (tested four at a time), by its
                    // centre, radius² and radius; other shapes are tested one by one
                    const Shape& s = scene.shapes[p.shape];
                    const PrimBlock& b = scene.bvh_blocks[slot / 4];
                    const int k = static_cast<int>(slot % 4);
                    const bool sphere_lane = (b.sphere_lanes() >> k) & 1u;
                    EXPECT_EQ(sphere_lane, s.world_form && s.type == ShapeType::sphere) << slot;
                    EXPECT_FALSE((b.triangle_lanes() >> k) & 1u);
                    if (sphere_lane) {
                        EXPECT_TRUE(b.corner(0, k) == s.centre);
                        EXPECT_EQ(b.v[1][0][k], s.radius * s.radius);
                        EXPECT_EQ(b.v[1][1][k], s.radius);
                    }
                    continue;
                }
                ASSERT_TRUE(mesh);
                ASSERT_LT(p.triangle, mesh->triangle_count());
                ++seen[p.shape][p.triangle];
                Vec3 p0, p1, p2;
                mesh->vertices(p.triangle, p0, p1, p2);
                EXPECT_TRUE(p.p0 == p0 && p.p1 == p1 && p.p2 == p2) << slot;
            }
            for (uint32_t slot = first + count; slot < first + 4 * blocks; ++slot) {
                const PrimBlock& b = scene.bvh_blocks[slot / 4];
                EXPECT_EQ(b.shape[slot % 4], PrimBlock::kPadding);
                EXPECT_FALSE((b.triangle_lanes() >> (slot % 4)) & 1u);
                EXPECT_TRUE(std::isnan(b.v[0][0][slot % 4]));
            }
        }
    }
    for (int used : block_used) EXPECT_EQ(used, 1);
    for (size_t i = 0; i < seen.size(); ++i)
        for (size_t t = 0; t < seen[i].size(); ++t) EXPECT_EQ(seen[i][t], 1) << i << " " << t;
}

// Counting primitives in blocks (leaf_block) changes only the costs: leaf_block 1 is the plain
// SAH tree; blocks of four give leaves that fill their blocks better.
TEST(Bvh, SahCountingBlocks) {
    Rng rng(3);
    std::vector<Bounds3> boxes;
    for (int i = 0; i < 5000; ++i) {
        const Vec3 c = random_point(rng, -10, 10);
        boxes.push_back(Bounds3{c - Vec3{0.1f}, c + Vec3{0.1f}});
    }
    BvhOptions one;
    one.leaf_block = 1;
    const Bvh plain = Bvh::build(boxes), same = Bvh::build(boxes, one);
    ASSERT_EQ(plain.nodes().size(), same.nodes().size());
    EXPECT_EQ(0, std::memcmp(plain.nodes().data(), same.nodes().data(),
                             plain.nodes().size() * sizeof(BvhNode)));
    EXPECT_EQ(plain.order(), same.order());
    BvhOptions four;
    four.leaf_block = 4;
    four.traversal_cost = 0.7f;
    const Bvh blocked = Bvh::build(boxes, four);
    const auto fill = [](const Bvh& bvh) {
        double prims = 0, blocks = 0;
        for (const BvhNode& n : bvh.nodes()) {
            if (!n.leaf()) continue;
            EXPECT_LE(n.count, 8u);
            prims += n.count;
            blocks += (n.count + 3) / 4;
        }
        return prims / (4 * blocks);
    };
    EXPECT_EQ(blocked.order().size(), boxes.size());
    EXPECT_GT(fill(blocked), fill(plain) + 0.2) << fill(blocked) << " vs " << fill(plain);
}

TEST(Bvh, EmptyAndCoincidentInputs) {
    EXPECT_TRUE(Bvh::build({}).empty());
    const std::vector<Bounds3> same(1000, Bounds3{{0, 0, 0}, {1, 1, 1}});
    const BinaryBvh one = BinaryBvh::build(same);  // nothing to split: a single leaf
    ASSERT_EQ(one.nodes().size(), 1u);
    EXPECT_EQ(one.nodes()[0].count, 1000u);
    uint64_t tests = 0;
    int visited = 0;
    float t_max = 100;
    one.nearest({{0.5f, 0.5f, -1}, {0, 0, 1}}, 0.0f, t_max, tests,
                [&](uint32_t, float&) { ++visited; });
    EXPECT_EQ(visited, 1000);
    EXPECT_EQ(tests, 1u);
}

TEST(Bvh, DeepChainsStayWithinTheTraversalStack) {
    // boxes of doubling sizes around one point: SAH would peel one at a time
    std::vector<Bounds3> boxes;
    for (int i = 0; i < 120; ++i) {
        const float s = std::ldexp(1.0f, i - 60);
        boxes.push_back({Vec3{s}, Vec3{s * 1.5f}});
    }
    const Bvh bvh = Bvh::build(boxes);
    std::vector<int> seen(boxes.size(), 0);
    EXPECT_LT(check_tree(bvh, boxes, 0, seen), Bvh::kMaxDepth);
}

TEST(Bvh, NearestVisitsNearChildrenFirstAndSkipsWhatLiesBeyond) {
    // a row of unit boxes along x; a ray along +x hits box 0 first and stops there
    std::vector<Bounds3> boxes;
    for (int i = 0; i < 64; ++i) boxes.push_back({{2.0f * i, 0, 0}, {2.0f * i + 1, 1, 1}});
    const BinaryBvh bvh = BinaryBvh::build(boxes);
    uint64_t tests = 0;
    std::vector<uint32_t> order;
    float t_max = std::numeric_limits<float>::infinity();
    bvh.nearest({{-1, 0.5f, 0.5f}, {1, 0, 0}}, 0.0f, t_max, tests, [&](uint32_t slot, float& t) {
        const uint32_t id = bvh.order()[slot];
        order.push_back(id);
        t = std::min(t, 2.0f * id + 1);  // the entry distance of box id
    });
    ASSERT_FALSE(order.empty());
    EXPECT_EQ(order.front(), 0u);
    EXPECT_LE(order.size(), 8u);  // one leaf or so, not all 64
    // the same ray the other way round starts from the last box
    order.clear();
    t_max = std::numeric_limits<float>::infinity();
    bvh.nearest({{200, 0.5f, 0.5f}, {-1, 0, 0}}, 0.0f, t_max, tests, [&](uint32_t slot, float& t) {
        const uint32_t id = bvh.order()[slot];
        order.push_back(id);
        t = std::min(t, 200.0f - (2.0f * id + 1));
    });
    ASSERT_FALSE(order.empty());
    EXPECT_EQ(*std::max_element(order.begin(), order.end()), 63u);
    EXPECT_LE(order.size(), 8u);
    // any() stops when told to
    int visits = 0;
    EXPECT_TRUE(bvh.any({{-1, 0.5f, 0.5f}, {1, 0, 0}}, 0.0f, 1000.0f, tests,
                        [&](uint32_t) { return ++visits == 3; }));
    EXPECT_EQ(visits, 3);
    EXPECT_FALSE(
        bvh.any({{-1, 5, 0.5f}, {1, 0, 0}}, 0.0f, 1000.0f, tests, [&](uint32_t) { return true; }));
}

}  // namespace
}  // namespace luz
