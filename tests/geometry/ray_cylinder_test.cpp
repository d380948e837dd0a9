// Open round cylinders in world form (geometry/ray_cylinder.h, shapes/cylinder.h): the lanes give
// the very bits world_cylinder_roots() gives one by one and flag the same rays for the double
// path; the world form agrees with the object-space test in double, to the formula on rays
// worked by hand; and only open cylinders that stay round take it.
#include "geometry/ray_cylinder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "geometry/shapes.h"
#include "geometry_fixtures.h"

namespace luz {
namespace {

using test::cylinder_desc;
using test::random_direction;
using test::random_point;
using test::Rng;
using test::uniform;
using test::user_transforms;

bool same_float_bits(float a, float b) { return std::memcmp(&a, &b, sizeof(float)) == 0; }

/// Up to four cylinders in world form by lane, as a BVH block holds them; unused lanes repeat
/// the cylinder added last.
struct CylinderGroup {
    float bx[4], by[4], bz[4], wx[4], wy[4], wz[4], rr[4], height[4];
    int count = 0;
    CylinderLanes lanes() const { return {bx, by, bz, wx, wy, wz, rr, height, (1u << count) - 1}; }
    void add(const Shape& s) {
        for (int k = count; k < 4; ++k) {
            bx[k] = s.centre.x, by[k] = s.centre.y, bz[k] = s.centre.z;
            wx[k] = s.normal.x, wy[k] = s.normal.y, wz[k] = s.normal.z;
            rr[k] = s.radius * s.radius;
            height[k] = s.offset;
        }
        ++count;
    }
};

/// An open cylinder from `base` along `axis`.
Shape open_cylinder(const Vec3& base, const Vec3& axis, float radius, float height) {
    ObjectDesc o = cylinder_desc(false);
    o.base = base;
    o.axis = axis;
    o.radius = radius;
    o.height = height;
    return make_shape(o, 0);
}

TEST(CylinderLanes, FourAtOnceEqualsOneByOneBitForBit) {
    Rng rng(23);
    int hits = 0, slow = 0, compared = 0, behind = 0, off_side = 0;
    for (int scene = 0; scene < 200; ++scene) {
        std::vector<Shape> cylinders(1 + scene % 4);
        CylinderGroup g;
        for (Shape& s : cylinders) {
            const float scale = scene % 3 == 0 ? 50.0f : 1.0f;
            s = open_cylinder(random_point(rng, -5, 5), random_direction(rng),
                              scale * uniform(rng, 0.02f, 1.0f), scale * uniform(rng, 0.1f, 4.0f));
            ASSERT_TRUE(s.world_form);
            g.add(s);
        }
        for (int k = 0; k < 400; ++k) {
            // origins far, near, and on a side (1e-4 off it, as spawned rays start), where the
            // float test hands over to double; rays along the axis; directions not unit
            Vec3 origin = random_point(rng, -20, 20);
            const Shape& on = cylinders[static_cast<size_t>(k) % cylinders.size()];
            Vec3 u, v;
            orthonormal_basis(on.normal, u, v);
            if (k % 3 == 0) {
                const float phi = uniform(rng, 0, 6.2831853f);
                const Vec3 across = u * std::cos(phi) + v * std::sin(phi);
                origin = on.centre + on.normal * (on.offset * uniform(rng, 0, 1)) +
                         across * (on.radius + ((k & 4) ? 1e-4f : -1e-4f));
            }
            Vec3 direction = random_direction(rng);
            if (k % 7 == 0) direction = on.normal;  // parallel to an axis: to double
            if (k % 5 == 0) direction = direction * 3.0f;
            const Ray r{origin, direction};
            const CylinderGroupRoots fast = cylinder_lanes_roots(g.lanes(), r, false);
            const CylinderGroupRoots ahead = cylinder_lanes_roots(g.lanes(), r, true);
            ASSERT_EQ(ahead.slow, fast.slow);
            ASSERT_EQ(ahead.hit & ~fast.hit, 0u);
            for (int lane = 0; lane < g.count; ++lane) {
                const unsigned bit = 1u << lane;
                const Shape& s = cylinders[static_cast<size_t>(lane)];
                float t0 = 0, t1 = 0;
                const CylinderRoots one =
                    world_cylinder_roots(s.centre, s.normal, g.rr[lane], s.offset, r, t0, t1);
                ++compared;
                ASSERT_EQ(one == CylinderRoots::slow, (fast.slow & bit) != 0)
                    << "scene " << scene << " ray " << k << " lane " << lane;
                if (one == CylinderRoots::slow) {
                    ++slow;
                    continue;
                }
                ASSERT_EQ(one == CylinderRoots::met, (fast.hit & bit) != 0);
                if (one != CylinderRoots::met) continue;
                ++hits;
                off_side += std::isnan(t0) + std::isnan(t1);
                ASSERT_TRUE(same_float_bits(t0, fast.t0[lane]) &&
                            same_float_bits(t1, fast.t1[lane]))
                    << "scene " << scene << " ray " << k << " lane " << lane;
                if (ahead.hit & bit) {
                    ASSERT_TRUE(same_float_bits(t0, ahead.t0[lane]) &&
                                same_float_bits(t1, ahead.t1[lane]));
                } else {  // left out ahead only: no root at t > 0
                    ++behind;
                    ASSERT_FALSE(t0 > 0) << "scene " << scene << " ray " << k;
                    ASSERT_FALSE(t1 > 0) << "scene " << scene << " ray " << k;
                }
            }
            EXPECT_EQ(fast.hit >> g.count, 0u);  // unused lanes are never reported
            EXPECT_EQ(fast.slow >> g.count, 0u);
        }
    }
    EXPECT_GT(hits, compared / 10);
    EXPECT_GT(slow, compared / 50);      // rays from on a side, rays along an axis
    EXPECT_GT(behind, compared / 50);    // rays leaving a side, cylinders behind an origin
    EXPECT_GT(off_side, compared / 50);  // roots beyond an end
}

TEST(CylinderWorldForm, AgreesWithTheObjectSpaceTestInDouble) {
    Rng rng(5);
    int agree = 0, hits = 0;
    for (int scene = 0; scene < 100; ++scene) {
        const Shape s = open_cylinder(random_point(rng, -3, 3), random_direction(rng),
                                      uniform(rng, 0.05f, 1.0f), uniform(rng, 0.2f, 3.0f));
        for (int k = 0; k < 200; ++k) {
            // aimed near the cylinder: from far, through a point near its middle
            const Vec3 target = s.centre + s.normal * (s.offset * uniform(rng, -0.2f, 1.2f)) +
                                random_direction(rng) * (s.radius * uniform(rng, 0, 1.5f));
            const Vec3 origin = target + random_direction(rng) * uniform(rng, 2, 20);
            const Ray r{origin, normalize(target - origin)};
            Hit world, object;
            const bool w = shapes::cylinder::intersect(s, r, 0, 1e30f, world);
            const bool o = shapes::cylinder::intersect_object(s, r, 0, 1e30f, object);
            if (w != o) continue;  // a graze of the rim or the side, within rounding
            ++agree;
            if (!w) continue;
            ++hits;
            // float against double: t to 1e-5 of itself, plus the rounding of the positions
            // (some ulp of coordinates up to ~25)
            ASSERT_NEAR(world.t, object.t, 1e-5f * object.t + 1e-5f)
                << "scene " << scene << " ray " << k;
            EXPECT_EQ(world.part, part_side);
        }
    }
    EXPECT_GT(agree, 100 * 200 * 99 / 100);  // all but grazes
    EXPECT_GT(hits, 100 * 200 / 4);
}

TEST(CylinderWorldForm, HitsWorkedByHand) {
    // radius 1 around the z axis, z ∈ [0, 2]
    const Shape s = open_cylinder({0, 0, 0}, {0, 0, 1}, 1.0f, 2.0f);
    ASSERT_TRUE(s.world_form);
    Hit hit;
    // from x = −5 at z = 1 along +x: in at t = 4 (x = −1), out at t = 6
    const Ray across{{-5, 0, 1}, {1, 0, 0}};
    ASSERT_TRUE(shapes::cylinder::intersect(s, across, 0, 100, hit));
    EXPECT_FLOAT_EQ(hit.t, 4.0f);
    SurfacePoint sp = shapes::cylinder::surface_at(s, across, hit);
    EXPECT_NEAR(sp.N.x, -1.0f, 1e-6f);
    EXPECT_NEAR(sp.N.y, 0.0f, 1e-6f);
    EXPECT_NEAR(sp.N.z, 0.0f, 1e-6f);
    ASSERT_TRUE(shapes::cylinder::intersect(s, across, 4.5f, 100, hit));  // the far wall
    EXPECT_FLOAT_EQ(hit.t, 6.0f);
    uint64_t tests = 0;
    EXPECT_EQ(shapes::cylinder::count_crossings(s, across, 0, 100, false, tests), 2u);
    EXPECT_EQ(shapes::cylinder::count_crossings(s, across, 0, 5, false, tests), 1u);
    // above the top (z = 3) it misses: the cylinder is open and ends at z = 2
    EXPECT_FALSE(shapes::cylinder::intersect(s, Ray{{-5, 0, 3}, {1, 0, 0}}, 0, 100, hit));
    // slanted through the open top: in at z = 2 nothing, the wall at x = 1, z = 1.5
    const Ray down{{-0.5f, 0, 2.25f}, {1.5f, 0, -0.75f}};  // reaches x = 1 at t = 1, z = 1.5
    ASSERT_TRUE(shapes::cylinder::intersect(s, down, 0, 100, hit));
    EXPECT_FLOAT_EQ(hit.t, 1.0f);
    sp = shapes::cylinder::surface_at(s, down, hit);
    EXPECT_NEAR(sp.N.x, 1.0f, 1e-6f);
    // the distance to a wall of radius 3 from its axis: t = 3 along any direction across it
    const Shape wide = open_cylinder({2, -1, 0.5f}, {1, 1, 0}, 3.0f, 10.0f);
    const Vec3 across_axis = normalize(Vec3{1, -1, 2});
    ASSERT_TRUE(shapes::cylinder::intersect(
        wide, Ray{Vec3{2, -1, 0.5f} + normalize(Vec3{1, 1, 0}) * 4.0f, across_axis}, 0, 100, hit));
    EXPECT_NEAR(hit.t, 3.0f, 3e-6f);
}

TEST(CylinderWorldForm, OnlyOpenCylindersThatStayRound) {
    EXPECT_TRUE(make_shape(cylinder_desc(false), 0).world_form);
    EXPECT_FALSE(make_shape(cylinder_desc(true), 0).world_form);  // caps: object space
    for (const auto& t : user_transforms()) {
        ObjectDesc o = cylinder_desc(false);
        o.transform = t.affine;
        EXPECT_EQ(make_shape(o, 0).world_form, t.similarity) << t.name;
    }
}

}  // namespace
}  // namespace luz
