// Tests of make_shape() (placement of the canonical shapes, user transform) and bounds().
#include "geometry/shape.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "geometry_fixtures.h"

namespace luz::test {
namespace {

void expect_near(const Vec3& a, const Vec3& b, float tol = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

TEST(MakeShape, CylinderRunsFromBaseAlongItsAxis) {
    for (const Vec3 axis : {Vec3{1, 2, 3}, Vec3{0, -5, 0}, Vec3{-0.3f, 0.1f, -2}, Vec3{4, 0, 0}}) {
        ObjectDesc o = cylinder_desc();
        o.axis = axis;
        const Shape s = make_shape(o, 0);
        EXPECT_EQ(s.type, ShapeType::cylinder);
        const Vec3 w = normalize(axis);
        expect_near(s.transform.point({0, 0, 0}), o.base);
        expect_near(s.transform.point({0, 0, 1}), o.base + w * o.height);
        // The rim: radius away from the base, perpendicular to the axis.
        for (const Vec3 rim : {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0.6f, -0.8f, 0}}) {
            const Vec3 d = s.transform.point(rim) - o.base;
            EXPECT_NEAR(length(d), o.radius, 1e-5f);
            EXPECT_NEAR(dot(d, w), 0.0f, 1e-5f);
        }
        EXPECT_GT(s.transform.world_from_object.determinant(), 0.0f);
    }
}

TEST(MakeShape, ConeHasItsRadiusAtTheBaseAndItsApexAtTheTop) {
    const ObjectDesc o = cone_desc();
    const Shape s = make_shape(o, 0);
    expect_near(s.transform.point({0, 0, 1}), o.base + normalize(o.axis) * o.height);
    EXPECT_NEAR(length(s.transform.point({1, 0, 0}) - o.base), o.radius, 1e-5f);
    EXPECT_TRUE(s.caps);
    EXPECT_FALSE(make_shape(cone_desc(false), 0).caps);
    EXPECT_FALSE(make_shape(cylinder_desc(false), 0).caps);
}

TEST(MakeShape, FrustumHasItsApexRadiusAtTheTop) {
    const ObjectDesc o = frustum_desc();
    const Shape s = make_shape(o, 0);
    EXPECT_FLOAT_EQ(s.apex, o.apex_radius / o.radius);
    const Vec3 top = o.base + normalize(o.axis) * o.height;
    expect_near(s.transform.point({0, 0, 1}), top);
    EXPECT_NEAR(length(s.transform.point({s.apex, 0, 1}) - top), o.apex_radius, 1e-5f);
    EXPECT_EQ(make_shape(cone_desc(), 0).apex, 0.0f);
}

TEST(MakeShape, SphereTorusPlaneBoxTriangle) {
    const ObjectDesc sphere = sphere_desc();
    const Shape s = make_shape(sphere, 0);
    expect_near(s.transform.point({0, 0, 0}), sphere.center);
    expect_near(s.transform.point({0, -1, 0}), sphere.center - Vec3{0, sphere.radius, 0});

    const ObjectDesc torus = torus_desc();
    const Shape t = make_shape(torus, 0);
    const Vec3 a = normalize(torus.axis);
    EXPECT_NEAR(t.minor, torus.minor_radius / torus.major_radius, 1e-7f);
    expect_near(t.transform.point({0, 0, 0}), torus.center);
    const Vec3 d = t.transform.point({0, 1, 0}) - torus.center;
    EXPECT_NEAR(length(d), torus.major_radius, 1e-5f);
    EXPECT_NEAR(dot(d, a), 0.0f, 1e-5f);
    expect_near(normalize(t.transform.normal({0, 0, 1})), a);

    const ObjectDesc plane = plane_desc();
    const Shape p = make_shape(plane, 0);
    expect_near(p.transform.point({0, 0, 0}), plane.point);
    expect_near(normalize(p.transform.normal({0, 0, 1})), normalize(plane.normal));

    ObjectDesc box = box_desc();
    std::swap(box.min.x, box.max.x);  // min and max given the wrong way round on x
    const Shape b = make_shape(box, 0);
    EXPECT_EQ(b.lo, (Vec3{-1, 0, -2}));
    EXPECT_EQ(b.hi, (Vec3{2, 1, 0.5f}));

    const ObjectDesc tri = triangle_desc();
    const Shape tr = make_shape(tri, 0);
    for (int k = 0; k < 3; ++k) expect_near(tr.transform.point(tr.vertices[k]), tri.vertices[k]);
}

TEST(MakeShape, UserTransformAppliesAfterThePlacement) {
    ObjectDesc o = sphere_desc();
    o.center = {1, 0, 0};
    o.radius = 0.5f;
    o.transform = user_transform(Vec3{2}, {0, 0, 90}, {0, 5, 0});
    o.material = 3;
    const Shape s = make_shape(o, 7);
    EXPECT_EQ(s.material, 3);
    EXPECT_EQ(s.object, 7);
    // About the world origin: scale 2 → (2, 0, 0), rotate 90° about z → (0, 2, 0), then + 5y.
    expect_near(s.transform.point({0, 0, 0}), {0, 7, 0});
    expect_near(s.transform.point({1, 0, 0}), {0, 8, 0});  // radius 0.5 · 2
}

TEST(MakeShape, MeshIsItsTrianglesInWorldSpace) {
    auto data = std::make_shared<MeshData>();
    data->positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    data->position = {0, 1, 2};
    data->normal = {-1, -1, -1};
    data->material = {-1};
    ObjectDesc o;
    o.type = ShapeType::mesh;
    o.mesh = data;
    o.transform = translation({0, 0, 5});
    const Shape s = make_shape(o, 0);
    ASSERT_NE(s.mesh, nullptr);
    EXPECT_EQ(s.mesh->positions[1], (Vec3{1, 0, 5}));
    EXPECT_EQ(s.transform.point({1, 2, 3}), (Vec3{1, 2, 3}));  // identity: already world space
    const Bounds3 b = bounds(s);
    EXPECT_LE(b.lo.z, 5.0f);
    EXPECT_GE(b.hi.x, 1.0f);
    o.mesh = nullptr;  // no OBJ loaded: an empty mesh with empty bounds
    EXPECT_TRUE(bounds(make_shape(o, 0)).empty());
}

/// Bounds of the tessellation's vertices.
Bounds3 vertex_bounds(const TriangleMesh& m) {
    Bounds3 b;
    for (const Vec3& p : m.positions) b.expand(p);
    return b;
}

TEST(Bounds, ContainEveryTessellatedVertex) {
    for (const auto& obj : all_objects()) {
        for (const auto& tr : user_transforms()) {
            const Shape s = make_shape(with_transform(obj.desc, tr.affine), 0);
            const Bounds3 b = bounds(s);
            for (int level : {3, 5, 64}) {
                SCOPED_TRACE(obj.name + " " + tr.name + " level " + std::to_string(level));
                const Bounds3 v = vertex_bounds(tessellated(s, level));
                for (int k = 0; k < 3; ++k) {
                    EXPECT_LE(b.lo[k], v.lo[k]);
                    EXPECT_GE(b.hi[k], v.hi[k]);
                }
            }
        }
    }
}

TEST(Bounds, AreTight) {
    for (const auto& obj : all_objects()) {
        for (const auto& tr : user_transforms()) {
            // Exact for every shape under a similarity; for the sphere, under any transform.
            if (!tr.similarity && obj.desc.type != ShapeType::sphere) continue;
            SCOPED_TRACE(obj.name + " " + tr.name);
            const Shape s = make_shape(with_transform(obj.desc, tr.affine), 0);
            const Bounds3 b = bounds(s);
            const Bounds3 v = vertex_bounds(tessellated(s, 256));
            for (int k = 0; k < 3; ++k) {
                const float tol = 0.01f * (b.hi[k] - b.lo[k]) + 1e-6f;
                EXPECT_LE(v.lo[k] - b.lo[k], tol) << "axis " << k;
                EXPECT_LE(b.hi[k] - v.hi[k], tol) << "axis " << k;
            }
        }
    }
}

TEST(Bounds, NonUniformShapesStayConservative) {
    // Torus under a non-uniform scale: a superset, never smaller than the surface.
    for (const auto& tr : user_transforms()) {
        const Shape s = make_shape(with_transform(torus_desc(), tr.affine), 0);
        const Bounds3 b = bounds(s), v = vertex_bounds(tessellated(s, 256));
        for (int k = 0; k < 3; ++k) {
            EXPECT_LE(b.lo[k], v.lo[k]);
            EXPECT_GE(b.hi[k], v.hi[k]);
            EXPECT_LT(b.hi[k] - b.lo[k], 1.5f * (v.hi[k] - v.lo[k]));
        }
    }
}

TEST(Bounds, PlaneIsUnbounded) {
    const Shape p = make_shape(plane_desc(), 0);
    EXPECT_FALSE(is_bounded(p));
    EXPECT_TRUE(is_bounded(make_shape(sphere_desc(), 0)));
    const Bounds3 b = bounds(p);
    for (int k = 0; k < 3; ++k) {
        EXPECT_TRUE(std::isinf(b.lo[k]) && b.lo[k] < 0);
        EXPECT_TRUE(std::isinf(b.hi[k]) && b.hi[k] > 0);
    }
}

}  // namespace
}  // namespace luz::test
