// Tests of intersect() and surface_at(): known hits of every shape, rays from inside, misses,
// the (t_min, t_max) interval, transformed shapes, outward unit normals, open ends of cylinders
// and cones.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "geometry/shapes.h"
#include "intersect_fixtures.h"

namespace luz::test {
namespace {

// ---- known hits, identity placement -----------------------------------------------------------

ObjectDesc object(ShapeType type) {
    ObjectDesc o;
    o.type = type;
    return o;
}

TEST(Intersect, SphereKnownHits) {
    ObjectDesc o = sphere_desc();  // centre (1, 2, 3), radius 1.5
    const Shape s = make_shape(o, 0);
    Hit h;
    const Ray down{{1, 2, 8}, {0, 0, -1}};
    ASSERT_TRUE(intersect(s, down, 0, inf, h));
    EXPECT_NEAR(h.t, 3.5f, 1e-5f);
    const SurfacePoint sp = surface_at(s, down, h);
    expect_near(sp.P, {1, 2, 4.5f}, 1e-5f);
    expect_near(sp.N, {0, 0, 1}, 1e-6f);
    expect_near(sp.Ng, {0, 0, 1}, 1e-6f);
    // the far wall with t_min past the near one; nothing before t_max
    ASSERT_TRUE(intersect(s, down, 3.6f, inf, h));
    EXPECT_NEAR(h.t, 6.5f, 1e-5f);
    EXPECT_FALSE(intersect(s, down, 0, 3.4f, h));
    EXPECT_FALSE(intersect(s, down, 6.6f, inf, h));
    // from inside: the far wall, normal along the ray (leaving)
    const Ray out{{1, 2, 3}, {0, 2, 0}};  // not unit: t in units of the direction
    ASSERT_TRUE(intersect(s, out, 0, inf, h));
    EXPECT_NEAR(h.t, 0.75f, 1e-6f);
    expect_near(surface_at(s, out, h).Ng, {0, 1, 0}, 1e-6f);
    // misses: beside it and behind the origin
    EXPECT_FALSE(intersect(s, Ray{{1, 3.6f, 8}, {0, 0, -1}}, 0, inf, h));
    EXPECT_FALSE(intersect(s, Ray{{1, 2, 8}, {0, 0, 1}}, 0, inf, h));
}

TEST(Intersect, BoxKnownHitsAndFaces) {
    const Shape s = make_shape(box_desc(), 0);  // [-1, 0, -2] … [2, 1, 0.5]
    const Vec3 c = (s.lo + s.hi) * 0.5f;
    Hit h;
    for (int face = 0; face < 6; ++face) {
        const int k = face / 2;
        const float sign = (face & 1) ? 1.0f : -1.0f;
        Vec3 n{0.0f};
        n[k] = sign;
        // from outside along −n towards the face centre, 3 units away
        Vec3 target = c;
        target[k] = (face & 1) ? s.hi[k] : s.lo[k];
        const Ray r{target + n * 3.0f, -n};
        ASSERT_TRUE(intersect(s, r, 0, inf, h)) << face;
        EXPECT_NEAR(h.t, 3.0f, 1e-5f);
        EXPECT_EQ(h.part, face);
        expect_near(surface_at(s, r, h).Ng, n, 1e-6f);
        // from the centre: the same face from inside
        const Ray in{c, n};
        ASSERT_TRUE(intersect(s, in, 0, inf, h));
        EXPECT_NEAR(h.t, 0.5f * (s.hi[k] - s.lo[k]), 1e-5f);
        EXPECT_EQ(h.part, face);
    }
    EXPECT_FALSE(intersect(s, Ray{{3, 0.5f, 5}, {0, 0, -1}}, 0, inf, h));
    EXPECT_FALSE(intersect(s, Ray{{0, 0.5f, 5}, {0, 0, 1}}, 0, inf, h));
}

TEST(Intersect, CylinderKnownHits) {
    ObjectDesc o = object(ShapeType::cylinder);
    o.base = {0, 0, 0};
    o.axis = {0, 3, 0};
    o.radius = 0.5f;
    o.height = 2.0f;
    o.caps = true;
    const Shape s = make_shape(o, 0);
    Hit h;
    const Ray side{{5, 1, 0}, {-1, 0, 0}};
    ASSERT_TRUE(intersect(s, side, 0, inf, h));
    EXPECT_NEAR(h.t, 4.5f, 1e-5f);
    EXPECT_EQ(h.part, part_side);
    expect_near(surface_at(s, side, h).Ng, {1, 0, 0}, 1e-6f);
    const Ray top{{0.1f, 5, 0}, {0, -1, 0}};
    ASSERT_TRUE(intersect(s, top, 0, inf, h));
    EXPECT_NEAR(h.t, 3.0f, 1e-5f);
    EXPECT_EQ(h.part, part_cap1);
    expect_near(surface_at(s, top, h).Ng, {0, 1, 0}, 1e-6f);
    ASSERT_TRUE(intersect(s, top, 3.1f, inf, h));
    EXPECT_NEAR(h.t, 5.0f, 1e-5f);
    EXPECT_EQ(h.part, part_cap0);
    expect_near(surface_at(s, top, h).Ng, {0, -1, 0}, 1e-6f);
    const Ray in{{0, 1, 0}, {0, 0, 1}};
    ASSERT_TRUE(intersect(s, in, 0, inf, h));
    EXPECT_NEAR(h.t, 0.5f, 1e-6f);
    // open: the ray along the axis passes through
    o.caps = false;
    EXPECT_FALSE(intersect(make_shape(o, 0), top, 0, inf, h));
    EXPECT_FALSE(intersect(s, Ray{{0.6f, 5, 0}, {0, -1, 0}}, 0, inf, h));
}

TEST(Intersect, ConeKnownHitsAndApex) {
    ObjectDesc o = object(ShapeType::cone);
    o.base = {0, 0, 0};
    o.axis = {0, 1, 0};
    o.radius = 1.0f;
    o.height = 2.0f;
    o.caps = true;
    const Shape s = make_shape(o, 0);
    Hit h;
    const Ray side{{5, 1, 0}, {-1, 0, 0}};  // radius 0.5 at height 1
    ASSERT_TRUE(intersect(s, side, 0, inf, h));
    EXPECT_NEAR(h.t, 4.5f, 1e-5f);
    expect_near(surface_at(s, side, h).Ng, normalize(Vec3{2, 1, 0}), 1e-6f);
    // down the axis: the apex at t = 3, normal along the axis by convention
    const Ray down{{0, 5, 0}, {0, -1, 0}};
    ASSERT_TRUE(intersect(s, down, 0, inf, h));
    EXPECT_NEAR(h.t, 3.0f, 1e-5f);
    SurfacePoint sp = surface_at(s, down, h);
    EXPECT_TRUE(unit(sp.N));
    expect_near(sp.Ng, {0, 1, 0}, 1e-6f);
    // from below: the base cap, or with no cap the apex from inside
    const Ray up{{0, -5, 0}, {0, 1, 0}};
    ASSERT_TRUE(intersect(s, up, 0, inf, h));
    EXPECT_NEAR(h.t, 5.0f, 1e-5f);
    EXPECT_EQ(h.part, part_cap0);
    expect_near(surface_at(s, up, h).Ng, {0, -1, 0}, 1e-6f);
    o.caps = false;
    const Shape open = make_shape(o, 0);
    ASSERT_TRUE(intersect(open, up, 0, inf, h));
    EXPECT_NEAR(h.t, 7.0f, 1e-5f);
    EXPECT_TRUE(unit(surface_at(open, up, h).Ng));
    // the mirrored nappe above the apex is not part of the cone
    EXPECT_FALSE(intersect(s, Ray{{5, 3, 0}, {-1, 0, 0}}, 0, inf, h));
}

TEST(Intersect, TorusKnownHits) {
    ObjectDesc o = object(ShapeType::torus);
    o.center = {0, 0, 0};
    o.axis = {0, 1, 0};
    o.major_radius = 2.0f;
    o.minor_radius = 0.5f;
    const Shape s = make_shape(o, 0);
    Hit h;
    const Ray r{{5, 0, 0}, {-1, 0, 0}};
    const float expected[] = {2.5f, 3.5f, 6.5f, 7.5f};
    float t_min = 0;
    for (int i = 0; i < 4; ++i) {
        ASSERT_TRUE(intersect(s, r, t_min, inf, h)) << i;
        EXPECT_NEAR(h.t, expected[i], 1e-5f);
        const SurfacePoint sp = surface_at(s, r, h);
        expect_near(sp.Ng, {i % 2 == 0 ? 1.0f : -1.0f, 0, 0}, 1e-5f);  // outward
        t_min = h.t + 0.01f;
    }
    EXPECT_FALSE(intersect(s, r, t_min, inf, h));
    // from the tube centre, through the hole, onto the top
    ASSERT_TRUE(intersect(s, Ray{{2, 0, 0}, {1, 0, 0}}, 0, inf, h));
    EXPECT_NEAR(h.t, 0.5f, 1e-6f);
    EXPECT_FALSE(intersect(s, Ray{{0, 5, 0}, {0, -1, 0}}, 0, inf, h));
    const Ray top{{0, 5, 2}, {0, -1, 0}};
    ASSERT_TRUE(intersect(s, top, 0, inf, h));
    EXPECT_NEAR(h.t, 4.5f, 1e-5f);
    expect_near(surface_at(s, top, h).Ng, {0, 1, 0}, 1e-5f);
    // far away: still accurate (the origin is moved to the bounding sphere first)
    const Ray far{{2, 0, 1e4f}, {0, 0, -1}};  // onto the tube around (0, 0, 2) at z = 1.5
    ASSERT_TRUE(intersect(s, far, 0, inf, h));
    EXPECT_NEAR(h.t, 1e4f - 1.5f, 2e-3f);
}

TEST(Intersect, PlaneFromBothSides) {
    const Shape s = make_shape(plane_desc(), 0);  // through (0, −1, 0), normal ∝ (0, 2, 0.5)
    const Vec3 n = normalize(plane_desc().normal);
    Hit h;
    for (const float side : {1.0f, -1.0f}) {
        const Ray r{Vec3{0.3f, -1.1f, 0.4f} + n * (2 * side), -n * side};
        ASSERT_TRUE(intersect(s, r, 0, inf, h));
        EXPECT_NEAR(h.t, 2.0f, 1e-5f);
        expect_near(surface_at(s, r, h).Ng, n, 1e-6f);  // +normal from either side
    }
    EXPECT_FALSE(intersect(s, Ray{{0, 0, 0}, {1, -0.25f, 1}}, 0, 1e4f, h));  // parallel
    EXPECT_FALSE(intersect(s, Ray{{0, 0, 0}, n}, 0, inf, h));                // away
    EXPECT_FALSE(intersect(s, Ray{{0, 0, 0}, -n}, 0, 0.5f, h));              // beyond t_max
}

TEST(Intersect, TriangleBarycentricsAndWindingNormal) {
    const ObjectDesc o = with_transform(triangle_desc(), user_transforms()[2].affine);
    const Shape s = make_shape(o, 0);
    Vec3 v[3];
    for (int k = 0; k < 3; ++k) v[k] = s.transform.point(s.vertices[k]);
    const Vec3 n = normalize(cross(v[1] - v[0], v[2] - v[0]));
    Hit h;
    for (const float side : {1.0f, -1.0f}) {
        const Vec3 target = v[0] * 0.5f + v[1] * 0.2f + v[2] * 0.3f;
        const Ray r{target + n * (3 * side), -n * side};
        ASSERT_TRUE(intersect(s, r, 0, inf, h));
        EXPECT_NEAR(h.t, 3.0f, 1e-4f);
        EXPECT_NEAR(h.u, 0.2f, 1e-5f);
        EXPECT_NEAR(h.v, 0.3f, 1e-5f);
        const SurfacePoint sp = surface_at(s, r, h);
        expect_near(sp.Ng, n, 1e-5f);  // the winding normal from both sides
        expect_near(sp.N, n, 1e-5f);
    }
    const Vec3 outside = v[0] * -0.1f + v[1] * 0.6f + v[2] * 0.5f;
    EXPECT_FALSE(intersect(s, Ray{outside + n, -n}, 0, inf, h));
    EXPECT_FALSE(intersect(s, Ray{v[0] + n, cross(n, v[1] - v[0])}, 0, inf, h));  // parallel
}

// ---- every shape, every transform -----------------------------------------------------------

TEST(Intersect, SurfacePointsFromBothSidesUnderEveryTransform) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> U(0, 1);
    for (const NamedObject& obj : shapes_under_test()) {
        for (const NamedTransform& tr : user_transforms()) {
            SCOPED_TRACE(obj.name + " / " + tr.name);
            const Shape s = make_shape(with_transform(obj.desc, tr.affine), 0);
            int failures = 0;
            for (int i = 0; i < 200 && failures < 5; ++i) {
                const SurfaceSample smp = sample_surface(s, rng);
                const Vec3 X = s.transform.point(smp.p);
                const Vec3 n = world_normal(s, smp.n);
                for (const float side : {1.0f, -1.0f}) {
                    // side +1: from outside along the normal; −1: from just inside (or behind)
                    const float dist = side > 0 ? 0.01f + 0.3f * U(rng) : 0.01f;
                    const float speed = 0.5f + 1.5f * U(rng);  // non-unit directions
                    const Vec3 O = X + n * (side * dist);
                    const Ray r{O, normalize(X - O) * speed};
                    const float t_expected = length(X - O) / speed;
                    Hit h;
                    if (!intersect(s, r, 0, inf, h)) {
                        ADD_FAILURE() << "no hit, side " << side;
                        ++failures;
                        continue;
                    }
                    EXPECT_NEAR(h.t, t_expected, 2e-5f + 1e-4f * t_expected) << side;
                    const SurfacePoint sp = surface_at(s, r, h);
                    EXPECT_NEAR(world_sdf(s, sp.P), 0.0, 1e-4);
                    expect_near(sp.P, r.at(h.t), 1e-6f);
                    EXPECT_TRUE(unit(sp.N));
                    EXPECT_TRUE(unit(sp.Ng));
                    EXPECT_GT(dot(sp.Ng, n), 0.9999f);  // outward, the analytic normal
                    EXPECT_GT(dot(sp.N, sp.Ng), 0.9999f);
                    // outside → the ray meets the outward normal head-on; inside → along it
                    EXPECT_LT(side * dot(sp.Ng, r.direction), 0.0f);
                    if (::testing::Test::HasFailure()) ++failures;
                }
            }
        }
    }
}

/// A point strictly inside a closed shape (object space).
Vec3 interior_point(const Shape& s, std::mt19937& rng) {
    std::uniform_real_distribution<float> U(-1, 1);
    switch (s.type) {
        case ShapeType::sphere:
            return Vec3{U(rng), U(rng), U(rng)} * 0.5f;
        case ShapeType::box:
            return (s.lo + s.hi) * 0.5f + (s.hi - s.lo) * (0.4f * U(rng));
        case ShapeType::cylinder:
            return {0.5f * U(rng), 0.5f * U(rng), 0.5f + 0.4f * U(rng)};
        case ShapeType::cone:
            return {0.3f * U(rng), 0.3f * U(rng), 0.3f + 0.2f * U(rng)};
        case ShapeType::torus: {
            const float phi = float(pi) * U(rng);
            return Vec3{std::cos(phi), std::sin(phi), 0} +
                   Vec3{U(rng), U(rng), U(rng)} * (0.5f * s.minor);
        }
        default:
            return {};
    }
}

TEST(Intersect, RaysFromInsideClosedShapesLeaveThroughTheWall) {
    std::mt19937 rng(11);
    std::normal_distribution<float> N01;
    for (const NamedObject& obj : shapes_under_test()) {
        if (!obj.closed) continue;
        for (const NamedTransform& tr : user_transforms()) {
            SCOPED_TRACE(obj.name + " / " + tr.name);
            const Shape s = make_shape(with_transform(obj.desc, tr.affine), 0);
            int misses = 0, bad = 0;
            for (int i = 0; i < 300; ++i) {
                const Vec3 p = interior_point(s, rng);
                ASSERT_LT(object_sdf(s, p), 0.0);
                const Ray r{s.transform.point(p), Vec3{N01(rng), N01(rng), N01(rng)}};
                Hit h;
                if (!intersect(s, r, 0, inf, h)) {
                    ++misses;
                    continue;
                }
                const SurfacePoint sp = surface_at(s, r, h);
                if (!(h.t > 0) || std::fabs(world_sdf(s, sp.P)) > 1e-4 ||
                    !(dot(sp.Ng, r.direction) > 0) || !unit(sp.N))
                    ++bad;
                // nothing of the shape between the origin and the hit
                for (int k = 1; k < 20; ++k)
                    if (world_sdf(s, r.at(h.t * k / 20.0f)) > 1e-5) ++bad;
            }
            EXPECT_EQ(misses, 0);
            EXPECT_EQ(bad, 0);
        }
    }
}

TEST(Intersect, MissesAndTheInterval) {
    std::mt19937 rng(5);
    std::normal_distribution<float> N01;
    for (const NamedObject& obj : shapes_under_test()) {
        if (obj.desc.type == ShapeType::plane) continue;
        for (const NamedTransform& tr : user_transforms()) {
            SCOPED_TRACE(obj.name + " / " + tr.name);
            const Shape s = make_shape(with_transform(obj.desc, tr.affine), 0);
            const Bounds3 b = bounds(s);
            const Vec3 c = b.centre();
            const float radius = 0.5f * length(b.extent());
            Hit h;
            for (int i = 0; i < 100; ++i) {
                const Vec3 u = normalize(Vec3{N01(rng), N01(rng), N01(rng)});
                // pointing away from the shape, or passing beside its bounding sphere
                EXPECT_FALSE(intersect(s, Ray{c + u * (1.5f * radius), u}, 0, inf, h));
                const Vec3 side = normalize(cross(u, Vec3{N01(rng), N01(rng), N01(rng)}));
                EXPECT_FALSE(intersect(s, Ray{c + u * (3 * radius) + side * (1.01f * radius), -u},
                                       0, inf, h));
            }
            // (t_min, t_max) around the first hit of a ray through the middle
            for (int i = 0; i < 50; ++i) {
                const SurfaceSample smp = sample_surface(s, rng);
                const Vec3 X = s.transform.point(smp.p);
                const Vec3 n = world_normal(s, smp.n);
                const Ray r{X + n * 0.5f, -n};
                ASSERT_TRUE(intersect(s, r, 0, inf, h));
                const float t0 = h.t;
                EXPECT_FALSE(intersect(s, r, 0, t0 * 0.999f, h));
                ASSERT_TRUE(intersect(s, r, t0 * 0.999f, t0 * 1.001f, h));
                EXPECT_NEAR(h.t, t0, 1e-6f * t0);
                if (intersect(s, r, t0 * 1.001f, inf, h)) {
                    EXPECT_GT(h.t, t0 * 1.001f);  // a farther wall
                } else {
                    EXPECT_FALSE(obj.closed);  // closed shapes are left again
                }
            }
        }
    }
}

// ---- open ends -------------------------------------------------------------------------------

TEST(Intersect, OpenEndsShowTheInsideWall) {
    for (const NamedTransform& tr : user_transforms()) {
        SCOPED_TRACE(tr.name);
        for (const bool caps : {false, true}) {
            // cylinder: in through the top (z = 1), onto the wall at x = 1, z = 0.75
            const Shape cyl = make_shape(with_transform(cylinder_desc(caps), tr.affine), 0);
            const Ray rc = world_ray(cyl, {0, 0, 2}, {0.8f, 0, -1});
            Hit h;
            ASSERT_TRUE(intersect(cyl, rc, 0, inf, h));
            if (caps) {
                EXPECT_NEAR(h.t, 1.0f, 1e-5f);
                EXPECT_EQ(h.part, part_cap1);
            } else {
                EXPECT_NEAR(h.t, 1.25f, 1e-5f);
                EXPECT_EQ(h.part, part_side);
                const SurfacePoint sp = surface_at(cyl, rc, h);
                EXPECT_GT(dot(sp.Ng, rc.direction), 0);  // seen from inside
                expect_near(sp.Ng, world_normal(cyl, {1, 0, 0}), 1e-5f);
            }
            // cone: in through the base (z = 0), onto the wall at z = 2/3
            const Shape cone = make_shape(with_transform(cone_desc(caps), tr.affine), 0);
            const Ray rk = world_ray(cone, {0, 0, -1}, {0.2f, 0, 1});
            ASSERT_TRUE(intersect(cone, rk, 0, inf, h));
            if (caps) {
                EXPECT_NEAR(h.t, 1.0f, 1e-5f);
                EXPECT_EQ(h.part, part_cap0);
            } else {
                EXPECT_NEAR(h.t, 5.0f / 3.0f, 1e-5f);
                const SurfacePoint sp = surface_at(cone, rk, h);
                EXPECT_GT(dot(sp.Ng, rk.direction), 0);
                expect_near(sp.Ng, world_normal(cone, {1, 0, 1}), 1e-5f);
            }
        }
    }
}

}  // namespace
}  // namespace luz::test
