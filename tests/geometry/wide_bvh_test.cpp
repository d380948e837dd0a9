// WideBvh (Bvh4, Bvh8): the collapsed trees hold every primitive once, inside boxes that are
// the binary tree's; their traversals give the binary tree's answers (nearest hit with ties,
// any hit, rays in the plane of a box face); the collapse keeps the leaves and has the least
// SAH; the tree is the same for any thread count.
#include "geometry/wide_bvh.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <set>
#include <vector>

#include "bvh_reference.h"
#include "geometry/shapes.h"
#include "geometry_fixtures.h"

namespace luz {
namespace {

using test::random_point;
using test::Rng;
using test::uniform;

/// A triangle soup in [−4, 4]³ on a grid of 1/8 (exactly representable: shared vertices,
/// coplanar faces and ties are common), and its boxes.
struct Soup {
    std::vector<Vec3> p;  // 3 per triangle
    std::vector<Bounds3> boxes;
};

Soup make_soup(int n, uint32_t seed) {
    Rng rng(seed);
    const auto grid = [&] {
        return Vec3{std::round(uniform(rng, -32, 32)) / 8, std::round(uniform(rng, -32, 32)) / 8,
                    std::round(uniform(rng, -32, 32)) / 8};
    };
    Soup s;
    for (int t = 0; t < n; ++t) {
        const Vec3 a = grid();
        Vec3 b = a + (grid() * 0.125f), c = a + (grid() * 0.125f);
        if (t % 5 == 0) b.z = c.z = a.z;  // axis-aligned faces: box faces in their planes
        s.p.insert(s.p.end(), {a, b, c});
        Bounds3 box;
        box.expand(a);
        box.expand(b);
        box.expand(c);
        s.boxes.push_back(box);
    }
    return s;
}

/// The nearest hit of r among the soup's triangles through `bvh` (ties: the lowest triangle),
/// as (t, triangle), or (∞, −1).
template <class B>
std::pair<float, int> nearest(const B& bvh, const Soup& s, const Ray& r) {
    const WatertightRay w = prepare_watertight(r);
    float best = std::numeric_limits<float>::infinity();
    int tri = -1;
    uint64_t boxes = 0;
    float t_max = best;
    bvh.nearest(r, 0.0f, t_max, boxes, [&](uint32_t slot, float& limit) {
        const uint32_t id = bvh.order()[slot];
        float t, b1, b2;
        if (intersect_triangle(w, s.p[3 * id], s.p[3 * id + 1], s.p[3 * id + 2], 0.0f,
                               std::nextafter(best, std::numeric_limits<float>::infinity()), t, b1,
                               b2) &&
            (t < best || (t == best && static_cast<int>(id) < tri))) {
            best = t;
            tri = static_cast<int>(id);
            limit = best;
        }
    });
    return {best, tri};
}

/// Whether any triangle meets r in (0, t_max), through `bvh`.
template <class B>
bool any_hit(const B& bvh, const Soup& s, const Ray& r, float t_max) {
    const WatertightRay w = prepare_watertight(r);
    uint64_t boxes = 0;
    return bvh.any(r, 0.0f, t_max, boxes, [&](uint32_t slot) {
        const uint32_t id = bvh.order()[slot];
        float t, b1, b2;
        return intersect_triangle(w, s.p[3 * id], s.p[3 * id + 1], s.p[3 * id + 2], 0.0f, t_max, t,
                                  b1, b2);
    });
}

/// Random rays, a quarter aimed at vertices, an eighth along an axis through grid points
/// (origins on box face planes, zero direction components, ±0).
std::vector<Ray> random_rays(const Soup& s, int n, uint32_t seed) {
    Rng rng(seed);
    std::vector<Ray> rays;
    for (int k = 0; k < n; ++k) {
        Ray r{random_point(rng, -6, 6), normalize(random_point(rng, -1, 1))};
        if (k % 4 == 0) {
            const Vec3 to = s.p[rng() % s.p.size()] - r.origin;
            if (length(to) > 0) r.direction = normalize(to);
        } else if (k % 8 == 1) {
            const Vec3 v = s.p[rng() % s.p.size()];
            const int axis = static_cast<int>(rng() % 3);
            r.origin = v;
            r.origin[axis] = k % 16 == 1 ? -6.0f : 6.0f;
            r.direction = Vec3{k % 3 == 0 ? -0.0f : 0.0f};
            r.direction[axis] = k % 16 == 1 ? 1.0f : -1.0f;
        }
        rays.push_back(r);
    }
    return rays;
}

template <class B>
void expect_same_answers_as_binary(int triangles, uint32_t seed) {
    const Soup s = make_soup(triangles, seed);
    const BinaryBvh binary = BinaryBvh::build(s.boxes);
    const B wide(Bvh::build(s.boxes));
    ASSERT_GT(wide.nodes().size(), 1u);
    EXPECT_EQ(wide.order(), binary.order());
    int hits = 0;
    for (const Ray& r : random_rays(s, 20000, seed + 1)) {
        const auto a = nearest(binary, s, r), b = nearest(wide, s, r);
        ASSERT_EQ(a.second, b.second) << r.origin.x << " " << r.direction.x;
        if (a.second >= 0) {
            ASSERT_EQ(a.first, b.first);
            ++hits;
            ASSERT_EQ(any_hit(binary, s, r, a.first * 1.01f), any_hit(wide, s, r, a.first * 1.01f));
            ASSERT_EQ(any_hit(binary, s, r, a.first * 0.99f), any_hit(wide, s, r, a.first * 0.99f));
        }
    }
    EXPECT_GT(hits, 2000);
}

TEST(WideBvh, Bvh4GivesTheBinaryAnswers) { expect_same_answers_as_binary<Bvh4>(3000, 5); }
TEST(WideBvh, Bvh8GivesTheBinaryAnswers) { expect_same_answers_as_binary<Bvh8>(3000, 6); }

/// Every slot in exactly one leaf, each primitive inside its leaf's box, each child's box
/// inside the box its parent holds for it; unused children empty.
template <class B>
void check_structure(const B& bvh, const std::vector<Bounds3>& boxes) {
    using Node = typename B::Node;
    constexpr int W = sizeof(Node::child) / sizeof(uint32_t);
    std::vector<int> seen(bvh.order().size(), 0);
    std::set<uint32_t> reached{0};
    // (node, box the parent gives it)
    std::vector<std::pair<uint32_t, Bounds3>> stack{{0u, Bounds3{Vec3{-1e30f}, Vec3{1e30f}}}};
    while (!stack.empty()) {
        const auto [i, outer] = stack.back();
        stack.pop_back();
        const Node& n = bvh.nodes()[i];
        for (int j = 0; j < W; ++j) {
            const Bounds3 box{{n.lo[0][j], n.lo[1][j], n.lo[2][j]},
                              {n.hi[0][j], n.hi[1][j], n.hi[2][j]}};
            if (n.child[j] == Node::kUnused) {
                EXPECT_EQ(n.count[j], 0u);
                EXPECT_TRUE(box.empty());
                continue;
            }
            for (int a = 0; a < 3; ++a) {
                EXPECT_GE(box.lo[a], outer.lo[a]);
                EXPECT_LE(box.hi[a], outer.hi[a]);
            }
            if (n.count[j] > 0) {
                for (uint32_t s = n.child[j]; s < n.child[j] + n.count[j]; ++s) {
                    ++seen[s];
                    const Bounds3& b = boxes[bvh.order()[s]];
                    for (int a = 0; a < 3; ++a) {
                        EXPECT_GE(b.lo[a], box.lo[a]);
                        EXPECT_LE(b.hi[a], box.hi[a]);
                    }
                }
            } else {
                EXPECT_GT(n.child[j], i);  // depth first
                EXPECT_TRUE(reached.insert(n.child[j]).second);
                stack.push_back({n.child[j], box});
            }
        }
    }
    EXPECT_EQ(reached.size(), bvh.nodes().size());
    for (size_t s = 0; s < seen.size(); ++s) ASSERT_EQ(seen[s], 1) << s;
}

TEST(WideBvh, EveryPrimitiveOnceInsideItsBoxes) {
    const Soup s = make_soup(5000, 9);
    check_structure(Bvh4(Bvh::build(s.boxes)), s.boxes);
    check_structure(Bvh8(Bvh::build(s.boxes)), s.boxes);
}

/// Half the surface area of a box given by lo/hi.
float half_area(const float* lo, const float* hi) {
    const float dx = hi[0] - lo[0], dy = hi[1] - lo[1], dz = hi[2] - lo[2];
    return dx * dy + dy * dz + dz * dx;
}

/// The SAH of a wide BVH over fixed leaves: Σ over its nodes of the area of the box around
/// their children (the binary node it stands for); and its leaves as (first slot, count).
template <class B>
double wide_sah(const B& bvh, std::set<std::pair<uint32_t, uint32_t>>& leaves) {
    using Node = typename B::Node;
    constexpr int W = sizeof(Node::child) / sizeof(uint32_t);
    double sah = 0;
    for (const Node& n : bvh.nodes()) {
        float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
        for (int j = 0; j < W; ++j) {
            if (n.child[j] == Node::kUnused) continue;
            if (n.count[j] > 0) leaves.insert({n.child[j], n.count[j]});
            for (int a = 0; a < 3; ++a) {
                lo[a] = std::min(lo[a], n.lo[a][j]);
                hi[a] = std::max(hi[a], n.hi[a][j]);
            }
        }
        sah += half_area(lo, hi);
    }
    return sah;
}

/// The SAH of the greedy collapse of binary node b's subtree (each wide node opens its
/// largest interior child until it has W), counting its nodes in `nodes`.
double greedy_sah(const HugeVector<BvhNode>& bin, uint32_t b, int W, size_t& nodes) {
    ++nodes;
    double sah = half_area(bin[b].lo, bin[b].hi);
    if (bin[b].leaf()) return sah;
    std::vector<uint32_t> kids{b + 1, bin[b].offset};
    while (static_cast<int>(kids.size()) < W) {
        int open = -1;
        float largest = -1;
        for (size_t i = 0; i < kids.size(); ++i) {
            const BvhNode& n = bin[kids[i]];
            if (!n.leaf() && half_area(n.lo, n.hi) > largest) {
                largest = half_area(n.lo, n.hi);
                open = static_cast<int>(i);
            }
        }
        if (open < 0) break;
        const uint32_t c = kids[open];
        kids[open] = c + 1;
        kids.insert(kids.begin() + open + 1, bin[c].offset);
    }
    for (uint32_t k : kids)
        if (!bin[k].leaf()) sah += greedy_sah(bin, k, W, nodes);
    return sah;
}

/// A bumpy height field of n × n quads (two triangles each), as a soup.
Soup make_grid(int n) {
    Soup s;
    const auto at = [](int i, int j) {
        return Vec3{static_cast<float>(i), static_cast<float>(j),
                    0.3f * std::sin(0.7f * i) * std::cos(0.5f * j)};
    };
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            const Vec3 q[4] = {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
            for (const Vec3* t : {q, q + 1}) {
                const Vec3 a = q[0], b = t[1], c = t[2];
                s.p.insert(s.p.end(), {a, b, c});
                Bounds3 box;
                box.expand(a);
                box.expand(b);
                box.expand(c);
                s.boxes.push_back(box);
            }
        }
    }
    return s;
}

/// The collapse keeps the binary tree's leaves and picks its wide nodes by least SAH: never
/// worse than opening the largest child first, and better (with fewer, fuller nodes) on a
/// regular mesh, where that greedy rule leaves many nodes with two leaves.
template <class B>
void expect_least_sah(const Soup& s, bool fewer_nodes) {
    constexpr int W = sizeof(B::Node::child) / sizeof(uint32_t);
    const BinaryBvh binary = BinaryBvh::build(s.boxes);
    std::set<std::pair<uint32_t, uint32_t>> binary_leaves, wide_leaves;
    for (const BvhNode& n : binary.nodes())
        if (n.leaf()) binary_leaves.insert({n.offset, n.count});
    size_t greedy_nodes = 0;
    const double greedy = greedy_sah(binary.nodes(), 0, W, greedy_nodes);
    const B wide(Bvh::build(s.boxes));
    const double sah = wide_sah(wide, wide_leaves);
    EXPECT_EQ(wide_leaves, binary_leaves);
    EXPECT_LE(sah, greedy * (1 + 1e-6));
    if (fewer_nodes) {
        EXPECT_LT(sah, greedy * 0.99);
        EXPECT_LT(wide.nodes().size(), greedy_nodes * 3 / 4);
    }
}

TEST(WideBvh, CollapseHasTheLeastSah) {
    for (uint32_t seed : {1u, 2u, 3u}) {
        expect_least_sah<Bvh4>(make_soup(2000, seed), false);
        expect_least_sah<Bvh8>(make_soup(2000, seed), false);
    }
    expect_least_sah<Bvh4>(make_grid(40), false);
    expect_least_sah<Bvh8>(make_grid(40), true);
}

TEST(WideBvh, EmptyAndSingleLeaf) {
    EXPECT_TRUE(Bvh8(Bvh::build({})).empty());
    const std::vector<Bounds3> same(100, Bounds3{{0, 0, 0}, {1, 1, 1}});
    const Bvh8 one(Bvh::build(same));  // a leaf root: one wide node with one leaf child
    ASSERT_EQ(one.nodes().size(), 1u);
    EXPECT_EQ(one.nodes()[0].count[0], 100u);
    int visited = 0;
    uint64_t tests = 0;
    float t_max = 10;
    one.nearest({{0.5f, 0.5f, -1}, {0, 0, 1}}, 0.0f, t_max, tests,
                [&](uint32_t, float&) { ++visited; });
    EXPECT_EQ(visited, 100);
    EXPECT_EQ(tests, 8u);  // one node visit: its eight boxes
    visited = 0;
    one.nearest({{5, 5, -1}, {0, 0, 1}}, 0.0f, t_max, tests, [&](uint32_t, float&) { ++visited; });
    EXPECT_EQ(visited, 0);
    EXPECT_EQ(tests, 16u);
    // any(): counted whether it stops at a hit or runs out of nodes
    EXPECT_TRUE(
        one.any({{0.5f, 0.5f, -1}, {0, 0, 1}}, 0.0f, 10.0f, tests, [](uint32_t) { return true; }));
    EXPECT_EQ(tests, 24u);
    EXPECT_FALSE(
        one.any({{0.5f, 0.5f, -1}, {0, 0, 1}}, 0.0f, 10.0f, tests, [](uint32_t) { return false; }));
    EXPECT_EQ(tests, 32u);
}

// hit_wide() on the distances' bits as integers (WideRay::as_ints, AVX2 builds) against the
// float minima and maxima: the same children hit, at the same entry distances, for rays from
// inside, outside and on the faces of grid-aligned boxes (−0 and exact-zero distances), with
// unused children (empty boxes) and an exit before or at the entry.
TEST(WideBvh, SlabDistancesAsIntegersGiveTheFloatAnswers) {
    Rng rng(5);
    const auto grid = [&] { return std::round(uniform(rng, -16, 16)) / 4; };
    int hits = 0;
    for (int i = 0; i < 20000; ++i) {
        Bvh8::Node n;
        for (int k = 0; k < 8; ++k) {
            for (int a = 0; a < 3; ++a) {
                const float x = grid(), y = grid();
                n.lo[a][k] = std::min(x, y);
                n.hi[a][k] = std::max(x, y);
            }
            if (k == 7 || rng() % 8 == 0) {  // unused
                for (int a = 0; a < 3; ++a) {
                    n.lo[a][k] = std::numeric_limits<float>::infinity();
                    n.hi[a][k] = -std::numeric_limits<float>::infinity();
                }
            }
            n.child[k] = n.count[k] = 0;
        }
        const Vec3 o{grid(), grid(), grid()};
        Vec3 d = test::random_direction(rng);
        if (i % 3 == 0) d = Vec3{grid(), grid(), grid()};  // a component of ±0 now and then
        if (!(std::isfinite(1 / d.x) && std::isfinite(1 / d.y) && std::isfinite(1 / d.z))) continue;
        const float t_min = i % 2 ? 0.0f : 1e-4f;
        const float t_max = i % 5 == 0 ? uniform(rng, 0, 3) : 1e30f;
        bvh_detail::WideRay<8> as_ints({o, d}, t_min), as_floats({o, d}, t_min);
        as_floats.as_ints = false;
#if defined(__AVX2__)
        ASSERT_TRUE(as_ints.as_ints);
#endif
        float e_int[8], e_float[8];
        const int m_int = bvh_detail::hit_wide<8>(n, as_ints, t_min, t_max, e_int);
        const int m_float = bvh_detail::hit_wide<8>(n, as_floats, t_min, t_max, e_float);
        ASSERT_EQ(m_int, m_float) << i;
        for (int k = 0; k < 8; ++k) {
            if ((m_int >> k) & 1) {
                EXPECT_EQ(e_int[k], e_float[k]) << i << " " << k;
            }
        }
        hits += __builtin_popcount(static_cast<unsigned>(m_int));
    }
    EXPECT_GT(hits, 10000);
    // a ray with a zero direction component, or a negative t_min, takes the float path
    EXPECT_FALSE(bvh_detail::WideRay<8>(Ray{{0, 0, 0}, {0, 0, 1}}, 0.0f).as_ints);
    EXPECT_FALSE(bvh_detail::WideRay<8>(Ray{{0, 0, 0}, {0.6f, 0.8f, 0.1f}}, -1.0f).as_ints);
}

#if defined(__AVX2__) && defined(__FMA__)
// The padded slab test (WideRay::padded, one fused multiply-add per plane) against the exact
// float test and against the slab distances in double: every child either of them hits, it
// hits, at an entry no later. Boxes near the origin and 1000 away, rays from inside, from far
// away and along faces with tiny direction components (1/direction up to ~1e30).
TEST(WideBvh, PaddedSlabTestHitsEveryChildTheExactTestHits) {
    Rng rng(11);
    int hits = 0, padded_rays = 0, extra = 0;
    for (int i = 0; i < 40000; ++i) {
        const float offset = i % 2 ? 1000.0f : 0.0f;
        const auto grid = [&] { return offset + std::round(uniform(rng, -16, 16)) / 4; };
        Bvh8::Node n;
        float reach = 0.0f;
        for (int k = 0; k < 8; ++k) {
            for (int a = 0; a < 3; ++a) {
                const float x = grid(), y = i % 3 == 0 ? x : grid();  // flat boxes now and then
                n.lo[a][k] = std::min(x, y);
                n.hi[a][k] = std::max(x, y);
                reach = std::max({reach, std::fabs(n.lo[a][k]), std::fabs(n.hi[a][k])});
            }
            if (k == 7 || rng() % 8 == 0) {  // unused
                for (int a = 0; a < 3; ++a) {
                    n.lo[a][k] = std::numeric_limits<float>::infinity();
                    n.hi[a][k] = -std::numeric_limits<float>::infinity();
                }
            }
            n.child[k] = n.count[k] = 0;
        }
        Vec3 o{grid(), grid(), grid()};
        if (i % 5 == 1) o = o + test::random_direction(rng) * 5000.0f;  // a far camera
        Vec3 d = test::random_direction(rng);
        if (i % 4 == 2) {  // towards a box corner, nearly along an axis: huge 1/direction
            const int k = static_cast<int>(rng() % 7);
            const Vec3 corner{n.lo[0][k], n.hi[1][k], n.lo[2][k]};
            if (std::isfinite(corner.x)) d = normalize(corner - o);
            const int axis = static_cast<int>(rng() % 3);
            d[axis] = std::copysign(i % 8 == 2 ? 1e-30f : 1e-7f, uniform(rng, -1, 1));
        }
        const float t_min = i % 2 ? 0.0f : 1e-4f;
        const float t_max = i % 5 == 0 ? uniform(rng, 0, 3) : 1e30f;
        const bvh_detail::WideRay<8> padded({o, d}, t_min, reach), exact({o, d}, t_min);
        if (!padded.padded) continue;
        ++padded_rays;
        ASSERT_FALSE(exact.padded);
        float e_padded[8], e_exact[8];
        const int m_padded = bvh_detail::hit_wide<8>(n, padded, t_min, t_max, e_padded);
        const int m_exact = bvh_detail::hit_wide<8>(n, exact, t_min, t_max, e_exact);
        for (int k = 0; k < 8; ++k) {
            // the slab distances in double (the division exact to double precision)
            double tn = t_min, tf = t_max;
            if (!(n.lo[0][k] <= n.hi[0][k])) tn = 1, tf = 0;  // unused: empty
            for (int a = 0; a < 3; ++a) {
                double t0 = (static_cast<double>(n.lo[a][k]) - o[a]) / d[a];
                double t1 = (static_cast<double>(n.hi[a][k]) - o[a]) / d[a];
                if (t0 > t1) std::swap(t0, t1);
                tn = std::max(tn, t0);
                tf = std::min(tf, t1);
            }
            const bool truth = tn <= tf;
            const bool p = (m_padded >> k) & 1, e = (m_exact >> k) & 1;
            if (truth || e) {
                ASSERT_TRUE(p) << i << " " << k;
                if (truth) {
                    EXPECT_LE(e_padded[k], static_cast<float>(tn)) << i << " " << k;
                }
                if (e) {
                    EXPECT_LE(e_padded[k], e_exact[k]) << i << " " << k;
                }
            }
            extra += p && !truth;
            hits += truth;
        }
    }
    EXPECT_GT(padded_rays, 30000);
    EXPECT_GT(hits, 10000);
    // the padding is small: few boxes hit that the ray misses (the far camera's most; the
    // exact test has 181 such here, the padded one 622)
    EXPECT_LT(extra, hits / 10);
    // without a reach, or with a zero direction component, the exact test
    EXPECT_FALSE(bvh_detail::WideRay<8>(Ray{{0, 0, 0}, {0.6f, 0.8f, 0.1f}}, 0.0f).padded);
    EXPECT_FALSE(bvh_detail::WideRay<8>(Ray{{0, 0, 0}, {0, 0, 1}}, 0.0f, 10.0f).padded);
    EXPECT_TRUE(bvh_detail::WideRay<8>(Ray{{0, 0, 0}, {0.6f, 0.8f, 0.1f}}, 0.0f, 10.0f).padded);
}
#endif

TEST(WideBvh, SameTreeForAnyThreadCount) {
    std::vector<Bounds3> boxes;
    Rng rng(3);
    for (int i = 0; i < 300000; ++i) {
        const Vec3 c = random_point(rng, -100, 100);
        boxes.push_back({c, c + random_point(rng, 0, 0.5f)});
    }
    const auto build = [&](int threads) {
        Bvh8 bvh;
        tbb::task_arena arena(threads);
        arena.execute([&] { bvh = Bvh8::build(boxes); });
        return bvh;
    };
    const Bvh8 one = build(1), two = build(2), five = build(5);
    ASSERT_EQ(one.nodes().size(), two.nodes().size());
    ASSERT_EQ(one.nodes().size(), five.nodes().size());
    const size_t bytes = one.nodes().size() * sizeof(Bvh8::Node);
    EXPECT_EQ(std::memcmp(one.nodes().data(), two.nodes().data(), bytes), 0);
    EXPECT_EQ(std::memcmp(one.nodes().data(), five.nodes().data(), bytes), 0);
    EXPECT_EQ(one.order(), five.order());
    EXPECT_EQ(one.memory_bytes(), one.nodes().capacity() * sizeof(Bvh8::Node) +
                                      one.order().capacity() * sizeof(uint32_t));
}

}  // namespace
}  // namespace luz
