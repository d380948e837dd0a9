// Tests of world-space meshes (build_mesh): transforms of positions and normals, winding under
// mirrors, angle-weighted and file normals, shared vertices, materials, and hits on meshes.
#include "geometry/mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "geometry/shape.h"
#include "geometry/shapes.h"
#include "math/transform.h"
#include "scene/input_error.h"

namespace luz {
namespace {

void expect_vec(const Vec3& a, const Vec3& b, float tol = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

/// The unit cube [0, 1]³ as 12 triangles, counter-clockwise from outside, its faces split
/// along different diagonals (angle weighting must not care).
std::shared_ptr<MeshData> cube() {
    auto d = std::make_shared<MeshData>();
    for (int i = 0; i < 8; ++i)
        d->positions.push_back({float(i & 1), float((i >> 1) & 1), float(i >> 2)});
    // quads (counter-clockwise from outside), each split as (a,b,c)(a,c,d) or (a,b,d)(b,c,d)
    const uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                  {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (int f = 0; f < 6; ++f) {
        const uint32_t* q = quads[f];
        if (f % 2 == 0) {
            d->position.insert(d->position.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
        } else {
            d->position.insert(d->position.end(), {q[0], q[1], q[3], q[1], q[2], q[3]});
        }
    }
    d->normal.assign(d->position.size(), -1);
    d->material.assign(12, -1);
    return d;
}

ObjectDesc mesh_desc(std::shared_ptr<MeshData> d, bool smooth, Affine transform = {}) {
    ObjectDesc o;
    o.type = ShapeType::mesh;
    o.path = "objects.0";
    o.mesh = std::move(d);
    o.smooth = smooth;
    o.transform = transform;
    return o;
}

TEST(Mesh, AngleWeightedNormalsOfACubeCornerPointAlongTheDiagonal) {
    const Mesh m = build_mesh(mesh_desc(cube(), true));
    ASSERT_EQ(m.positions.size(), 8u);  // no file normals: vertices are the positions
    ASSERT_EQ(m.normals.size(), 8u);
    for (size_t i = 0; i < 8; ++i) {
        const Vec3 outward = m.positions[i] - Vec3{0.5f};
        expect_vec(m.normals[i], normalize(outward));
    }
    // every face normal points away from the centre
    for (size_t t = 0; t < m.triangle_count(); ++t) {
        Vec3 a, b, c;
        m.vertices(t, a, b, c);
        EXPECT_GT(dot(m.face_normal(t), (a + b + c) / 3.0f - Vec3{0.5f}), 0) << t;
    }
}

TEST(Mesh, TransformsPositionsAndNormalsAndKeepsWindingOutwardUnderMirrors) {
    const Affine mirror = translation({1, 2, 3}) * rotation(1, 30) * scaling({-2, 0.5f, 1.5f});
    const Mesh m = build_mesh(mesh_desc(cube(), true, mirror));
    const Transform xf = Transform::from(mirror);
    const Vec3 centre = xf.point(Vec3{0.5f});
    for (size_t i = 0; i < m.positions.size(); ++i) {
        EXPECT_GT(dot(m.normals[i], m.positions[i] - centre), 0) << i;
    }
    for (size_t t = 0; t < m.triangle_count(); ++t) {
        Vec3 a, b, c;
        m.vertices(t, a, b, c);
        const Vec3 mid = (a + b + c) / 3.0f;
        EXPECT_GT(dot(m.face_normal(t), mid - centre), 0) << t;
        // flat faces of a cube: the face normal is the inverse transpose of the object one
        const Vec3 object_mid = xf.object_from_world.point(mid) - Vec3{0.5f};
        Vec3 n_obj{0.0f};
        int axis = 0;
        for (int k = 1; k < 3; ++k)
            if (std::fabs(object_mid[k]) > std::fabs(object_mid[axis])) axis = k;
        n_obj[axis] = object_mid[axis] > 0 ? 1.0f : -1.0f;
        expect_vec(m.face_normal(t), normalize(xf.normal(n_obj)));
    }
    expect_vec(m.bounds.lo, xf.bounds(Bounds3{Vec3{0.0f}, Vec3{1.0f}}).lo);
}

TEST(Mesh, FileNormalsByTheInverseTransposeAndSharedVertices) {
    auto d = std::make_shared<MeshData>();
    d->positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    d->normals = {{0, 0, 1}, {1, 0, 1}, {0, 0, 0}};
    // two triangles; vertex 0 and 2 appear with the same normal in both, vertex 1 with two
    d->position = {0, 1, 2, 0, 2, 3};
    d->normal = {0, 1, 0, 0, 0, -1};
    d->material = {-1, -1};
    const Mesh m = build_mesh(mesh_desc(d, true, scaling({2, 1, 1})));
    // (pos 0, n0), (1, n1), (2, n0), (3, computed) — and nothing twice
    ASSERT_EQ(m.positions.size(), 4u);
    EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
    expect_vec(m.normals[1], normalize(Vec3{0.5f, 0, 1}));  // (1,0,1) by diag(1/2, 1, 1)
    expect_vec(m.normals[3], {0, 0, 1});                    // angle-weighted
    // a corner with a zero file normal falls back to the computed normal
    d->normal = {0, 2, 0, 0, 0, -1};
    const Mesh z = build_mesh(mesh_desc(d, true));
    EXPECT_EQ(z.positions.size(), 4u);
    expect_vec(z.normals[1], {0, 0, 1});
}

TEST(Mesh, FlatMeshesHaveNoVertexNormals) {
    const Mesh m = build_mesh(mesh_desc(cube(), false));
    EXPECT_FALSE(m.smooth());
    EXPECT_EQ(m.triangle_count(), 12u);
    for (size_t t = 0; t < m.triangle_count(); ++t) {
        EXPECT_EQ(m.shading_normal(t, 0.2f, 0.3f), m.face_normal(t));
    }
}

TEST(Mesh, TriangleMaterials) {
    auto d = cube();
    d->material = {0, 0, 1, 1, -1, -1, 0, 0, 1, 1, -1, -1};
    ObjectDesc o = mesh_desc(d, true);
    o.material = 7;
    o.mesh_materials = {4, 5};
    const Mesh m = build_mesh(o);
    EXPECT_EQ(m.materials, (std::vector<int32_t>{4, 4, 5, 5, 7, 7, 4, 4, 5, 5, 7, 7}));
    o.mesh_materials.clear();  // the object names a material: all of them
    EXPECT_EQ(build_mesh(o).materials, std::vector<int32_t>(12, 7));
}

TEST(Mesh, HitsGiveInterpolatedShadingNormalsAndTheFaceNormal) {
    const Shape s = make_shape(mesh_desc(cube(), true), 0);
    const Ray r{{0.25f, 0.5f, 5}, {0, 0, -1}};
    Hit hit;
    ASSERT_TRUE(intersect(s, r, 0.0f, 100.0f, hit));
    EXPECT_FLOAT_EQ(hit.t, 4.0f);  // the top face z = 1, not the bottom one
    const SurfacePoint sp = surface_at(s, r, hit);
    expect_vec(sp.P, {0.25f, 0.5f, 1});
    expect_vec(sp.Ng, {0, 0, 1});
    // between the corner normals (±1, ±1, 1)/√3 at x = 0.25, y = 0.5: tilted towards −x
    EXPECT_LT(sp.N.x, -0.1f);
    EXPECT_NEAR(sp.N.y, 0.0f, 1e-5f);
    EXPECT_NEAR(length(sp.N), 1.0f, 1e-5f);
    // flat: N is the face normal
    const Shape f = make_shape(mesh_desc(cube(), false), 0);
    ASSERT_TRUE(intersect(f, r, 0.0f, 100.0f, hit));
    expect_vec(surface_at(f, r, hit).N, {0, 0, 1});
    // nothing behind the ray's start
    EXPECT_FALSE(intersect(s, {{0.5f, 0.5f, 5}, {0, 0, 1}}, 0.0f, 100.0f, hit));
}

TEST(Mesh, VerticesOutOfFloatRangeAreAnInputError) {
    auto d = cube();
    d->positions[3] = {3e38f, 0, 0};
    EXPECT_THROW(build_mesh(mesh_desc(d, true, scaling(Vec3{10}))), InputError);
}

}  // namespace
}  // namespace luz
