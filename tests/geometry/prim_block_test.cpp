// intersect_triangles4() against intersect_triangle(), lane by lane: on random triangles, on
// triangles sharing edges and vertices that rays pass through exactly (where an edge function is
// 0 and the test defers to the double path), on axis-aligned rays and on degenerate triangles,
// every lane gives the scalar test's decision and, on a hit, its very t and barycentrics.
// axis_lanes_missed() rejects only lanes the exact cylinder and cone tests miss.
#include "geometry/prim_block.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <set>
#include <vector>

#include "bvh_fixtures.h"
#include "geometry/scene.h"
#include "geometry/shapes.h"
#include "geometry_fixtures.h"

namespace luz {
namespace {

using test::cylinder_field;
using test::random_direction;
using test::random_point;
using test::Rng;
using test::scene_with;
using test::uniform;

uint32_t bits(float x) {
    uint32_t u;
    std::memcpy(&u, &x, sizeof u);
    return u;
}

struct Triangle {
    Vec3 p[3];
};

PrimBlock block_of(const Triangle* t) {
    PrimBlock b;
    for (int k = 0; k < 4; ++k) {
        for (int c = 0; c < 3; ++c)
            for (int a = 0; a < 3; ++a) b.v[c][a][k] = t[k].p[c][a];
        b.shape[k] = 0;
        b.triangle[k] = static_cast<uint32_t>(k);
    }
    return b;
}

/// Lane k of the block test against the scalar test, for the four triangles and ray r; counts
/// the hits and the lanes left to the double path.
void expect_same_as_scalar(const Triangle* tris, const Ray& r, float t_min, float t_max, int& hits,
                           int& deferred) {
    const WatertightRay w = prepare_watertight(r);
    const PrimBlock b = block_of(tris);
    Lane4f t, b1, b2;
    unsigned scalar;
    const unsigned hit = intersect_triangles4(w, b, t_min, t_max, t, b1, b2, scalar);
    ASSERT_EQ(hit & scalar, 0u);
    for (int k = 0; k < 4; ++k) {
        float ts = 0, b1s = 0, b2s = 0;
        const bool hs = intersect_triangle(w, tris[k].p[0], tris[k].p[1], tris[k].p[2], t_min,
                                           t_max, ts, b1s, b2s);
        if ((scalar >> k) & 1u) {
            ++deferred;  // the caller tests this lane with intersect_triangle() itself
            continue;
        }
        ASSERT_EQ(((hit >> k) & 1u) != 0, hs) << "lane " << k;
        if (!hs) continue;
        ++hits;
        EXPECT_EQ(bits(t[k]), bits(ts));
        EXPECT_EQ(bits(b1[k]), bits(b1s));
        EXPECT_EQ(bits(b2[k]), bits(b2s));
    }
}

TEST(PrimBlock, RandomTrianglesGiveTheScalarAnswersBitForBit) {
    Rng rng(11);
    int hits = 0, deferred = 0;
    for (int i = 0; i < 20000; ++i) {
        Triangle tris[4];
        for (Triangle& t : tris) {
            const Vec3 c = random_point(rng, -2, 2);
            for (Vec3& p : t.p) p = c + random_point(rng, -1.5f, 1.5f);
        }
        // rays aimed at one of the triangles (so that about a quarter hit), or anywhere
        const Vec3 o = random_point(rng, -5, 5);
        const Triangle& aim = tris[i % 4];
        const float u = uniform(rng, 0, 1), v = uniform(rng, 0, 1 - u);
        const Vec3 target = aim.p[0] + (aim.p[1] - aim.p[0]) * u + (aim.p[2] - aim.p[0]) * v;
        const Vec3 d = i % 3 == 0 ? random_direction(rng) : normalize(target - o);
        const float t_max = i % 5 == 0 ? uniform(rng, 0.5f, 6) : 1e30f;
        expect_same_as_scalar(tris, Ray{o, d}, 1e-4f, t_max, hits, deferred);
    }
    EXPECT_GT(hits, 10000);
}

// Rays through the shared vertices and edges of a grid (exactly, in float): edge functions of
// 0, which the block leaves to the double path, and the watertight test's ties.
TEST(PrimBlock, SharedEdgesAndVerticesAndAxisRays) {
    int hits = 0, deferred = 0;
    const Triangle grid[4] = {{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}},
                              {{{0, 0, 0}, {1, 1, 0}, {0, 1, 0}}},
                              {{{1, 0, 0}, {2, 0, 0}, {2, 1, 0}}},
                              {{{1, 0, 0}, {2, 1, 0}, {1, 1, 0}}}};
    for (float x : {0.0f, 0.25f, 0.5f, 1.0f, 1.5f, 2.0f}) {
        for (float y : {0.0f, 0.5f, 1.0f}) {
            for (const Vec3& d : {Vec3{0, 0, -1}, Vec3{0, 0, 1}, normalize(Vec3{0.3f, 0.2f, -1})}) {
                const Vec3 o = Vec3{x, y, 0} - d * 3.0f;
                expect_same_as_scalar(grid, Ray{o, d}, 0.0f, 1e30f, hits, deferred);
            }
        }
    }
    EXPECT_GT(hits, 5);
    EXPECT_GT(deferred, 0);  // the double path is reached
    // degenerate lanes: zero area, a point, NaN vertices (padding)
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const Triangle odd[4] = {{{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}},
                             {{{0.5f, 0.5f, 0}, {0.5f, 0.5f, 0}, {0.5f, 0.5f, 0}}},
                             {{{nan, nan, nan}, {nan, nan, nan}, {nan, nan, nan}}},
                             {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}};
    const unsigned before = static_cast<unsigned>(hits);
    for (const Vec3& d : {Vec3{0, 0, -1}, normalize(Vec3{0.1f, -0.2f, 1})}) {
        expect_same_as_scalar(odd, Ray{Vec3{0.25f, 0.25f, 0} - d * 2.0f, d}, 0.0f, 1e30f, hits,
                              deferred);
    }
    EXPECT_EQ(static_cast<unsigned>(hits), before + 2);  // only the real triangle
}

TEST(PrimBlock, TriangleLanesAndPaddingLanes) {
    PrimBlock b;
    for (int k = 0; k < 4; ++k) {
        b.shape[k] = 0;
        b.triangle[k] = k == 2 ? PrimBlock::kNotTriangle : static_cast<uint32_t>(k);
    }
    EXPECT_EQ(b.triangle_lanes(), 0b1011u);
    EXPECT_EQ(b.sphere_lanes(), 0u);
    b.triangle[0] = PrimBlock::kSphere;
    EXPECT_EQ(b.triangle_lanes(), 0b1010u);
    EXPECT_EQ(b.sphere_lanes(), 0b0001u);
}

// A block's sphere lanes (centre, radius², radius by lane) give world_sphere_roots()'s roots,
// lane for lane, whatever the other lanes hold (triangles, padding).
TEST(PrimBlock, SphereLanesGiveTheScalarRoots) {
    Rng rng(7);
    int hits = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        PrimBlock b;
        const float nan = std::numeric_limits<float>::quiet_NaN();
        for (auto& corner : b.v)
            for (auto& axis : corner)
                for (float& x : axis) x = nan;
        Vec3 centre[4];
        float radius[4];
        for (int k = 0; k < 4; ++k) {
            centre[k] = random_point(rng, -2.0f, 2.0f);
            radius[k] = uniform(rng, 0.05f, 1.0f);
            b.shape[k] = static_cast<uint32_t>(k);
            b.triangle[k] = k == 3 ? 0u : PrimBlock::kSphere;  // lane 3: a (NaN) triangle
            for (int a = 0; a < 3; ++a) b.v[0][a][k] = centre[k][a];
            b.v[1][0][k] = radius[k] * radius[k];
            b.v[1][1][k] = radius[k];
        }
        const unsigned spheres = b.sphere_lanes();
        ASSERT_EQ(spheres, 0b0111u);
        // rays from outside and from a sphere's surface (the double path)
        Vec3 o = random_point(rng, -4.0f, 4.0f);
        if (trial % 4 == 0) o = centre[0] + random_direction(rng) * radius[0];
        Vec3 d = random_direction(rng);
        if (trial % 2 == 1) d = normalize(centre[trial % 3] + random_direction(rng) - o);
        const Ray r{o, d * uniform(rng, 0.5f, 2.0f)};
        const SphereGroupRoots q = sphere_lanes_roots(b.spheres(spheres), r);
        for (int k = 0; k < 3; ++k) {
            float t0 = 0, t1 = 0;
            const bool met = world_sphere_roots(centre[k], radius[k], r, t0, t1);
            if ((q.slow >> k) & 1u) continue;  // the caller tests it alone
            ASSERT_EQ(((q.hit >> k) & 1u) != 0, met) << trial << " lane " << k;
            if (!met) continue;
            ++hits;
            EXPECT_EQ(bits(q.t0[k]), bits(t0));
            EXPECT_EQ(bits(q.t1[k]), bits(t1));
        }
        EXPECT_EQ((q.hit | q.slow) & ~spheres, 0u);
    }
    EXPECT_GT(hits, 300);
}

// axis_lanes_missed() rejects a lane only when the exact test misses the whole line, and it
// rejects many lanes (rays through the cylinders' surfaces and
// just outside them included).
TEST(PrimBlock, AxisLanesMissedOnlyWhatTheExactTestMisses) {
    Rng rng(4);
    const BuiltScene scene = build_scene(scene_with(cylinder_field(rng)));
    ASSERT_EQ(scene.root_leaf, 0u);
    std::vector<std::pair<const PrimBlock*, int>> lanes;
    std::set<uint32_t> shapes, cylinder_lanes;
    for (const PrimBlock& b : scene.bvh_blocks) {
        for (unsigned a = b.axis_lanes(); a != 0; a &= a - 1)
            lanes.push_back({&b, __builtin_ctz(a)});
        for (unsigned c = b.cylinder_lanes(); c != 0; c &= c - 1) {
            shapes.insert(b.shape[__builtin_ctz(c)]);
            cylinder_lanes.insert(b.shape[__builtin_ctz(c)]);
        }
    }
    // each of the 300 cylinders and cones, the long slanted ones as pieces in several leaves:
    // the open round cylinders in cylinder lanes (ray_cylinder.h), the others in axis lanes
    for (const auto& [b, lane] : lanes) shapes.insert(b->shape[lane]);
    ASSERT_EQ(shapes.size(), 300u);
    ASSERT_GT(cylinder_lanes.size(), 50u);
    ASSERT_GT(lanes.size(), 150u);
    const float inf = std::numeric_limits<float>::infinity();
    int rejected = 0, tested = 0, grazing_hits = 0;
    for (int k = 0; k < 200000; ++k) {
        const auto [b, lane] = lanes[rng() % lanes.size()];
        const Shape& s = scene.shapes[b->shape[lane]];
        ASSERT_TRUE(s.type == ShapeType::cylinder || s.type == ShapeType::cone);
        // aimed at a point on (or just off) the side or a rim, or anywhere
        const float phi = uniform(rng, 0, 6.2831853f);
        float rho = k % 3 == 0 ? 1.0f : uniform(rng, 0.99f, 1.01f);
        float z = k % 5 == 0 ? 1.0f : uniform(rng, 0, 1);
        if (s.type == ShapeType::cone) {  // radius 1 − z
            z = k % 5 == 0 ? 0.0f : z;
            rho *= 1 - z;
        }
        const Vec3 target =
            s.transform.world_from_object.point({rho * std::cos(phi), rho * std::sin(phi), z});
        Ray r{random_point(rng, -6, 6), random_direction(rng)};
        if (k % 2 == 0) r.direction = (target - r.origin) * uniform(rng, 0.1f, 3.0f);
        const bool missed = (axis_lanes_missed(*b, 1u << lane, r) >> lane) & 1u;
        Hit h;
        const bool met = intersect(s, r, -inf, inf, h);
        ++tested;
        rejected += missed;
        grazing_hits += met && rho != 1.0f;
        if (missed) {
            ASSERT_FALSE(met) << "ray " << k << " lane " << lane;
        }
    }
    EXPECT_GT(rejected, tested / 3);
    EXPECT_GT(grazing_hits, 1000);
}

}  // namespace
}  // namespace luz
