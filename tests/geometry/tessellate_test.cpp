// Tests of tessellate() and analytic_area(): unit outward normals, watertightness, winding,
// convergence of the area, and transformed (scaled, rotated, mirrored) shapes.
#include "geometry/tessellate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>

#include "geometry_fixtures.h"

namespace luz::test {
namespace {

constexpr double pi = std::numbers::pi;
const int kLevels[] = {3, 4, 5, 7, 16, 64};

TEST(Tessellate, NormalsAreUnitAndOutward) {
    for (const auto& obj : all_objects()) {
        if (obj.desc.type == ShapeType::triangle) continue;  // two-sided: no outside
        for (const auto& tr : user_transforms()) {
            const Shape s = make_shape(with_transform(obj.desc, tr.affine), 0);
            for (int level : kLevels) {
                SCOPED_TRACE(obj.name + " " + tr.name + " level " + std::to_string(level));
                const TriangleMesh m = tessellated(s, level);
                ASSERT_GT(m.triangle_count(), 0u);
                ASSERT_EQ(m.positions.size(), m.normals.size());
                int bad_length = 0, inward = 0;
                for (size_t i = 0; i < m.positions.size(); ++i) {
                    const Vec3& n = m.normals[i];
                    if (std::fabs(length(n) - 1.0f) > 1e-5f) ++bad_length;
                    if (!(dot(n, m.positions[i] - reference_point(s, m.positions[i])) > 0))
                        ++inward;
                }
                EXPECT_EQ(bad_length, 0);
                EXPECT_EQ(inward, 0);
            }
        }
    }
}

// The memory check counts a tessellation's triangles before making it: the count must be the
// tessellation's own, for every shape and variant (caps or not, cone or frustum), every level.
TEST(Tessellate, TriangleCountIsTheTessellations) {
    for (const auto& obj : all_objects()) {
        const Shape s = make_shape(obj.desc, 0);
        for (int level : {1, 3, 4, 5, 7, 16, 64, 65}) {
            SCOPED_TRACE(obj.name + " level " + std::to_string(level));
            EXPECT_EQ(tessellated_triangle_count(obj.desc, level),
                      tessellated(s, level).triangle_count());
        }
    }
    ObjectDesc plane;
    plane.type = ShapeType::plane;
    EXPECT_EQ(tessellated_triangle_count(plane, 64), 0u);
}

TEST(Tessellate, ClosedShapesAreWatertightAndConsistentlyOriented) {
    for (const auto& obj : all_objects()) {
        if (!obj.closed) continue;
        for (const auto& tr : user_transforms()) {
            const Shape s = make_shape(with_transform(obj.desc, tr.affine), 0);
            for (int level : {3, 4, 5, 7, 16, 64, 256}) {
                SCOPED_TRACE(obj.name + " " + tr.name + " level " + std::to_string(level));
                const TriangleMesh m = tessellated(s, level);
                const EdgeCounts directed = directed_edges(m);  // sorted once for both checks
                int not_two = 0;
                for (const auto& [e, n] : undirected_edges(directed)) not_two += (n != 2);
                EXPECT_EQ(not_two, 0) << "edges not shared by exactly two triangles";
                // Consistent orientation: each directed edge once, its reverse once.
                int unpaired = 0;
                for (const auto& [e, n] : directed) {
                    unpaired += (n != 1 || directed.count({e.second, e.first}) != 1);
                }
                EXPECT_EQ(unpaired, 0);
            }
        }
    }
}

TEST(Tessellate, OpenShapesAreOpenOnlyAtTheirRims) {
    for (int level : {3, 8, 64}) {
        SCOPED_TRACE(level);
        const Shape cyl = make_shape(cylinder_desc(false), 0);
        const Shape cone = make_shape(cone_desc(false), 0);
        const Shape frustum = make_shape(frustum_desc(false), 0);
        for (const auto& [s, rims] :
             {std::pair{cyl, 2}, std::pair{cone, 1}, std::pair{frustum, 2}}) {
            int boundary = 0, more = 0;
            for (const auto& [e, n] : undirected_edges(tessellated(s, level))) {
                boundary += (n == 1);
                more += (n > 2);
            }
            EXPECT_EQ(boundary, rims * level);
            EXPECT_EQ(more, 0);
        }
    }
}

TEST(Tessellate, WindingAgreesWithNormalsAndNoTriangleIsDegenerate) {
    for (const auto& obj : all_objects()) {
        for (const auto& tr : user_transforms()) {
            const Shape s = make_shape(with_transform(obj.desc, tr.affine), 0);
            for (int level : kLevels) {
                SCOPED_TRACE(obj.name + " " + tr.name + " level " + std::to_string(level));
                const TriangleMesh m = tessellated(s, level);
                // A strong non-uniform scale may tilt the analytic normals of a very coarse
                // facet by more than 90° from the facet itself; compare them from level 16.
                const bool compare_normals = tr.similarity || level >= 16;
                int against_normals = 0, facing_in = 0, degenerate = 0;
                for (size_t t = 0; t < m.triangle_count(); ++t) {
                    double f[3];
                    face(m, t, f);
                    const Vec3& a = m.positions[m.indices[3 * t]];
                    const Vec3& b = m.positions[m.indices[3 * t + 1]];
                    const Vec3& c = m.positions[m.indices[3 * t + 2]];
                    const Vec3 n = m.normals[m.indices[3 * t]] + m.normals[m.indices[3 * t + 1]] +
                                   m.normals[m.indices[3 * t + 2]];
                    if (compare_normals && !(f[0] * n.x + f[1] * n.y + f[2] * n.z > 0))
                        ++against_normals;
                    // The facet faces away from the inside, whatever the transform (a torus of
                    // 3 or 4 segments is too coarse for its major circle to tell the inside).
                    if (obj.desc.type != ShapeType::triangle &&
                        (obj.desc.type != ShapeType::torus || level >= 5)) {
                        const Vec3 centroid = (a + b + c) / 3.0f;
                        const Vec3 d = centroid - reference_point(s, centroid);
                        if (!(f[0] * d.x + f[1] * d.y + f[2] * d.z > 0)) ++facing_in;
                    }
                    if (!(face_area(m, t) > 1e-9)) ++degenerate;
                }
                EXPECT_EQ(against_normals, 0);
                EXPECT_EQ(facing_in, 0);
                EXPECT_EQ(degenerate, 0);
            }
        }
    }
}

TEST(Tessellate, LevelIsSegmentsAroundAFullCircle) {
    const int L = 16;
    EXPECT_EQ(tessellated(make_shape(sphere_desc(), 0), L).triangle_count(),
              size_t(2 * L * (L / 2 - 1)));  // L/2 rings, fans at the poles
    EXPECT_EQ(tessellated(make_shape(torus_desc(), 0), L).triangle_count(), size_t(2 * L * L / 2));
    EXPECT_EQ(tessellated(make_shape(cylinder_desc(true), 0), L).triangle_count(), size_t(4 * L));
    EXPECT_EQ(tessellated(make_shape(cylinder_desc(false), 0), L).triangle_count(), size_t(2 * L));
    EXPECT_EQ(tessellated(make_shape(cone_desc(true), 0), L).triangle_count(), size_t(2 * L));
    EXPECT_EQ(tessellated(make_shape(cone_desc(false), 0), L).triangle_count(), size_t(L));
    EXPECT_EQ(tessellated(make_shape(frustum_desc(true), 0), L).triangle_count(), size_t(4 * L));
    EXPECT_EQ(tessellated(make_shape(frustum_desc(false), 0), L).triangle_count(), size_t(2 * L));
    // Torus tube: max(3, level/2) segments.
    EXPECT_EQ(tessellated(make_shape(torus_desc(), 0), 4).triangle_count(), size_t(2 * 4 * 3));
    // Below 3 the level is clamped to 3.
    const Shape sphere = make_shape(sphere_desc(), 0);
    EXPECT_EQ(tessellated(sphere, 1).triangle_count(), tessellated(sphere, 3).triangle_count());
}

TEST(Tessellate, BoxIsTwelveTrianglesWithFaceNormals) {
    for (const auto& tr : user_transforms()) {
        SCOPED_TRACE(tr.name);
        const Shape s = make_shape(with_transform(box_desc(), tr.affine), 0);
        const TriangleMesh m = tessellated(s, 64);
        EXPECT_EQ(m.triangle_count(), 12u);
        EXPECT_EQ(m.positions.size(), 24u);
        // The three vertex normals of each triangle are the face's own normal.
        for (size_t t = 0; t < m.triangle_count(); ++t) {
            double f[3];
            face(m, t, f);
            const double len = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
            for (int k = 0; k < 3; ++k) {
                const Vec3& n = m.normals[m.indices[3 * t + k]];
                EXPECT_NEAR((f[0] * n.x + f[1] * n.y + f[2] * n.z) / len, 1.0, 1e-5);
            }
        }
    }
}

TEST(Tessellate, TriangleNormalFollowsItsWinding) {
    for (const auto& tr : user_transforms()) {
        SCOPED_TRACE(tr.name);
        const ObjectDesc o = with_transform(triangle_desc(), tr.affine);
        const Shape s = make_shape(o, 0);
        const TriangleMesh m = tessellated(s, 64);
        ASSERT_EQ(m.triangle_count(), 1u);
        // The world triangle keeps the keys' vertex order, possibly rotated or reversed.
        const Vec3 a = s.transform.point(o.vertices[0]), b = s.transform.point(o.vertices[1]),
                   c = s.transform.point(o.vertices[2]);
        const Vec3 expected =
            normalize(cross(b - a, c - a)) * (tr.affine.determinant() < 0 ? -1.0f : 1.0f);
        for (int k = 0; k < 3; ++k) {
            const Vec3& n = m.normals[k];
            EXPECT_NEAR(dot(n, expected), 1.0f, 1e-5f);
        }
        // Without a mirror the keys' order is kept.
        if (tr.affine.determinant() > 0) {
            EXPECT_EQ(m.positions[m.indices[0]], a);
            EXPECT_EQ(m.positions[m.indices[1]], b);
            EXPECT_EQ(m.positions[m.indices[2]], c);
        }
    }
}

TEST(Tessellate, PlaneAppendsNothing) {
    TriangleMesh m;
    tessellate(make_shape(plane_desc(), 0), 64, m);
    EXPECT_EQ(m.positions.size(), 0u);
    EXPECT_EQ(m.indices.size(), 0u);
}

TEST(Tessellate, AppendsToTheMesh) {
    TriangleMesh m;
    tessellate(make_shape(box_desc(), 0), 8, m);
    const size_t vertices = m.positions.size(), indices = m.indices.size();
    tessellate(make_shape(sphere_desc(), 1), 8, m);
    EXPECT_GT(m.positions.size(), vertices);
    EXPECT_EQ(m.positions.size(), m.normals.size());
    for (size_t i = 0; i < indices; ++i) EXPECT_LT(m.indices[i], vertices);
    for (size_t i = indices; i < m.indices.size(); ++i) {
        EXPECT_GE(m.indices[i], vertices);
        EXPECT_LT(m.indices[i], m.positions.size());
    }
}

TEST(Tessellate, NormalsAreAnalytic) {
    for (const auto& tr : user_transforms()) {
        SCOPED_TRACE(tr.name);
        // Sphere: the normal of the ellipsoid is M⁻ᵀ·(object point).
        const Shape sphere = make_shape(with_transform(sphere_desc(), tr.affine), 0);
        TriangleMesh m = tessellated(sphere, 32);
        for (size_t i = 0; i < m.positions.size(); ++i) {
            const Vec3 q = sphere.transform.object_from_world.point(m.positions[i]);
            EXPECT_NEAR(dot(m.normals[i], normalize(sphere.transform.normal(q))), 1.0f, 1e-5f);
        }
        // Torus: the object normal points from the major circle to the vertex.
        const Shape torus = make_shape(with_transform(torus_desc(), tr.affine), 0);
        m = tessellated(torus, 32);
        for (size_t i = 0; i < m.positions.size(); ++i) {
            const Vec3 q = torus.transform.object_from_world.point(m.positions[i]);
            const Vec3 n = q - normalize(Vec3{q.x, q.y, 0});
            EXPECT_NEAR(dot(m.normals[i], normalize(torus.transform.normal(n))), 1.0f, 1e-4f);
        }
    }
}

TEST(Tessellate, CylinderAndConeSideNormals) {
    const ObjectDesc cyl = cylinder_desc(false), cone = cone_desc(false);
    const Vec3 cyl_axis = normalize(cyl.axis), cone_axis = normalize(cone.axis);
    for (const Vec3& n : tessellated(make_shape(cyl, 0), 24).normals)
        EXPECT_NEAR(dot(n, cyl_axis), 0.0f, 1e-6f);
    // Every side normal, the apex ring's included, makes the same angle with the axis:
    // N·axis = r / slant.
    const TriangleMesh m = tessellated(make_shape(cone, 0), 24);
    const float expected = cone.radius / std::hypot(cone.radius, cone.height);
    for (const Vec3& n : m.normals) EXPECT_NEAR(dot(n, cone_axis), expected, 1e-5f);
    // The apex ring: one vertex per segment at the apex, each with its own mid-angle normal,
    // halfway between the normals of the segment's base vertices.
    const Vec3 apex = cone.base + cone_axis * cone.height;
    std::set<std::tuple<float, float, float>> apex_normals;
    for (size_t t = 0; t < m.triangle_count(); ++t) {
        for (int k = 0; k < 3; ++k) {
            const uint32_t i = m.indices[3 * t + k];
            if (length(m.positions[i] - apex) > 1e-5f) continue;
            apex_normals.insert(key(m.normals[i]));
            // Equally far from both base normals (the mid-angle), and close to them.
            const Vec3& n1 = m.normals[m.indices[3 * t + (k + 1) % 3]];
            const Vec3& n2 = m.normals[m.indices[3 * t + (k + 2) % 3]];
            EXPECT_NEAR(dot(m.normals[i], n1), dot(m.normals[i], n2), 1e-6f);
            EXPECT_GT(dot(m.normals[i], n1), dot(n1, n2));
        }
    }
    EXPECT_EQ(apex_normals.size(), 24u);
}

TEST(Tessellate, FrustumSideNormalsAndTopRim) {
    const ObjectDesc f = frustum_desc(false);
    const Vec3 axis = normalize(f.axis), top = f.base + axis * f.height;
    const TriangleMesh m = tessellated(make_shape(f, 0), 24);
    // N·axis = (r − r′) / slant at every vertex; each vertex on the base rim or the top rim
    const double dr = f.radius - f.apex_radius;
    const float expected = static_cast<float>(dr / std::hypot(dr, double(f.height)));
    for (size_t i = 0; i < m.positions.size(); ++i) {
        EXPECT_NEAR(dot(m.normals[i], axis), expected, 1e-5f);
        const float from_base = length(m.positions[i] - f.base);
        const float from_top = length(m.positions[i] - top);
        EXPECT_TRUE(std::fabs(from_base - f.radius) < 1e-5f ||
                    std::fabs(from_top - f.apex_radius) < 1e-5f)
            << i;
    }
}

TEST(Tessellate, AnalyticAreas) {
    const double k = 1.7 * 1.7;  // the similarity transform's uniform scale, squared
    const Affine sim = user_transforms()[1].affine;
    struct Case {
        ObjectDesc o;
        double area;
    } cases[] = {
        {sphere_desc(), 4 * pi * 1.5 * 1.5},
        {box_desc(), 2 * (3 * 1 + 1 * 2.5 + 2.5 * 3)},
        {cylinder_desc(true), 2 * pi * 0.5 * 2 + 2 * pi * 0.25},
        {cylinder_desc(false), 2 * pi * 0.5 * 2},
        {cone_desc(true), pi * 0.6 * std::hypot(0.6, 1.5) + pi * 0.36},
        {cone_desc(false), pi * 0.6 * std::hypot(0.6, 1.5)},
        {frustum_desc(true), pi * 0.85 * std::hypot(0.35, 1.5) + pi * (0.36 + 0.0625)},
        {frustum_desc(false), pi * 0.85 * std::hypot(0.35, 1.5)},
        {torus_desc(), 4 * pi * pi * 1.2 * 0.35},
        {triangle_desc(), 0.5 * 3.5},  // |(−1.5, −1, 3)| / 2
    };
    for (const auto& c : cases) {
        EXPECT_NEAR(analytic_area(make_shape(c.o, 0)), c.area, 1e-5 * c.area);
        EXPECT_NEAR(analytic_area(make_shape(with_transform(c.o, sim), 0)), k * c.area,
                    1e-5 * k * c.area);
    }
    EXPECT_TRUE(std::isinf(analytic_area(make_shape(plane_desc(), 0))));
}

TEST(Tessellate, AreaConvergesToAnalyticArea) {
    for (const auto& obj : all_objects()) {
        for (const auto& tr : user_transforms()) {
            if (!tr.similarity) continue;  // analytic_area assumes a uniform scale
            const Shape s = make_shape(with_transform(obj.desc, tr.affine), 0);
            const double exact = analytic_area(s);
            SCOPED_TRACE(obj.name + " " + tr.name);
            if (obj.desc.type == ShapeType::box || obj.desc.type == ShapeType::triangle) {
                EXPECT_NEAR(total_area(tessellated(s, 8)), exact, 1e-5 * exact);
                continue;
            }
            double previous = 1e300;
            for (int level : {8, 16, 32, 64, 128, 256}) {
                const double error = std::fabs(total_area(tessellated(s, level)) - exact) / exact;
                EXPECT_LT(error, previous) << "level " << level;
                previous = error;
            }
            EXPECT_LT(previous, 1e-3);
        }
    }
}

}  // namespace
}  // namespace luz::test
