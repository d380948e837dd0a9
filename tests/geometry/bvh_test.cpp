// The BVH against brute force: the same nearest hit (t, shape, triangle) and the same shadow
// answers for 100 000 random rays per scene, on random and degenerate meshes (zero-area
// triangles, every triangle in one plane, duplicated triangles) mixed with other shapes.
#include "geometry/bvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <random>

#include "bvh_fixtures.h"
#include "bvh_reference.h"
#include "geometry/prim_block.h"
#include "geometry/scene.h"
#include "geometry/scene_query.h"
#include "geometry_fixtures.h"
#include "math/lane_count.h"

namespace luz {
namespace {

using test::box;
using test::cylinder_field;
using test::degenerate_mesh;
using test::mesh_object;
using test::planar_grid;
using test::plane;
using test::random_direction;
using test::random_point;
using test::random_soup;
using test::RandomRays;
using test::Rng;
using test::scene_with;
using test::sphere;
using test::uniform;

// Random rays each brute-force comparison traces: a fifth under AddressSanitizer, where each
// takes ten times as long (the same traversal code, the memory checks on every access).
#if defined(__SANITIZE_ADDRESS__)
constexpr int kBruteForceRays = 20000;
#else
constexpr int kBruteForceRays = 100000;
#endif

/// Runs `rays` random rays through both accelerations; every answer must be the same.
/// `fewer_tests`: the BVH must also test far fewer primitives (not so where large overlapping
/// shapes fill the scene: `none` tests each behind its own box, a BVH leaf all its lanes).
void expect_bvh_equals_brute_force(const SceneDesc& desc, int rays, bool fewer_tests = true) {
    const BuiltScene bvh = build_scene(desc);
    ASSERT_TRUE(bvh.has_bvh);
    ASSERT_GT(bvh.bvh.nodes().size(), 1u);
    BuiltScene all = bvh;
    all.geometry.accel = Accel::none;

    RandomRays gen;
    for (const Shape& s : bvh.shapes) {
        if (s.mesh) {
            gen.targets.insert(gen.targets.end(), s.mesh->positions.begin(),
                               s.mesh->positions.end());
        }
    }
    IntersectCounters cb, ca;
    int hits = 0, shadowed = 0, partial = 0, mismatches = 0;
    for (int k = 0; k < rays; ++k) {
        float t_max;
        const Ray r = gen.next(k, t_max);
        Hit hb, ha;
        const bool fb = nearest_hit(bvh, r, 0.0f, t_max, hb, cb);
        const bool fa = nearest_hit(all, r, 0.0f, t_max, ha, ca);
        const bool same = fb == fa && (!fb || (hb.t == ha.t && hb.shape == ha.shape &&
                                               hb.part == ha.part && hb.u == ha.u && hb.v == ha.v));
        const float Tb = transmittance(bvh, desc.materials, r, 0.0f, t_max, cb);
        const float Ta = transmittance(all, desc.materials, r, 0.0f, t_max, ca);
        if (!same || std::memcmp(&Tb, &Ta, sizeof(float)) != 0) {
            if (++mismatches <= 5) {
                ADD_FAILURE() << "ray " << k << " from (" << r.origin.x << ", " << r.origin.y
                              << ", " << r.origin.z << ") dir (" << r.direction.x << ", "
                              << r.direction.y << ", " << r.direction.z << "): bvh " << fb
                              << " t=" << hb.t << " shape " << hb.shape << " part " << hb.part
                              << " T=" << Tb << "; all " << fa << " t=" << ha.t << " shape "
                              << ha.shape << " part " << ha.part << " T=" << Ta;
            }
        }
        hits += fa;
        shadowed += Ta == 0;
        partial += Ta > 0 && Ta < 1;
    }
    EXPECT_EQ(mismatches, 0);
    // The rays did meet things, and the BVH tested far fewer primitives.
    EXPECT_GT(hits, rays / 5);
    EXPECT_GT(shadowed, rays / 20);
    EXPECT_GT(partial, rays / 100);
    if (fewer_tests) {
        EXPECT_LT(cb.primitive * 5, ca.primitive);
    }
    ::testing::Test::RecordProperty("primitive_tests_bvh", std::to_string(cb.primitive));
    ::testing::Test::RecordProperty("primitive_tests_all", std::to_string(ca.primitive));
}

TEST(BvhEqualsBruteForce, RandomMeshesAndShapes) {
    Rng rng(1);
    std::vector<ObjectDesc> objects = {random_soup(rng, 300, 0), random_soup(rng, 150, 1),
                                       sphere({1, 1, 1}, 1.5f, 1), sphere({-2, 2, -1}, 0.7f, 0)};
    objects.push_back(box({2, -3, -3}, {3, -1, 0}, 2));
    objects.push_back(plane({0, -5, 0}, 2));
    expect_bvh_equals_brute_force(scene_with(objects), kBruteForceRays);
}

TEST(BvhEqualsBruteForce, CylindersAmongSpheres) {
    Rng rng(3);
    expect_bvh_equals_brute_force(scene_with(cylinder_field(rng)), kBruteForceRays, false);
}

TEST(BvhEqualsBruteForce, AllTrianglesInOnePlane) {
    Rng rng(2);
    // a regular grid (shared edges and vertices), and random triangles lying in the same plane
    ObjectDesc soup = random_soup(rng, 200, 1);
    auto data = std::make_shared<MeshData>(*soup.mesh);
    for (Vec3& p : data->positions) p.z = 0.0f;
    soup.mesh = data;
    expect_bvh_equals_brute_force(scene_with({planar_grid(16, 0.0f, 0), soup}), kBruteForceRays);
}

TEST(BvhEqualsBruteForce, ZeroAreaAndDuplicatedTriangles) {
    Rng rng(3);
    const ObjectDesc soup = random_soup(rng, 150, 0);
    const ObjectDesc grid = planar_grid(8, 1.0f, 1);
    // the same triangles twice in one mesh, and again as another object
    expect_bvh_equals_brute_force(
        scene_with({degenerate_mesh(rng, soup, 100, 0), degenerate_mesh(rng, grid, 60, 1), soup,
                    sphere({0, 0, 1}, 1.0f, 2)}),
        kBruteForceRays);
}

TEST(BvhEqualsBruteForce, ShadowProductsDoNotDependOnTheOrderOfCrossings) {
    // 40 stacked transparent layers of four materials, interleaved: the BVH meets them in
    // space order, testing everything meets them object by object; the float products must
    // still be the same bits.
    SceneDesc d = scene_with({});
    d.materials.resize(5);
    const float tau[4] = {0.7f, 0.35f, 0.9f, 0.61f};
    for (int m = 0; m < 4; ++m) d.materials[m + 1].transparency = tau[m];
    for (int m = 0; m < 4; ++m) {
        std::vector<Vec3> p;
        std::vector<uint32_t> idx;
        for (int k = 0; k < 10; ++k) {
            const float z = 0.1f * (4 * k + (m * 3) % 4);
            const uint32_t i = static_cast<uint32_t>(p.size());
            p.insert(p.end(), {{-9, -9, z}, {9, -9, z}, {0, 9, z}});
            idx.insert(idx.end(), {i, i + 1, i + 2});
        }
        d.objects.push_back(mesh_object(p, idx, m + 1));
    }
    const BuiltScene bvh = build_scene(d);
    BuiltScene all = bvh;
    all.geometry.accel = Accel::none;
    Rng rng(7);
    IntersectCounters c;
    for (int k = 0; k < 2000; ++k) {
        const Vec3 o{uniform(rng, -1, 1), uniform(rng, -1, 1), -1};
        const Vec3 to{uniform(rng, -1, 1), uniform(rng, -1, 1), 6};
        const Ray r{o, normalize(to - o)};
        const float Tb = transmittance(bvh, d.materials, r, 0.0f, length(to - o), c);
        const float Ta = transmittance(all, d.materials, r, 0.0f, length(to - o), c);
        ASSERT_EQ(std::memcmp(&Tb, &Ta, sizeof(float)), 0) << k << ": " << Tb << " vs " << Ta;
        ASSERT_NEAR(Ta, std::pow(0.7 * 0.35 * 0.9 * 0.61, 10), 1e-9);
    }
}

/// A cylinder (or, `cone`, a frustum) of radius r from `base` along `axis` for `height`.
ObjectDesc rod(Vec3 base, Vec3 axis, float height, float r, int material, bool cone = false) {
    ObjectDesc o;
    o.type = cone ? ShapeType::cone : ShapeType::cylinder;
    o.base = base;
    o.axis = axis;
    o.height = height;
    o.radius = r;
    o.apex_radius = cone ? r / 2 : 0.0f;
    o.caps = true;
    o.material = material;
    return o;
}

// Long slanted cylinders and frusta enter the BVH as pieces (Shape::split), each in its own
// leaf: a nearest hit is found whichever piece meets the ray first, and a shadow ray counts a
// glass rod's crossings once however many of its pieces it passes.
TEST(BvhEqualsBruteForce, SplitGlassRods) {
    Rng rng(11);
    std::vector<ObjectDesc> objects;
    for (int i = 0; i < 240; ++i) {
        objects.push_back(rod(random_point(rng, -4, 4), random_direction(rng), uniform(rng, 1, 4),
                              uniform(rng, 0.05f, 0.2f), i % 3, i % 4 == 0));
    }
    const SceneDesc desc = scene_with(objects);
    const BuiltScene scene = build_scene(desc);
    int split = 0;
    for (const Shape& s : scene.shapes) split += s.split;
    EXPECT_GT(split, 120);
    expect_bvh_equals_brute_force(desc, kBruteForceRays, false);
}

// A segment through more split glass rods than a shadow ray remembers (query::Crossings):
// the product is then found by testing every shape, the same bits as the brute force.
TEST(BvhEqualsBruteForce, SegmentThroughFortySplitGlassRods) {
    std::vector<ObjectDesc> objects;
    for (int i = 0; i < 40; ++i)  // rods along (0, 1, 1) in a row along x
        objects.push_back(rod({i * 0.5f, -2, -2}, {0, 1, 1}, 6, 0.2f, 1 + i % 2, i % 3 == 0));
    const SceneDesc d = scene_with(objects);
    const BuiltScene bvh = build_scene(d);
    for (const Shape& s : bvh.shapes) ASSERT_TRUE(s.split);
    BuiltScene all = bvh;
    all.geometry.accel = Accel::none;
    Rng rng(5);
    IntersectCounters c;
    SegmentLanes lanes;
    float T_lanes[kMaxPacket];
    for (int k = 0; k < 400; ++k) {
        // along x through every rod (at any height, so also where two pieces meet and the
        // segment passes through both their boxes), or across a few of them
        const float h = uniform(rng, -1.8f, 1.8f);
        const Vec3 o{-1, h + uniform(rng, -0.05f, 0.05f), h + uniform(rng, -0.05f, 0.05f)};
        const Vec3 to = k % 2 == 0 ? Vec3{21, o.y, o.z} : random_point(rng, 0, 6);
        const Ray r{o, normalize(to - o)};
        const float t_max = length(to - o);
        const float Tb = transmittance(bvh, d.materials, r, 0.0f, t_max, c);
        const float Ta = transmittance(all, d.materials, r, 0.0f, t_max, c);
        ASSERT_EQ(std::memcmp(&Tb, &Ta, sizeof(float)), 0) << k << ": " << Tb << " vs " << Ta;
        if (k % 2 == 0) {
            ASSERT_NEAR(Ta, std::pow(0.7 * 0.35, 40), 1e-20) << k;
        }
        const int l = k % kMaxPacket;
        lanes.ox[l] = r.origin.x, lanes.oy[l] = r.origin.y, lanes.oz[l] = r.origin.z;
        lanes.dx[l] = r.direction.x, lanes.dy[l] = r.direction.y, lanes.dz[l] = r.direction.z;
        lanes.t_max[l] = t_max;
        if (l + 1 < kMaxPacket) continue;
        transmittances(bvh, d.materials, lanes, (1u << kMaxPacket) - 1, T_lanes, c);
        for (int j = 0; j < kMaxPacket; ++j) {
            const float Tj = transmittance(all, d.materials, lanes.ray(j), 0.0f, lanes.t_max[j], c);
            ASSERT_EQ(std::memcmp(&T_lanes[j], &Tj, sizeof(float)), 0) << k << " lane " << j;
        }
    }
}

}  // namespace
}  // namespace luz
