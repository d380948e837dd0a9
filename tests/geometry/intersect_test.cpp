// Tests of intersect() and surface_at(): known hits of every shape, rays from inside, misses,
// grazing rays, the (t_min, t_max) interval, transformed shapes, outward unit normals, the torus
// against a brute-force march, open ends of cylinders and cones, watertight shared edges.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "geometry/shapes.h"
#include "geometry_fixtures.h"

namespace luz::test {
namespace {

constexpr float inf = std::numeric_limits<float>::infinity();
constexpr double pi = std::numbers::pi;

// ---- helpers --------------------------------------------------------------------------------

/// The world ray whose object-space image is (o, d): t is the same along both.
Ray world_ray(const Shape& s, const Vec3& o, const Vec3& d) {
    return {s.transform.point(o), s.transform.vector(d)};
}

/// Signed distance-like function of the shape in object space (double): > 0 outside, < 0
/// inside, 0 on the surface, |value| ≈ the distance near the surface (exact for most shapes).
double object_sdf(const Shape& s, const Vec3& pf) {
    const double x = pf.x, y = pf.y, z = pf.z;
    const double r = std::sqrt(x * x + y * y);
    switch (s.type) {
        case ShapeType::sphere:
            return std::sqrt(x * x + y * y + z * z) - 1.0;
        case ShapeType::box: {
            double q[3], out = 0, in = -1e30;
            for (int k = 0; k < 3; ++k) {
                const double c = 0.5 * (double(s.lo[k]) + s.hi[k]);
                const double h = 0.5 * (double(s.hi[k]) - s.lo[k]);
                q[k] = std::fabs(pf[k] - c) - h;
                out += std::max(q[k], 0.0) * std::max(q[k], 0.0);
                in = std::max(in, q[k]);
            }
            return std::sqrt(out) + std::min(in, 0.0);
        }
        case ShapeType::cylinder: {
            const double dr = r - 1.0;
            if (!s.caps) return dr;
            const double dz = std::max(-z, z - 1.0);
            return std::hypot(std::max(dr, 0.0), std::max(dz, 0.0)) +
                   std::min(std::max(dr, dz), 0.0);
        }
        case ShapeType::cone: {
            const double m = 1.0 - s.apex;  // the slope: radius 1 − m·z
            const double side = (r - (1.0 - m * z)) / std::sqrt(1.0 + m * m);
            if (!s.caps) return side;
            return s.apex > 0 ? std::max({side, -z, z - 1.0}) : std::max(side, -z);
        }
        case ShapeType::torus:
            return std::hypot(r - 1.0, z) - s.minor;
        case ShapeType::plane:
            return z;
        case ShapeType::triangle: {
            const Vec3 n =
                normalize(cross(s.vertices[1] - s.vertices[0], s.vertices[2] - s.vertices[0]));
            return dot(pf - s.vertices[0], n);
        }
        case ShapeType::mesh:
            break;
    }
    return 0;
}

double world_sdf(const Shape& s, const Vec3& P) {
    return object_sdf(s, s.transform.object_from_world.point(P));
}

/// A point of the surface (object space) away from edges, with its outward object normal.
struct SurfaceSample {
    Vec3 p, n;
};

SurfaceSample sample_surface(const Shape& s, std::mt19937& rng) {
    std::uniform_real_distribution<float> U(0, 1);
    const float phi = 2 * float(pi) * U(rng);
    const float c = std::cos(phi), sn = std::sin(phi);
    switch (s.type) {
        case ShapeType::sphere: {
            const float z = 2 * U(rng) - 1, rr = std::sqrt(1 - z * z);
            const Vec3 p{rr * c, rr * sn, z};
            return {p, p};
        }
        case ShapeType::box: {
            const int face = int(U(rng) * 6) % 6, k = face / 2;
            Vec3 p, n{0.0f};
            for (int i = 0; i < 3; ++i)
                p[i] = s.lo[i] + (0.1f + 0.8f * U(rng)) * (s.hi[i] - s.lo[i]);
            p[k] = (face & 1) ? s.hi[k] : s.lo[k];
            n[k] = (face & 1) ? 1.0f : -1.0f;
            return {p, n};
        }
        case ShapeType::cylinder:
        case ShapeType::cone: {
            const bool cone = s.type == ShapeType::cone;
            const int caps = s.caps ? (cone && s.apex == 0 ? 1 : 2) : 0;
            const int pick = int(U(rng) * (2 + caps));  // the side twice as often
            if (pick >= 2) {
                const float z = (pick == 2) ? 0.0f : 1.0f;
                const float rr = 0.9f * std::sqrt(U(rng)) * (cone && z == 1 ? s.apex : 1.0f);
                return {{rr * c, rr * sn, z}, {0, 0, z == 0 ? -1.0f : 1.0f}};
            }
            const float z = 0.1f + 0.8f * U(rng);
            if (!cone) return {{c, sn, z}, {c, sn, 0}};
            const float m = 1 - s.apex, rr = 1 - m * z;
            return {{rr * c, rr * sn, z}, {c, sn, m}};
        }
        case ShapeType::torus: {
            const float psi = 2 * float(pi) * U(rng);
            const Vec3 n{std::cos(psi) * c, std::cos(psi) * sn, std::sin(psi)};
            return {Vec3{c, sn, 0} + n * s.minor, n};
        }
        case ShapeType::plane:
            return {{10 * U(rng) - 5, 10 * U(rng) - 5, 0}, {0, 0, 1}};
        case ShapeType::triangle: {
            float b1 = 0.05f + 0.9f * U(rng), b2 = 0.05f + 0.9f * U(rng);
            if (b1 + b2 > 0.95f) b1 = 0.95f - b1, b2 = 0.95f - b2;
            b1 = std::max(b1, 0.02f), b2 = std::max(b2, 0.02f);
            const Vec3* v = s.vertices;
            return {v[0] * (1 - b1 - b2) + v[1] * b1 + v[2] * b2, cross(v[1] - v[0], v[2] - v[0])};
        }
        case ShapeType::mesh:
            break;
    }
    return {};
}

/// Every shape: the fixtures' objects and a plane.
std::vector<NamedObject> shapes_under_test() {
    std::vector<NamedObject> all = all_objects();
    all.push_back({"plane", plane_desc(), false});
    return all;
}

bool unit(const Vec3& v) { return is_finite(v) && std::fabs(length(v) - 1.0f) < 1e-5f; }

void expect_near(const Vec3& a, const Vec3& b, float tol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

/// The world normal of an object-space normal.
Vec3 world_normal(const Shape& s, const Vec3& n) { return normalize(s.transform.normal(n)); }

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

// ---- grazing rays ---------------------------------------------------------------------------

struct Tangent {
    std::string name;
    Vec3 o, d;    ///< object space, touching the surface at o + t_touch·d
    Vec3 offset;  ///< unit direction in which the ray is moved away from the surface
    float t_touch;
};

std::vector<Tangent> tangent_rays(const Shape& s) {
    const float m = s.minor;
    switch (s.type) {
        case ShapeType::sphere:
            return {{"sphere", {1, 0, -3}, {0, 0, 1}, {1, 0, 0}, 3},
                    {"sphere_oblique", Vec3{0.6f, 0.8f, 0} - normalize(Vec3{-0.8f, 0.6f, 0.5f}) * 2,
                     normalize(Vec3{-0.8f, 0.6f, 0.5f}), Vec3{0.6f, 0.8f, 0}, 2}};
        case ShapeType::box: {
            const Vec3 mid = (s.lo + s.hi) * 0.5f;
            return {
                {"box_face", {s.hi.x, mid.y, s.lo.z - 2}, {0, 0, 1}, {1, 0, 0}, 2},
                {"box_edge", {s.hi.x, s.hi.y, s.lo.z - 2}, {0, 0, 1}, normalize(Vec3{1, 1, 0}), 2}};
        }
        case ShapeType::cylinder:
            return {{"cyl_side", {1, -3, 0.5f}, {0, 1, 0}, {1, 0, 0}, 3},
                    {"cyl_along_side", {1, 0, -2}, {0, 0, 1}, {1, 0, 0}, 2},
                    {"cyl_rim", {-3, 0, 1}, {1, 0, 0}, {0, 0, 1}, 2}};
        case ShapeType::cone: {
            // along a generator x = 1 − k·z (the quadratic's a = 0) and across the side;
            // k = 1 − apex is the slope
            const float k = 1 - s.apex;
            return {{"cone_generator", {1 + 2 * k, 0, -2}, {-k, 0, 1}, normalize(Vec3{1, 0, k}), 2},
                    {"cone_side", {-3, 1 - 0.5f * k, 0.5f}, {1, 0, 0}, {0, 1, 0}, 3}};
        }
        case ShapeType::torus:
            return {{"torus_top", {-3, 0, m}, {1, 0, 0}, {0, 0, 1}, 2},
                    {"torus_outer", {1 + m, -3, 0}, {0, 1, 0}, {1, 0, 0}, 3},
                    {"torus_inner", {1 - m, 0, -3}, {0, 0, 1}, {-1, 0, 0}, 3},
                    {"torus_oblique",
                     Vec3{0, -1 - m, 0} - Vec3{1, 0, 1} * 3,
                     normalize(Vec3{1, 0, 1}),
                     {0, -1, 0},
                     3 * std::sqrt(2.0f)}};
        case ShapeType::plane:
            return {{"plane", {-3, 0, 0}, {1, 0, 0}, {0, 0, 1}, 3}};
        case ShapeType::triangle: {
            const Vec3* v = s.vertices;
            const Vec3 n = normalize(cross(v[1] - v[0], v[2] - v[0]));
            const Vec3 c = (v[0] + v[1] + v[2]) / 3.0f, e = v[1] - v[0];
            return {{"triangle_edge_on", c - e, e, n, 1}};
        }
        case ShapeType::mesh:
            break;
    }
    return {};
}

TEST(Intersect, GrazingRaysNeverGiveNaN) {
    for (const NamedObject& obj : shapes_under_test()) {
        for (const NamedTransform& tr : user_transforms()) {
            const Shape s = make_shape(with_transform(obj.desc, tr.affine), 0);
            for (const Tangent& tg : tangent_rays(s)) {
                SCOPED_TRACE(obj.name + " / " + tr.name + " / " + tg.name);
                for (const float delta :
                     {-1e-3f, -1e-4f, -1e-6f, -1e-7f, 0.0f, 1e-7f, 1e-6f, 1e-4f, 1e-3f}) {
                    const Ray r = world_ray(s, tg.o + tg.offset * delta, tg.d);
                    Hit h;
                    const bool hit = intersect(s, r, 0, inf, h);
                    const bool near_touch = hit && std::fabs(h.t - tg.t_touch) < 0.1f;
                    if (hit) {
                        EXPECT_TRUE(std::isfinite(h.t) && h.t > 0) << delta;
                        EXPECT_TRUE(std::isfinite(h.u) && std::isfinite(h.v)) << delta;
                        const SurfacePoint sp = surface_at(s, r, h);
                        EXPECT_TRUE(is_finite(sp.P)) << delta;
                        EXPECT_TRUE(unit(sp.N) && unit(sp.Ng)) << delta;
                        // (a nearly parallel ray may meet the plane far away: float tolerance)
                        EXPECT_NEAR(world_sdf(s, sp.P), 0.0, 1e-4 + 1e-6 * length(sp.P))
                            << delta << " t " << h.t;
                    }
                    // clearly off the surface: no hit there; clearly into it: a hit there
                    // (open shapes and the plane can only be missed or hit elsewhere)
                    if (delta >= 1e-4f) {
                        EXPECT_FALSE(near_touch) << delta;
                    }
                    if (delta <= -1e-4f && obj.closed) {
                        EXPECT_TRUE(near_touch) << delta;
                    }
                }
            }
        }
    }
}

// ---- torus against a brute-force march --------------------------------------------------------

/// Brute force on the object-space ray in double: sample the torus's signed distance along
/// the ray with steps no longer than its value (a 1-Lipschitz function cannot change sign
/// within that step, so no crossing is skipped), down to 1e-7, and bisect the first sign
/// change. min_abs is the closest the samples came to the surface.
bool march_torus(const Ray& ro, double m, double t_min, double t_max, double& t_hit,
                 double& min_abs) {
    const double o[3] = {ro.origin.x, ro.origin.y, ro.origin.z};
    const double d[3] = {ro.direction.x, ro.direction.y, ro.direction.z};
    const double dl = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const auto sd = [&](double s) {  // s: distance along the unit direction
        const double x = o[0] + s * d[0] / dl, y = o[1] + s * d[1] / dl, z = o[2] + s * d[2] / dl;
        return std::hypot(std::hypot(x, y) - 1.0, z) - m;
    };
    const auto radius2 = [&](double s) {
        double r2 = 0;
        for (int k = 0; k < 3; ++k) r2 += (o[k] + s * d[k] / dl) * (o[k] + s * d[k] / dl);
        return r2;
    };
    const double s_end = std::min(t_max * dl, 1e9);
    double s = t_min * dl, f = sd(s);
    min_abs = std::fabs(f);
    for (long i = 0; i < 50'000'000; ++i) {
        double s1 = std::min(s + std::max(std::fabs(f), 1e-7), s_end);
        const double f1 = sd(s1);
        min_abs = std::min(min_abs, std::fabs(f1));
        if ((f > 0) != (f1 > 0)) {
            double lo = s, hi = s1;
            for (int k = 0; k < 80; ++k) {
                const double mid = 0.5 * (lo + hi);
                ((sd(mid) > 0) == (f > 0) ? lo : hi) = mid;
            }
            t_hit = 0.5 * (lo + hi) / dl;
            return true;
        }
        // past the torus and moving away from it: nothing more
        if (s1 >= s_end || (radius2(s1) > (2 + m) * (2 + m) && radius2(s1) > radius2(s)))
            return false;
        s = s1;
        f = f1;
    }
    return false;
}

TEST(Intersect, TorusMatchesBruteForceMarch) {
    std::mt19937 rng(2024);
    std::uniform_real_distribution<float> U(0, 1);
    std::normal_distribution<float> N01;
    const auto unit_vector = [&] { return normalize(Vec3{N01(rng), N01(rng), N01(rng)}); };
    std::vector<Shape> tori;
    for (const float minor : {0.35f, 0.1f, 1.0f, 0.9f * 1.2f}) {
        ObjectDesc o = torus_desc();  // major radius 1.2
        o.minor_radius = minor;
        for (const NamedTransform& tr : user_transforms())
            tori.push_back(make_shape(with_transform(o, tr.affine), 0));
    }
    int hits = 0, compared = 0, ambiguous = 0, mismatched = 0;
    double worst = 0;
    for (int i = 0; i < 20000; ++i) {
        const Shape& s = tori[i % tori.size()];
        const float m = s.minor;
        Vec3 o, d = unit_vector() * (0.3f + 2 * U(rng));
        switch (i / 5000) {
            case 0:  // anywhere around it, inside the hole and the tube included
                o = Vec3{4 * U(rng) - 2, 4 * U(rng) - 2, 2 * U(rng) - 1};
                break;
            case 1: {  // from inside the tube
                const float phi = 2 * float(pi) * U(rng);
                o = Vec3{std::cos(phi), std::sin(phi), 0} + unit_vector() * (0.95f * m * U(rng));
                break;
            }
            case 2: {  // grazing: tangent to the surface, moved off it by ±[1e-6, 1e-2]·m
                const SurfaceSample smp = sample_surface(s, rng);
                const Vec3 tangent = normalize(cross(smp.n, unit_vector()));
                const float delta = m * std::pow(10.0f, -6 + 4 * U(rng)) * (U(rng) < 0.5f ? -1 : 1);
                d = tangent * length(d);
                o = smp.p + smp.n * delta - d * (3 * U(rng));
                break;
            }
            default:  // from far away, aimed at the torus
                o = unit_vector() * (20 + 500 * U(rng));
                d = normalize(Vec3{2 * U(rng) - 1, 2 * U(rng) - 1, m * (2 * U(rng) - 1)} - o) *
                    length(d);
                break;
        }
        const Ray r = world_ray(s, o, d);
        const float t_min = (i % 7 == 0) ? 0.5f * U(rng) : 0.0f;
        const float t_max = (i % 11 == 0) ? 1 + 3 * U(rng) : inf;
        Hit h;
        const bool hit = intersect(s, r, t_min, t_max, h);
        double t_ref = 0, min_abs = 0;
        // the same object-space ray the intersector sees
        const bool ref = march_torus(s.transform.to_object(r), m, t_min, t_max, t_ref, min_abs);
        if (hit != ref) {
            // only acceptable where the ray touches the surface to within double rounding
            if (min_abs < 1e-9) {
                ++ambiguous;
            } else {
                ++mismatched;
                if (mismatched < 10)
                    ADD_FAILURE() << "ray " << i << ": intersect " << hit << ", march " << ref
                                  << " (t " << (hit ? h.t : t_ref) << ", closest " << min_abs
                                  << ")";
            }
            continue;
        }
        if (!hit) continue;
        ++hits;
        ++compared;
        const double err = std::fabs(h.t - t_ref) / std::max(t_ref, 1e-3);
        worst = std::max(worst, err);
        EXPECT_LT(err, 1e-3) << "ray " << i << ": t " << h.t << " vs " << t_ref;
        EXPECT_TRUE(h.t > t_min && h.t < t_max);
        const SurfacePoint sp = surface_at(s, r, h);
        EXPECT_TRUE(unit(sp.N) && unit(sp.Ng));
    }
    EXPECT_EQ(mismatched, 0);
    EXPECT_LE(ambiguous, 5);
    EXPECT_GT(hits, 8000);  // the sample exercises hits as well as misses
    EXPECT_LT(worst, 1e-5);
    std::printf("torus: %d hits of 20000, %d ambiguous, worst relative t error %g\n", hits,
                ambiguous, worst);
    (void)compared;
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

// ---- watertight triangles --------------------------------------------------------------------

Shape triangle_shape(const Vec3& a, const Vec3& b, const Vec3& c, const Affine& transform) {
    ObjectDesc o;
    o.type = ShapeType::triangle;
    o.vertices = {a, b, c};
    o.transform = transform;
    return make_shape(o, 0);
}

TEST(Intersect, RaysThroughASharedEdgeOrVertexNeverSlipThrough) {
    std::mt19937 rng(99);
    std::uniform_real_distribution<float> U(0, 1);
    const auto sign = [&] { return U(rng) < 0.5f ? -1.0f : 1.0f; };
    // Two triangles on edge a–b, consistently wound, bent 3° along it; the rays cross their
    // plane at 10° or more, so in projection they lie on both sides of the edge (no fold).
    const Vec3 a{0.1f, 0.2f, 0.3f}, b{1.7f, -0.3f, 0.9f}, c{0.4f, 1.9f, -0.2f};
    const Vec3 n = normalize(cross(b - a, c - a)), mid = (a + b) * 0.5f;
    const Vec3 d = mid - (c - mid) + n * 0.1f;
    const Vec3 u = normalize(b - a), w = cross(n, u);
    for (const NamedTransform& tr : user_transforms()) {
        SCOPED_TRACE(tr.name);
        const Shape t1 = triangle_shape(a, b, c, tr.affine),
                    t2 = triangle_shape(b, a, d, tr.affine);
        int neither = 0;
        for (int i = 0; i < 20000; ++i) {
            const Vec3 e = a + (b - a) * U(rng);  // on the edge up to rounding
            const Vec3 o =
                e + n * (sign() * (2 + 8 * U(rng))) + u * (10 * U(rng) - 5) + w * (10 * U(rng) - 5);
            const Ray r = world_ray(t1, o, (e - o) * (0.1f + U(rng)));  // the same transform
            Hit h1, h2;
            neither += !intersect(t1, r, 0, inf, h1) && !intersect(t2, r, 0, inf, h2);
        }
        EXPECT_EQ(neither, 0);
        // a closed fan of six triangles around a shared vertex, slopes ≤ 0.2
        const Vec3 centre{0.3f, -0.7f, 0.2f};
        const auto rim = [&](int j) {
            const float phi = 2 * float(pi) / 6 * (j % 6) + 0.2f * std::sin(float(j % 6));
            return centre + Vec3{std::cos(phi), std::sin(phi), 0.1f * std::sin(3 * phi)};
        };
        std::vector<Shape> fan;
        for (int k = 0; k < 6; ++k)
            fan.push_back(triangle_shape(centre, rim(k), rim(k + 1), tr.affine));
        int missed = 0;
        for (int i = 0; i < 5000; ++i) {
            const Vec3 o =
                centre + Vec3{10 * U(rng) - 5, 10 * U(rng) - 5, sign() * (3 + 7 * U(rng))};
            const Ray r = world_ray(fan[0], o, centre - o);
            bool any = false;
            Hit h;
            for (const Shape& f : fan) any = any || intersect(f, r, 0, inf, h);
            missed += !any;
        }
        EXPECT_EQ(missed, 0);
    }
}

}  // namespace
}  // namespace luz::test

namespace luz::test {
namespace {

/// The roots in (0, inf) of r with the world form of s, solved in double from the same float
/// parameters (centre, radius; normal, offset), nearest first.
std::vector<double> world_form_reference(const Shape& s, const Ray& r) {
    const double ox = r.origin.x, oy = r.origin.y, oz = r.origin.z;
    const double dx = r.direction.x, dy = r.direction.y, dz = r.direction.z;
    std::vector<double> roots;
    if (s.type == ShapeType::plane) {
        const double nd = s.normal.x * dx + s.normal.y * dy + s.normal.z * dz;
        roots = {(s.offset - (s.normal.x * ox + s.normal.y * oy + s.normal.z * oz)) / nd};
    } else {
        const double px = ox - s.centre.x, py = oy - s.centre.y, pz = oz - s.centre.z;
        const double a = dx * dx + dy * dy + dz * dz, b = px * dx + py * dy + pz * dz;
        const double c = px * px + py * py + pz * pz - double(s.radius) * s.radius;
        const double disc = b * b - a * c;
        if (disc >= 0) roots = {(-b - std::sqrt(disc)) / a, (-b + std::sqrt(disc)) / a};
    }
    std::erase_if(roots, [](double t) { return !(t > 0 && std::isfinite(t)); });
    return roots;
}

// The world-space fast path (Shape::world_form: spheres under a similarity — solved in float
// unless an origin on the surface needs double — and planes) against the same equations in
// double: the same hit or miss, and t within float rounding of the ray (relative to the
// origin's distance from the centre, the radius and t; planes divided by the cosine of the
// incidence), for origins far away, near and on the surface (spawned rays, 1e-4 off either
// side, as the ray tracer spawns them), spheres of radius 0.01 to 1000; the same crossing
// counts.
TEST(Intersect, WorldFormSpheresAndPlanesAgreeWithDoubleSolutions) {
    Rng rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    auto unit = [&] { return random_direction(rng); };
    int compared = 0, disagreements = 0, counted = 0, count_differs = 0;
    int spawned_disagreements = 0;  // rays from (1e-4 off) the surface: never a wrong answer
    for (float radius : {0.01f, 1.0f, 37.5f, 1000.0f}) {
        for (int object = 0; object < 2; ++object) {
            ObjectDesc o = sphere_desc();
            if (object == 0) {
                o.radius = radius;
                o.transform = rotation(1, 30.0f) * scaling(Vec3{-1.0f});  // a similarity
            } else {
                o.type = ShapeType::plane;
                o.point = Vec3{0.3f, -0.2f, 0.1f} * radius;
                o.normal = {0.2f, 1.0f, -0.4f};
                o.transform = rotation(0, 20.0f) * scaling({1.0f, 2.0f, 0.5f});  // any affine
            }
            const Shape fast = make_shape(o, 0);
            ASSERT_TRUE(fast.world_form);
            Shape slow = fast;
            slow.world_form = false;
            const Vec3 centre = fast.transform.point({0, 0, 0});
            for (int k = 0; k < 6000; ++k) {
                // an origin: far, on the surface (1e-4 off either side) or near
                Vec3 origin = centre + unit() * (radius * (k % 3 == 0 ? 40.0f : 1.5f * u(rng)));
                if (k % 3 == 1) {
                    Hit h;
                    const Ray probe{centre + unit() * (3.0f * radius), unit()};
                    if (!intersect(slow, probe, 0, inf, h)) continue;
                    const SurfacePoint sp = surface_at(slow, probe, h);
                    origin = sp.P + sp.Ng * ((k & 4) ? 1e-4f : -1e-4f);  // kRayEpsilon
                }
                const Ray r{origin, unit()};
                Hit h;
                const bool hit = intersect(fast, r, 0, inf, h);
                const std::vector<double> roots = world_form_reference(fast, r);
                const double ref = roots.empty() ? 0.0 : roots[0];
                ++compared;
                if (hit != !roots.empty()) {
                    spawned_disagreements += k % 3 == 1;
                    ++disagreements;  // tangent rays, at the rounding of the discriminant
                    continue;
                }
                if (hit) {
                    const double scale =
                        object == 0
                            ? std::max({double(length(origin - centre)), double(radius), ref})
                            : std::max(double(length(origin)), ref) /
                                  std::fabs(dot(fast.normal, r.direction));
                    EXPECT_NEAR(h.t, ref, 2e-6 * scale)
                        << "radius " << radius << " object " << object << " ray " << k;
                    const SurfacePoint a = surface_at(fast, r, h), b = surface_at(slow, r, h);
                    EXPECT_GT(dot(a.N, b.N), 0.9999f);
                }
                uint64_t tests = 0;
                ++counted;
                count_differs += count_crossings(fast, r, 0, inf, false, tests) != roots.size();
            }
        }
    }
    EXPECT_GT(compared, 20000);
    EXPECT_LE(disagreements, compared / 10000) << disagreements << " of " << compared;
    EXPECT_EQ(spawned_disagreements, 0);
    EXPECT_LE(count_differs, counted / 1000) << count_differs << " of " << counted;
    // not a similarity: an ellipsoid stays in object space
    ObjectDesc e = sphere_desc();
    e.transform = scaling({1.0f, 2.0f, 1.0f});
    EXPECT_FALSE(make_shape(e, 0).world_form);
}

}  // namespace
}  // namespace luz::test
