// Sphere lanes (geometry/sphere_group.h): four spheres tested at once must give the very bits
// world_sphere_roots() gives one by one, and flag exactly the lanes that need its double path.
#include "geometry/sphere_group.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "geometry_fixtures.h"

namespace luz {
namespace {

using test::random_direction;
using test::random_point;
using test::Rng;
using test::uniform;

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof(float)) == 0; }

/// Up to four spheres in world form by lane, as a BVH block holds them; unused lanes repeat the
/// sphere added last.
struct SphereGroup {
    float cx[4], cy[4], cz[4], rr[4], radius[4];
    int count = 0;
    SphereLanes lanes() const { return {cx, cy, cz, rr, radius, (1u << count) - 1}; }
};

/// Adds sphere s to the last group, or to a new one; its lane number over all groups.
int add_to_sphere_groups(std::vector<SphereGroup>& groups, const Shape& s) {
    if (groups.empty() || groups.back().count == 4) groups.emplace_back();
    SphereGroup& g = groups.back();
    for (int k = g.count; k < 4; ++k) {
        g.cx[k] = s.centre.x;
        g.cy[k] = s.centre.y;
        g.cz[k] = s.centre.z;
        g.rr[k] = s.radius * s.radius;
        g.radius[k] = s.radius;
    }
    const int lane = g.count++;
    return static_cast<int>(groups.size() - 1) * 4 + lane;
}

TEST(SphereLanes, FourAtOnceEqualsOneByOneBitForBit) {
    Rng rng(11);
    int hits = 0, slow = 0, compared = 0, behind = 0;
    for (int scene = 0; scene < 200; ++scene) {
        // 1 to 8 spheres of very different sizes (two groups when more than four)
        std::vector<Shape> spheres(1 + scene % 8);
        std::vector<SphereGroup> groups;
        for (size_t i = 0; i < spheres.size(); ++i) {
            Shape& s = spheres[i];
            s.world_form = true;
            s.centre = random_point(rng, -5, 5);
            s.radius = (scene % 3 == 0 ? 100.0f : 1.0f) * uniform(rng, 0.01f, 2.0f);
            const int lane = add_to_sphere_groups(groups, s);
            ASSERT_EQ(lane, static_cast<int>(i));
        }
        for (int k = 0; k < 500; ++k) {
            // origins far, near, and on a sphere (1e-4 off it, as spawned rays start), where
            // the float test hands over to double
            Vec3 origin = random_point(rng, -20, 20);
            const Shape& on = spheres[static_cast<size_t>(k) % spheres.size()];
            if (k % 3 == 0) {
                origin =
                    on.centre + random_direction(rng) * (on.radius + ((k & 4) ? 1e-4f : -1e-4f));
            }
            Vec3 direction = random_direction(rng);
            if (k % 5 == 0) direction = direction * 3.0f;  // not unit
            if (k == 7) direction = Vec3{0.0f};            // degenerate: all to double
            const Ray r{origin, direction};
            for (const SphereGroup& g : groups) {
                const SphereGroupRoots fast = sphere_lanes_roots(g.lanes(), r);
                for (int lane = 0; lane < g.count; ++lane) {
                    const unsigned bit = 1u << lane;
                    float t0 = 0, t1 = 0;
                    const bool hit = world_sphere_roots({g.cx[lane], g.cy[lane], g.cz[lane]},
                                                        g.radius[lane], r, t0, t1);
                    ++compared;
                    // world_sphere_roots()' own condition for its double path
                    const Vec3 o = r.origin - Vec3{g.cx[lane], g.cy[lane], g.cz[lane]};
                    const float oo = dot(o, o), rr = g.radius[lane] * g.radius[lane];
                    const bool needs_double = std::fabs(oo - rr) < 0x1p-17f * std::max(oo, rr) ||
                                              !(dot(r.direction, r.direction) > 0);
                    ASSERT_EQ(needs_double, (fast.slow & bit) != 0)
                        << "scene " << scene << " ray " << k << " lane " << lane;
                    if (fast.slow & bit) {  // the caller tests it alone
                        ++slow;
                        EXPECT_FALSE(fast.hit & bit);
                        continue;
                    }
                    ASSERT_EQ(hit, (fast.hit & bit) != 0) << "scene " << scene << " ray " << k;
                    if (!hit) continue;
                    ++hits;
                    ASSERT_TRUE(same_bits(t0, fast.t0[lane]) && same_bits(t1, fast.t1[lane]))
                        << "scene " << scene << " ray " << k << " lane " << lane << ": " << t0
                        << ", " << t1 << " vs " << fast.t0[lane] << ", " << fast.t1[lane];
                }
                // Ahead only (the scene queries): the same lanes and bits, less those whose
                // roots are both at t ≤ 0, which no query with t_min ≥ 0 takes.
                const SphereGroupRoots ahead = sphere_lanes_roots(g.lanes(), r, true);
                ASSERT_EQ(ahead.slow, fast.slow);
                ASSERT_EQ(ahead.hit & ~fast.hit, 0u);
                for (int lane = 0; lane < g.count; ++lane) {
                    const unsigned bit = 1u << lane;
                    if (ahead.hit & bit) {
                        ASSERT_TRUE(same_bits(ahead.t0[lane], fast.t0[lane]) &&
                                    same_bits(ahead.t1[lane], fast.t1[lane]));
                    } else if (fast.hit & bit) {
                        ++behind;
                        ASSERT_LE(fast.t0[lane], 0.0f) << "scene " << scene << " ray " << k;
                        ASSERT_LE(fast.t1[lane], 0.0f) << "scene " << scene << " ray " << k;
                    }
                }
                EXPECT_EQ(fast.hit >> g.count, 0u);  // unused lanes are never reported
                EXPECT_EQ(fast.slow >> g.count, 0u);
                // the portable version agrees too, and leaves nothing to the caller
                const SphereGroupRoots one = sphere_lanes_roots_one_by_one(g.lanes(), r);
                EXPECT_EQ(one.slow, 0u);
                EXPECT_EQ(one.hit & ~fast.slow, fast.hit);
            }
        }
    }
    EXPECT_GT(hits, compared / 10);
    EXPECT_GT(slow, compared / 50);    // rays from on a sphere, and the zero direction
    EXPECT_GT(behind, compared / 50);  // rays leaving a sphere, and spheres behind an origin
}

}  // namespace
}  // namespace luz
