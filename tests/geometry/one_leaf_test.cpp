// Scenes whose BVH is one leaf (BuiltScene::root_leaf): the leaf alone, the traversed BVH and
// testing everything give the same bits; shadow segments and packets four at a time bit for bit;
// an opaque cylinder ends a shadow ray's block before its spheres.
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
#include "geometry/bvh.h"
#include "geometry/prim_block.h"
#include "geometry/scene.h"
#include "geometry/scene_query.h"
#include "geometry_fixtures.h"
#include "math/lane_count.h"

namespace luz {
namespace {

using test::box;
using test::camera_rays;
using test::plane;
using test::random_direction;
using test::random_point;
using test::RandomRays;
using test::Rng;
using test::scene_with;
using test::sphere;
using test::uniform;

/// The world-form sphere lanes of the scene's BVH blocks.
int sphere_lanes(const BuiltScene& scene) {
    int n = 0;
    for (const PrimBlock& b : scene.bvh_blocks) n += lane_count(b.sphere_lanes());
    return n;
}

/// Whether r meets the world-form sphere (centre c, radius) by world_sphere_roots()'s double
/// path, as a block's sphere lane hands it over.
bool takes_double_path(const Vec3& c, float radius, const Ray& r) {
    const float cx[4] = {c.x}, cy[4] = {c.y}, cz[4] = {c.z}, rr[4] = {radius * radius},
                rad[4] = {radius};
    return sphere_lanes_roots({cx, cy, cz, rr, rad, 1u}, r).slow != 0;
}

TEST(OneLeaf, TheLeafAloneEqualsTheTraversedBvhAndTestingEverything) {
    // A few shapes: the BVH is one leaf (BuiltScene::root_leaf), tested without the node loop
    // (spheres in world form without any box). Spheres far away make the same scene a BVH of
    // several leaves, traversed; every answer must be the same bits in all three ways,
    // including ties: two coincident spheres of different materials (the lower one wins).
    std::vector<ObjectDesc> objects = {sphere({0, 0, 0}, 1.5f, 1), sphere({0, 0, 0}, 1.5f, 2),
                                       sphere({2, 1, -1}, 0.8f, 0)};
    ObjectDesc ellipsoid = sphere({-2, 1, 1}, 1.0f, 1);
    ellipsoid.transform = scaling({1.5f, 0.5f, 1.0f});  // not a similarity: object space
    objects.push_back(ellipsoid);
    objects.push_back(box({1, -3, 1}, {3, -1, 2}, 2));
    ObjectDesc torus = test::torus_desc();
    torus.material = 1;
    objects.push_back(torus);
    objects.push_back(plane({0, -4, 0}, 2));
    ASSERT_LE(objects.size(), 8u);
    const SceneDesc leaf_desc = scene_with(objects);
    const BuiltScene leaf = build_scene(leaf_desc);
    for (int k = 0; k < 4; ++k) objects.push_back(sphere({500, 500, 500.0f + 3 * k}, 1.0f, 0));
    const BuiltScene bvh = build_scene(scene_with(objects));
    BuiltScene all = leaf;
    all.geometry.accel = Accel::none;

    RandomRays gen;
    IntersectCounters cd, cb, ca;
    int hits = 0, ties = 0, partial = 0, mismatches = 0, slow = 0;
    ASSERT_NE(leaf.root_leaf, 0u);
    ASSERT_EQ(bvh.root_leaf, 0u);
    ASSERT_EQ(sphere_lanes(leaf), 3);  // the three spheres in world form
    for (int k = 0; k < 50000; ++k) {
        float t_max;
        Ray r = gen.next(k, t_max);
        if (k % 3 == 2) {
            // from the first sphere's surface: 1e-4 off it, as spawned rays start, or on it,
            // where its lane hands over to the scalar test's double path
            const float offset = (k & 8) ? 1e-4f : (k & 16) ? -1e-4f : 0.0f;
            r.origin = random_direction(gen.rng) * (1.5f + offset);
            slow += takes_double_path({0, 0, 0}, 1.5f, r);
        }
        Hit h[3];
        const bool f[3] = {nearest_hit(leaf, r, 0.0f, t_max, h[0], cd),
                           nearest_hit(bvh, r, 0.0f, t_max, h[1], cb),
                           nearest_hit(all, r, 0.0f, t_max, h[2], ca)};
        const float T[3] = {transmittance(leaf, leaf_desc.materials, r, 0.0f, t_max, cd),
                            transmittance(bvh, leaf_desc.materials, r, 0.0f, t_max, cb),
                            transmittance(all, leaf_desc.materials, r, 0.0f, t_max, ca)};
        for (int w = 1; w < 3; ++w) {
            const bool same =
                f[0] == f[w] &&
                (!f[0] || (h[0].t == h[w].t && h[0].shape == h[w].shape && h[0].part == h[w].part));
            if ((!same || std::memcmp(&T[0], &T[w], sizeof(float)) != 0) && ++mismatches <= 5) {
                ADD_FAILURE() << "ray " << k << " way " << w << ": shape " << h[0].shape
                              << " t=" << h[0].t << " T=" << T[0] << " vs shape " << h[w].shape
                              << " t=" << h[w].t << " T=" << T[w];
            }
        }
        hits += f[0];
        ties += f[0] && h[0].shape == 0;
        EXPECT_NE(h[0].shape, 1) << "ray " << k << ": the tie went to the higher sphere";
        partial += T[0] > 0 && T[0] < 1;
    }
    EXPECT_EQ(mismatches, 0);
    EXPECT_GT(hits, 10000);
    EXPECT_GT(ties, 1000);
    EXPECT_GT(partial, 1000);
    EXPECT_GT(slow, 1000);
    // The one leaf was tested without a box around a world-form sphere; the BVH and `none`
    // tested boxes.
    EXPECT_LT(cd.bounds, ca.bounds / 2);
}

// A few primitives of both kinds (a ground quad's two triangles and two spheres) stay one leaf:
// leaves by kind (BvhOptions::kinds) start only where the BVH has nodes anyway.
TEST(OneLeaf, AFewTrianglesAndShapesShareTheOneLeaf) {
    const ObjectDesc quad =
        test::mesh_object({{-5, -5, 0}, {5, -5, 0}, {5, 5, 0}, {-5, 5, 0}}, {0, 1, 2, 0, 2, 3}, 0);
    const BuiltScene scene =
        build_scene(scene_with({quad, sphere({0, 0, 1}, 1.0f, 0), sphere({2, 2, 1}, 0.5f, 1)}));
    EXPECT_EQ(scene.root_leaf, 4u);
    EXPECT_EQ(scene.mesh_triangles, 2u);
}

TEST(OneLeaf, AnOpaqueCylinderSparesItsBlocksSpheres) {
    // Two open cylinders in world form and two spheres: one leaf, one block. A shadow ray that
    // an opaque cylinder blocks stops before the spheres' test (query_parts.h,
    // cross_block_shapes()); one that no cylinder blocks tests all four lanes.
    const auto open_cylinder = [](Vec3 base, int material) {
        ObjectDesc o;
        o.type = ShapeType::cylinder;
        o.base = base;
        o.axis = {0, 0, 1};
        o.height = 2.0f;
        o.radius = 0.5f;
        o.caps = false;
        o.material = material;
        return o;
    };
    const SceneDesc d = scene_with({open_cylinder({0, 0, 0}, 0), open_cylinder({3, 0, 0}, 1),
                                    sphere({6, 0, 1}, 0.5f, 0), sphere({-3, 0, 1}, 0.5f, 0)});
    const BuiltScene scene = build_scene(d);
    ASSERT_EQ(scene.root_leaf, 4u);
    ASSERT_EQ(scene.bvh_blocks.size(), 1u);
    ASSERT_EQ(lane_count(scene.bvh_blocks[0].cylinder_lanes()), 2);
    ASSERT_EQ(lane_count(scene.bvh_blocks[0].sphere_lanes()), 2);

    IntersectCounters blocked;  // through the opaque cylinder at x = 0
    EXPECT_EQ(transmittance(scene, d.materials, Ray{{0, -5, 1}, {0, 1, 0}}, 0.0f, 10.0f, blocked),
              0.0f);
    EXPECT_EQ(blocked.primitive, 2u);

    IntersectCounters glass;  // through the glass cylinder at x = 3 (0.7, crossed twice)
    EXPECT_FLOAT_EQ(
        transmittance(scene, d.materials, Ray{{3, -5, 1}, {0, 1, 0}}, 0.0f, 10.0f, glass),
        0.7f * 0.7f);
    EXPECT_EQ(glass.primitive, 4u);
}

TEST(OneLeaf, ShadowSegmentsFourAtATimeBitForBit) {
    // transmittances() in a scene whose BVH is one leaf takes four segments at a time against
    // each sphere in world form and each plane (query_leaf_packet.cpp): every transmittance and
    // every count must be what transmittance() gives segment by segment — five spheres (two
    // groups; opaque, 0.7 and 0.35 transparent, a tie), two planes; segments from a sphere's
    // surface (its double path), through glass (products), into opaque spheres and planes
    // (early ends), of zero or tiny direction (one by one), any subset of eight lanes. Then
    // the same with an ellipsoid added, whose block is left to transmittance().
    std::vector<ObjectDesc> objects = {sphere({0, 0, 0}, 1.5f, 1),  sphere({0, 0, 0}, 1.5f, 2),
                                       sphere({2, 1, -1}, 0.8f, 0), sphere({-2, 2, 0}, 0.6f, 1),
                                       sphere({0, 3, -2}, 1.1f, 2), plane({0, -4, 0}, 1),
                                       plane({0, 5, 0}, 0)};
    for (const bool with_ellipsoid : {false, true}) {
        if (with_ellipsoid) {
            ObjectDesc ellipsoid = sphere({-2, 1, 1}, 1.0f, 1);
            ellipsoid.transform = scaling({1.5f, 0.5f, 1.0f});
            objects.push_back(ellipsoid);
        }
        const SceneDesc desc = scene_with(objects);
        const BuiltScene scene = build_scene(desc);
        ASSERT_NE(scene.root_leaf, 0u);
        ASSERT_EQ(sphere_lanes(scene), 5);
        RandomRays gen;
        IntersectCounters by_lanes, one_by_one;
        int mismatches = 0, partial = 0, blocked = 0, slow = 0;
        for (int batch = 0; batch < 6000; ++batch) {
            SegmentLanes seg;
            const unsigned active = batch % 7 == 3 ? (batch * 37u) & 0xFFu : 0xFFu;
            for (int k = 0; k < kMaxPacket; ++k) {
                float t_max;
                Ray r = gen.next(batch * 8 + k, t_max);
                if (k % 3 == 1) {  // from the first sphere's surface, on it or 1e-4 off it
                    const float offset = (k & 4) ? 1e-4f : (batch & 1) ? -1e-4f : 0.0f;
                    r.origin = random_direction(gen.rng) * (1.5f + offset);
                    slow += takes_double_path({0, 0, 0}, 1.5f, r);
                }
                if (batch % 97 == 5 && k == 2) r.direction = Vec3{0.0f};
                if (batch % 89 == 7 && k == 6) r.direction = r.direction * 0x1p-40f;
                if (std::isinf(t_max)) t_max = uniform(gen.rng, 1.0f, 20.0f);
                seg.ox[k] = r.origin.x;
                seg.oy[k] = r.origin.y;
                seg.oz[k] = r.origin.z;
                seg.dx[k] = r.direction.x;
                seg.dy[k] = r.direction.y;
                seg.dz[k] = r.direction.z;
                seg.t_max[k] = t_max;
            }
            float T[kMaxPacket];
            transmittances(scene, desc.materials, seg, active, T, by_lanes);
            for (int k = 0; k < kMaxPacket; ++k) {
                if (!(active >> k & 1u)) continue;
                const float expected = transmittance(scene, desc.materials, seg.ray(k), 0.0f,
                                                     seg.t_max[k], one_by_one);
                if (std::memcmp(&expected, &T[k], sizeof(float)) != 0 && ++mismatches <= 5) {
                    ADD_FAILURE() << "batch " << batch << " lane " << k << ": " << T[k]
                                  << " vs transmittance() " << expected;
                }
                partial += expected > 0 && expected < 1;
                blocked += expected == 0;
            }
        }
        EXPECT_EQ(mismatches, 0);
        EXPECT_EQ(by_lanes.primitive, one_by_one.primitive);
        EXPECT_EQ(by_lanes.bounds, one_by_one.bounds);
        EXPECT_GT(partial, 2000);
        EXPECT_GT(blocked, 2000);
        EXPECT_GT(slow, 1000);
    }
}

TEST(OneLeaf, PacketsTestFourRaysPerSphereBitForBit) {
    // nearest_hits() in a scene whose BVH is one leaf takes four rays at a time against each
    // sphere in world form (query_leaf_packet.cpp): every hit and every count must be what
    // nearest_hit() gives ray by ray — five spheres (two groups) with a tie, an ellipsoid and a
    // box (tested per ray), a plane; camera packets, random rays, rays from a sphere's surface
    // (its double path) and rays of zero or tiny direction (the packet goes ray by ray), packets
    // of every size 1–8 and a finite t_max.
    std::vector<ObjectDesc> objects = {sphere({0, 0, 0}, 1.5f, 1), sphere({0, 0, 0}, 1.5f, 2),
                                       sphere({2, 1, -1}, 0.8f, 0), sphere({-2, 2, 0}, 0.6f, 1),
                                       sphere({0, 3, -2}, 1.1f, 0)};
    ObjectDesc ellipsoid = sphere({-2, 1, 1}, 1.0f, 1);
    ellipsoid.transform = scaling({1.5f, 0.5f, 1.0f});  // not a similarity: object space
    objects.push_back(ellipsoid);
    objects.push_back(box({1, -3, 1}, {3, -1, 2}, 2));
    objects.push_back(plane({0, -4, 0}, 2));
    const BuiltScene scene = build_scene(scene_with(objects));
    ASSERT_NE(scene.root_leaf, 0u);
    ASSERT_EQ(sphere_lanes(scene), 5);

    std::vector<Ray> rays;
    for (const Vec3& eye : {Vec3{0, 0, 12}, Vec3{9, 4, -7}, Vec3{0.1f, -3.5f, 0}})
        for (const Ray& r : camera_rays(eye, {0, 0, 0}, 48, 32, 0.6f)) rays.push_back(r);
    RandomRays gen;
    for (int k = 0; k < 30000; ++k) {
        float t_max;
        Ray r = gen.next(k, t_max);
        if (k % 3 == 2) {  // from the first sphere's surface, on it or 1e-4 off it
            const float offset = (k & 8) ? 1e-4f : (k & 16) ? -1e-4f : 0.0f;
            r.origin = random_direction(gen.rng) * (1.5f + offset);
        }
        if (k % 97 == 5) r.direction = Vec3{0.0f};              // no direction at all
        if (k % 89 == 7) r.direction = r.direction * 0x1p-40f;  // |d|² below the pre-test's
        rays.push_back(r);
    }
    int hits = 0, slow = 0;
    for (const float t_max : {std::numeric_limits<float>::infinity(), 7.5f}) {
        for (int packet = 1; packet <= kMaxPacket; ++packet) {
            SCOPED_TRACE("packets of " + std::to_string(packet) + ", t_max " +
                         std::to_string(t_max));
            IntersectCounters by_packet, by_ray;
            int mismatches = 0;
            for (size_t first = 0; first < rays.size(); first += static_cast<size_t>(packet)) {
                const int n = static_cast<int>(std::min<size_t>(packet, rays.size() - first));
                Hit hs[kMaxPacket];
                bool found[kMaxPacket];
                nearest_hits(scene, &rays[first], n, 0.0f, t_max, hs, found, by_packet);
                for (int k = 0; k < n; ++k) {
                    Hit h;
                    const bool f = nearest_hit(scene, rays[first + k], 0.0f, t_max, h, by_ray);
                    const bool same =
                        f == found[k] && (!f || (std::memcmp(&h, &hs[k], sizeof h) == 0));
                    if (!same && ++mismatches <= 5) {
                        ADD_FAILURE() << "ray " << first + k << ": alone " << f << " t=" << h.t
                                      << " shape " << h.shape << "; packet " << found[k]
                                      << " t=" << hs[k].t << " shape " << hs[k].shape;
                    }
                    hits += f;
                }
            }
            EXPECT_EQ(mismatches, 0);
            EXPECT_EQ(by_packet.primitive, by_ray.primitive);
            EXPECT_EQ(by_packet.bounds, by_ray.bounds);
        }
    }
    for (const Ray& r : rays) slow += takes_double_path({0, 0, 0}, 1.5f, r);
    EXPECT_GT(hits, 100000);
    EXPECT_GT(slow, 1000);
}

}  // namespace
}  // namespace luz
