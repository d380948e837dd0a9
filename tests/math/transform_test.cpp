// Affine transforms: composition order, inverse, normals by the inverse transpose.
#include "math/transform.h"

#include <gtest/gtest.h>

namespace luz {
namespace {

void expect_vec(const Vec3& a, const Vec3& b, float tol = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

TEST(Transform, RotationFollowsTheRightHandRule) {
    expect_vec(rotation(2, 90).point({1, 0, 0}), {0, 1, 0});
    expect_vec(rotation(0, 90).point({0, 1, 0}), {0, 0, 1});
    expect_vec(rotation(1, 90).point({0, 0, 1}), {1, 0, 0});
}

TEST(Transform, ProductAppliesTheRightFactorFirst) {
    const Affine m = translation({1, 2, 3}) * scaling(Vec3{2.0f});
    expect_vec(m.point({1, 1, 1}), {3, 4, 5});
}

TEST(Transform, InverseUndoes) {
    const Affine m = translation({1, -2, 3}) * rotation(2, 30) * rotation(1, -70) *
                     rotation(0, 10) * scaling({2, 0.5f, -3});
    const Affine inv = inverse(m);
    const Vec3 p{0.3f, -1.2f, 4.0f};
    expect_vec(inv.point(m.point(p)), p, 1e-4f);
    expect_vec(m.point(inv.point(p)), p, 1e-4f);
}

TEST(Transform, NormalsStayPerpendicularUnderNonUniformScale) {
    const Transform t = Transform::from(rotation(2, 25) * scaling({3, 1, 0.5f}));
    // The plane x + y = 0 in object space: tangent (1, −1, 0), normal (1, 1, 0).
    const Vec3 tangent = t.vector({1, -1, 0});
    const Vec3 n = t.normal({1, 1, 0});
    EXPECT_NEAR(dot(tangent, n), 0.0f, 1e-5f);
    EXPECT_NEAR(dot(t.vector({0, 0, 1}), n), 0.0f, 1e-5f);
}

TEST(Transform, BoundsContainTheTransformedBox) {
    const Transform t = Transform::from(rotation(2, 45));
    const Bounds3 b = t.bounds(Bounds3{{-1, -1, -1}, {1, 1, 1}});
    EXPECT_NEAR(b.hi.x, std::sqrt(2.0f), 1e-5f);
    EXPECT_NEAR(b.lo.y, -std::sqrt(2.0f), 1e-5f);
    EXPECT_NEAR(b.hi.z, 1.0f, 1e-6f);
}

}  // namespace
}  // namespace luz
