// The BVH against brute force: the same nearest hit (t, shape, triangle) and the same shadow
// answers for 100 000 random rays per scene, on random and degenerate meshes (zero-area
// triangles, every triangle in one plane, duplicated triangles) mixed with other shapes; and
// the structure of the tree itself; the scene's mesh and BVH memory.
#include "geometry/bvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <random>

#include "bvh_reference.h"
#include "geometry/prim_block.h"
#include "geometry/scene.h"
#include "geometry/scene_query.h"
#include "geometry_fixtures.h"
#include "math/lane_count.h"

namespace luz {
namespace {

using test::random_direction;
using test::random_point;
using test::Rng;
using test::uniform;

/// A mesh object from triangle vertex triples (vertices shared where the triples share them).
ObjectDesc mesh_object(const std::vector<Vec3>& positions, const std::vector<uint32_t>& index,
                       int material, bool smooth = false) {
    auto data = std::make_shared<MeshData>();
    data->file = "test.obj";
    data->positions = positions;
    data->position = index;
    data->normal.assign(index.size(), -1);
    data->material.assign(index.size() / 3, -1);
    ObjectDesc o;
    o.type = ShapeType::mesh;
    o.material = material;
    o.smooth = smooth;
    o.mesh = data;
    return o;
}

/// A triangle soup: n random triangles of random sizes in [−4, 4]³.
ObjectDesc random_soup(Rng& rng, int n, int material) {
    std::vector<Vec3> p;
    std::vector<uint32_t> idx;
    for (int t = 0; t < n; ++t) {
        const Vec3 c = random_point(rng, -4, 4);
        const float size = uniform(rng, 0.05f, 1.2f);
        for (int k = 0; k < 3; ++k) {
            idx.push_back(static_cast<uint32_t>(p.size()));
            p.push_back(c + random_point(rng, -size, size));
        }
    }
    return mesh_object(p, idx, material);
}

/// A grid of n×n quads in the plane z = z0 (shared vertices), as two triangles each.
ObjectDesc planar_grid(int n, float z0, int material) {
    std::vector<Vec3> p;
    std::vector<uint32_t> idx;
    const float s = 8.0f / n;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) p.push_back({-4 + i * s, -4 + j * s, z0});
    const auto at = [n](int i, int j) { return static_cast<uint32_t>(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            idx.insert(idx.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            idx.insert(idx.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    }
    return mesh_object(p, idx, material);
}

/// Degenerate triangles: zero-area ones (a repeated vertex, collinear vertices, a point),
/// and every triangle of `base` twice (the copy later in the index list, reversed).
ObjectDesc degenerate_mesh(Rng& rng, const ObjectDesc& base, int zero_area, int material) {
    std::vector<Vec3> p = base.mesh->positions;
    std::vector<uint32_t> idx = base.mesh->position;
    const size_t n = idx.size();
    for (size_t c = 0; c < n; c += 3) idx.insert(idx.end(), {idx[c], idx[c + 2], idx[c + 1]});
    for (int t = 0; t < zero_area; ++t) {
        const Vec3 a = random_point(rng, -4, 4), b = random_point(rng, -4, 4);
        const uint32_t i = static_cast<uint32_t>(p.size());
        switch (t % 3) {
            case 0:  // a repeated vertex
                p.insert(p.end(), {a, b});
                idx.insert(idx.end(), {i, i + 1, i});
                break;
            case 1:  // collinear
                p.insert(p.end(), {a, b, (a + b) * 0.5f});
                idx.insert(idx.end(), {i, i + 1, i + 2});
                break;
            default:  // one point
                p.push_back(a);
                idx.insert(idx.end(), {i, i, i});
                break;
        }
    }
    return mesh_object(p, idx, material);
}

/// Materials: 0 default (opaque), 1 glass (transparency 0.7), 2 water (0.35); not powers of
/// two, so that the order of multiplication would show in the products.
SceneDesc scene_with(std::vector<ObjectDesc> objects) {
    SceneDesc d;
    d.render.pipeline = Pipeline::raytrace;
    d.geometry.accel = Accel::bvh;
    d.materials.resize(3);
    d.materials[1].transparency = 0.7f;
    d.materials[2].transparency = 0.35f;
    for (size_t i = 0; i < objects.size(); ++i) objects[i].path = "objects." + std::to_string(i);
    d.objects = std::move(objects);
    return d;
}

ObjectDesc sphere(Vec3 c, float r, int material) {
    ObjectDesc o;
    o.type = ShapeType::sphere;
    o.center = c;
    o.radius = r;
    o.material = material;
    return o;
}

ObjectDesc box(Vec3 lo, Vec3 hi, int material) {
    ObjectDesc o;
    o.type = ShapeType::box;
    o.min = lo;
    o.max = hi;
    o.material = material;
    return o;
}

ObjectDesc plane(Vec3 point, int material) {
    ObjectDesc o;
    o.type = ShapeType::plane;
    o.point = point;
    o.material = material;
    return o;
}

/// Random rays: from points in [−6, 6]³ in random directions; every fourth aimed exactly at a
/// mesh vertex (where triangles meet and ties happen) and every eighth a segment (for shadows).
struct RandomRays {
    std::vector<Vec3> targets;
    Rng rng{12345};
    Ray next(int k, float& t_max) {
        Ray r{random_point(rng, -6, 6), random_direction(rng)};
        t_max = std::numeric_limits<float>::infinity();
        if (k % 4 == 0 && !targets.empty()) {
            const Vec3 to = targets[rng() % targets.size()] - r.origin;
            if (length(to) > 0) r.direction = normalize(to);
        }
        if (k % 8 == 1) t_max = uniform(rng, 0.5f, 12.0f);
        return r;
    }
};

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
    if (fewer_tests) EXPECT_LT(cb.primitive * 5, ca.primitive);
    ::testing::Test::RecordProperty("primitive_tests_bvh", std::to_string(cb.primitive));
    ::testing::Test::RecordProperty("primitive_tests_all", std::to_string(ca.primitive));
}

TEST(BvhEqualsBruteForce, RandomMeshesAndShapes) {
    Rng rng(1);
    std::vector<ObjectDesc> objects = {random_soup(rng, 300, 0), random_soup(rng, 150, 1),
                                       sphere({1, 1, 1}, 1.5f, 1), sphere({-2, 2, -1}, 0.7f, 0)};
    objects.push_back(box({2, -3, -3}, {3, -1, 0}, 2));
    objects.push_back(plane({0, -5, 0}, 2));
    expect_bvh_equals_brute_force(scene_with(objects), 100000);
}

/// Thin and thick cylinders and cones (capped or open, opaque or glass), sheared, mirrored and
/// scaled by the user transforms, among spheres: the cylinders are axis lanes (prim_block.h)
/// pre-tested four at a time.
std::vector<ObjectDesc> cylinder_field(Rng& rng) {
    std::vector<ObjectDesc> objects;
    const auto transforms = test::user_transforms();
    for (int i = 0; i < 300; ++i) {
        ObjectDesc o;
        o.type = i % 6 == 1 ? ShapeType::cone : ShapeType::cylinder;
        o.base = random_point(rng, -4, 4);
        o.axis = random_direction(rng);
        o.radius = i % 3 == 0 ? uniform(rng, 0.3f, 1.0f) : uniform(rng, 0.01f, 0.1f);
        o.height = i % 5 == 0 ? uniform(rng, 2.0f, 8.0f) : uniform(rng, 0.2f, 1.5f);
        o.caps = i % 2 == 0;
        o.material = i % 7 == 0 ? 1 : 0;
        if (i % 4 == 0) o.transform = transforms[i / 4 % transforms.size()].affine;
        objects.push_back(o);
    }
    for (int i = 0; i < 40; ++i)
        objects.push_back(sphere(random_point(rng, -4, 4), uniform(rng, 0.1f, 0.6f), i % 3));
    return objects;
}

TEST(BvhEqualsBruteForce, CylindersAmongSpheres) {
    Rng rng(3);
    expect_bvh_equals_brute_force(scene_with(cylinder_field(rng)), 100000, false);
}

// axis_lanes_missed() rejects a lane only when the exact test misses the whole line, and it
// rejects many lanes (rays through the cylinders' surfaces and
// just outside them included).
TEST(PrimBlock, AxisLanesMissedOnlyWhatTheExactTestMisses) {
    Rng rng(4);
    const BuiltScene scene = build_scene(scene_with(cylinder_field(rng)));
    ASSERT_EQ(scene.root_leaf, 0u);
    std::vector<std::pair<const PrimBlock*, int>> lanes;
    for (const PrimBlock& b : scene.bvh_blocks)
        for (unsigned a = b.axis_lanes(); a != 0; a &= a - 1)
            lanes.push_back({&b, __builtin_ctz(a)});
    ASSERT_EQ(lanes.size(), 300u);
    const float inf = std::numeric_limits<float>::infinity();
    int rejected = 0, tested = 0, grazing_hits = 0;
    for (int k = 0; k < 200000; ++k) {
        const auto [b, lane] = lanes[rng() % lanes.size()];
        const Shape& s = scene.shapes[b->shape[lane]];
        ASSERT_TRUE(s.type == ShapeType::cylinder || s.type == ShapeType::cone);
        // aimed at a point on (or just off) the side or a rim, or anywhere
        const float phi = uniform(rng, 0, 6.2831853f);
        float rho = k % 3 == 0 ? 1.0f : uniform(rng, 0.99f, 1.01f);
        float z = k % 5 == 0 ? 1.0f : uniform(rng, 0, 1);
        if (s.type == ShapeType::cone) {  // radius 1 − z
            z = k % 5 == 0 ? 0.0f : z;
            rho *= 1 - z;
        }
        const Vec3 target =
            s.transform.world_from_object.point({rho * std::cos(phi), rho * std::sin(phi), z});
        Ray r{random_point(rng, -6, 6), random_direction(rng)};
        if (k % 2 == 0) r.direction = (target - r.origin) * uniform(rng, 0.1f, 3.0f);
        const bool missed = (axis_lanes_missed(*b, 1u << lane, r) >> lane) & 1u;
        Hit h;
        const bool met = intersect(s, r, -inf, inf, h);
        ++tested;
        rejected += missed;
        grazing_hits += met && rho != 1.0f;
        if (missed) {
            ASSERT_FALSE(met) << "ray " << k << " lane " << lane;
        }
    }
    EXPECT_GT(rejected, tested / 3);
    EXPECT_GT(grazing_hits, 1000);
}

TEST(BvhEqualsBruteForce, AllTrianglesInOnePlane) {
    Rng rng(2);
    // a regular grid (shared edges and vertices), and random triangles lying in the same plane
    ObjectDesc soup = random_soup(rng, 200, 1);
    auto data = std::make_shared<MeshData>(*soup.mesh);
    for (Vec3& p : data->positions) p.z = 0.0f;
    soup.mesh = data;
    expect_bvh_equals_brute_force(scene_with({planar_grid(16, 0.0f, 0), soup}), 100000);
}

TEST(BvhEqualsBruteForce, ZeroAreaAndDuplicatedTriangles) {
    Rng rng(3);
    const ObjectDesc soup = random_soup(rng, 150, 0);
    const ObjectDesc grid = planar_grid(8, 1.0f, 1);
    // the same triangles twice in one mesh, and again as another object
    expect_bvh_equals_brute_force(
        scene_with({degenerate_mesh(rng, soup, 100, 0), degenerate_mesh(rng, grid, 60, 1), soup,
                    sphere({0, 0, 1}, 1.0f, 2)}),
        100000);
}

/// nearest_hits() of packets of `rays` must give each ray exactly what nearest_hit() gives it.
/// Returns the number of mismatches (the first few reported).
int packet_mismatches(const BuiltScene& scene, const std::vector<Ray>& rays,
                      const std::vector<float>& t_max, int packet) {
    int mismatches = 0;
    IntersectCounters c;
    for (size_t first = 0; first < rays.size(); first += static_cast<size_t>(packet)) {
        const int n = static_cast<int>(std::min<size_t>(packet, rays.size() - first));
        // a packet shares t_max: group rays of one t_max (the generator's are per packet)
        Hit hits[kMaxPacket];
        bool found[kMaxPacket];
        nearest_hits(scene, &rays[first], n, 0.0f, t_max[first], hits, found, c);
        for (int k = 0; k < n; ++k) {
            Hit h;
            const bool f = nearest_hit(scene, rays[first + k], 0.0f, t_max[first], h, c);
            const Hit& p = hits[k];
            const bool same =
                f == found[k] &&
                (!f || (std::memcmp(&h.t, &p.t, sizeof(float)) == 0 && h.shape == p.shape &&
                        h.part == p.part && std::memcmp(&h.u, &p.u, sizeof(float)) == 0 &&
                        std::memcmp(&h.v, &p.v, sizeof(float)) == 0));
            if (!same && ++mismatches <= 5) {
                ADD_FAILURE() << "packet at " << first << ", ray " << k << ": one by one " << f
                              << " t=" << h.t << " shape " << h.shape << " part " << h.part
                              << "; packet " << found[k] << " t=" << p.t << " shape " << p.shape
                              << " part " << p.part;
            }
        }
    }
    return mismatches;
}

/// Camera-like packets: rays from one eye through neighbouring points of a small square of
/// the view (8 in a row, as the renderer's tiles give them), over a w×h grid aimed at `at`.
std::vector<Ray> camera_rays(Vec3 eye, Vec3 at, int w, int h, float half) {
    const Vec3 f = normalize(at - eye);
    const Vec3 r = normalize(cross(f, Vec3{0, 1, 0})), u = cross(r, f);
    std::vector<Ray> rays;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            rays.push_back({eye, normalize(f + r * ((2.0f * (x + 0.5f) / w - 1) * half) +
                                           u * ((1 - 2.0f * (y + 0.5f) / h) * half))});
    return rays;
}

TEST(PacketQuery, EachRayGetsWhatItGetsAlone) {
    // A scene with meshes (random, degenerate, planar), spheres, a box and a plane in the BVH;
    // packets of camera rays (coherent, shared axes), random rays (incoherent, mixed axes, some
    // aimed at vertices where ties happen), of every size 1–8, with and without a finite t_max.
    Rng rng(11);
    const ObjectDesc soup = random_soup(rng, 300, 0);
    std::vector<ObjectDesc> objects = {soup, degenerate_mesh(rng, soup, 40, 1),
                                       planar_grid(12, -1.0f, 2), sphere({1, 1, 1}, 1.5f, 1),
                                       sphere({-2, 2, -1}, 0.7f, 0)};
    objects.push_back(box({2, -3, -3}, {3, -1, 0}, 2));
    objects.push_back(plane({0, -5, 0}, 2));
    const BuiltScene scene = build_scene(scene_with(objects));
    ASSERT_TRUE(scene.has_bvh);
    ASSERT_EQ(scene.root_leaf, 0u);

    std::vector<Ray> rays;
    std::vector<float> t_max;
    for (const Vec3& eye : {Vec3{0, 0, 12}, Vec3{9, 4, -7}, Vec3{-3, 11, 2}, Vec3{0.1f, -4, 0}}) {
        for (const Ray& r : camera_rays(eye, {0, 0, 0}, 64, 48, 0.6f)) {
            rays.push_back(r);
            t_max.push_back(std::numeric_limits<float>::infinity());
        }
    }
    const size_t coherent = rays.size();
    RandomRays gen;
    gen.targets = soup.mesh->positions;
    for (int k = 0; k < 40000; ++k) {
        float tm;
        rays.push_back(gen.next(k, tm));
        t_max.push_back(k % 16 < 8 ? std::numeric_limits<float>::infinity() : 7.5f);
    }
    // the finite t_max holds for whole packets of 8 (rays 8..15 of every 16)
    for (int packet = 1; packet <= kMaxPacket; ++packet) {
        SCOPED_TRACE("packets of " + std::to_string(packet));
        std::vector<Ray> r = rays;
        std::vector<float> tm = t_max;
        if (kMaxPacket % packet != 0) {  // keep t_max per packet: one value for the coherent rays
            r.resize(coherent);
            tm.resize(coherent);
        }
        EXPECT_EQ(packet_mismatches(scene, r, tm, packet), 0);
    }
    // the packets did take the packet path, and found hits
    int hits = 0;
    IntersectCounters c;
    for (size_t k = 0; k < coherent; ++k) {
        Hit h;
        hits += nearest_hit(scene, rays[k], 0.0f, t_max[k], h, c);
    }
    EXPECT_GT(hits, static_cast<int>(coherent) / 4);
}

TEST(PacketQuery, OneLeafScenesAndNoBvhAnswerRayByRay) {
    Rng rng(12);
    const BuiltScene small = build_scene(scene_with(
        {sphere({0, 0, 0}, 1.5f, 1), box({1, -3, 1}, {3, -1, 2}, 2), plane({0, -4, 0}, 2)}));
    ASSERT_NE(small.root_leaf, 0u);
    BuiltScene all = build_scene(scene_with({random_soup(rng, 100, 0), sphere({1, 1, 1}, 1, 0)}));
    all.geometry.accel = Accel::none;
    const std::vector<Ray> rays = camera_rays({0, 1, 9}, {0, 0, 0}, 32, 32, 0.7f);
    const std::vector<float> t_max(rays.size(), std::numeric_limits<float>::infinity());
    EXPECT_EQ(packet_mismatches(small, rays, t_max, 8), 0);
    EXPECT_EQ(packet_mismatches(all, rays, t_max, 5), 0);
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

// ---- the tree itself ------------------------------------------------------------------------

bool contains(const BvhNode& n, const Bounds3& b) {
    for (int a = 0; a < 3; ++a)
        if (b.lo[a] < n.lo[a] || b.hi[a] > n.hi[a]) return false;
    return true;
}

/// Checks every node: children inside parents, primitives inside their leaf, each primitive in
/// exactly one leaf; returns the depth.
int check_tree(const Bvh& bvh, const std::vector<Bounds3>& boxes, uint32_t node,
               std::vector<int>& seen) {
    const BvhNode& n = bvh.nodes()[node];
    if (n.leaf()) {
        for (uint32_t i = n.offset; i < n.offset + n.count; ++i) {
            const uint32_t id = bvh.order()[i];
            EXPECT_TRUE(contains(n, boxes[id]));
            ++seen[id];
        }
        return 1;
    }
    const uint32_t a = node + 1, b = n.offset;
    EXPECT_GT(b, a);
    Bounds3 ba, bb;
    for (int k = 0; k < 3; ++k) {
        ba.lo[k] = bvh.nodes()[a].lo[k];
        ba.hi[k] = bvh.nodes()[a].hi[k];
        bb.lo[k] = bvh.nodes()[b].lo[k];
        bb.hi[k] = bvh.nodes()[b].hi[k];
    }
    EXPECT_TRUE(contains(n, ba));
    EXPECT_TRUE(contains(n, bb));
    return 1 + std::max(check_tree(bvh, boxes, a, seen), check_tree(bvh, boxes, b, seen));
}

TEST(Bvh, EveryPrimitiveInOneLeafInsideEveryAncestor) {
    Rng rng(4);
    std::vector<Bounds3> boxes;
    for (int i = 0; i < 5000; ++i) {
        const Vec3 c = random_point(rng, -10, 10), e = random_point(rng, 0, 0.5f);
        boxes.push_back({c - e, c + e});
    }
    boxes.push_back(Bounds3{});  // empty: left out
    const Bvh bvh = Bvh::build(boxes);
    std::vector<int> seen(boxes.size(), 0);
    const int depth = check_tree(bvh, boxes, 0, seen);
    for (size_t i = 0; i + 1 < boxes.size(); ++i) EXPECT_EQ(seen[i], 1) << i;
    EXPECT_EQ(seen.back(), 0);
    EXPECT_EQ(bvh.order().size(), boxes.size() - 1);
    EXPECT_LT(depth, 40);
    // SAH leaves are small; nodes: at most 2n − 1
    EXPECT_LE(bvh.nodes().size(), 2 * bvh.order().size() - 1);
    for (const BvhNode& n : bvh.nodes()) {
        if (n.leaf()) {
            EXPECT_LE(n.count, BvhOptions{}.max_leaf_size);
        }
    }
    EXPECT_EQ(bvh.memory_bytes(),
              bvh.nodes().capacity() * sizeof(BvhNode) + bvh.order().capacity() * 4);
}

/// A bumpy sphere of n segments and n/2 rings (as scripts/make_big_mesh.py makes, smaller).
ObjectDesc bumpy_sphere(int n) {
    std::vector<Vec3> p;
    std::vector<uint32_t> idx;
    const int rings = n / 2;
    const float pi = 3.14159265f;
    const auto r = [](float th, float ph) {
        return 1 + 0.04f * std::sin(12 * th) * std::sin(15 * ph);
    };
    p.push_back({0, r(0, 0), 0});
    for (int j = 1; j < rings; ++j) {
        const float th = pi * j / rings;
        for (int i = 0; i < n; ++i) {
            const float ph = 2 * pi * i / n, rr = r(th, ph);
            p.push_back({rr * std::sin(th) * std::cos(ph), rr * std::cos(th),
                         rr * std::sin(th) * std::sin(ph)});
        }
    }
    p.push_back({0, -r(pi, 0), 0});
    const auto at = [n](int j, int i) { return static_cast<uint32_t>(1 + (j - 1) * n + i % n); };
    const uint32_t south = static_cast<uint32_t>(p.size() - 1);
    for (int i = 0; i < n; ++i) {
        idx.insert(idx.end(), {0u, at(1, i + 1), at(1, i)});
        idx.insert(idx.end(), {south, at(rings - 1, i), at(rings - 1, i + 1)});
        for (int j = 1; j + 1 < rings; ++j) {
            idx.insert(idx.end(), {at(j, i), at(j, i + 1), at(j + 1, i + 1)});
            idx.insert(idx.end(), {at(j, i), at(j + 1, i + 1), at(j + 1, i)});
        }
    }
    return mesh_object(p, idx, 0);
}

// The scene keeps its primitives in blocks of four, leaf by leaf, and not the order itself: a
// mesh and its BVH (nodes and blocks with the vertices) take under 100 bytes per triangle.
TEST(Bvh, SceneMeshAndBvhUnder100BytesPerTriangle) {
    for (int n : {64, 180}) {
        const BuiltScene scene = build_scene(scene_with({bumpy_sphere(n)}));
        ASSERT_TRUE(scene.has_bvh);
        EXPECT_TRUE(scene.bvh.order().empty());
        const Mesh& m = *scene.shapes[0].mesh;
        const size_t triangles = m.triangle_count();
        EXPECT_GE(scene.bvh_blocks.size() * PrimBlock::kLanes, triangles);
        EXPECT_EQ(scene.bvh_bytes(), scene.bvh.nodes().capacity() * sizeof(Bvh8::Node) +
                                         scene.bvh_blocks.capacity() * sizeof(PrimBlock));
        const size_t bytes = scene.bvh_bytes() + m.positions.capacity() * sizeof(Vec3) +
                             m.indices.capacity() * sizeof(uint32_t);
        EXPECT_LT(static_cast<double>(bytes) / static_cast<double>(triangles), 100.0) << n;
    }
}

// Each leaf of the scene's BVH starts a block and holds at most two; every triangle and shape
// is in exactly one leaf lane, with its own vertices; the lanes after a leaf's end are padding
// (no shape, NaN vertices), and no block is shared by two leaves.
TEST(Bvh, SceneLeavesStartBlocksAndHoldEachPrimitiveOnce) {
    Rng rng(7);
    const ObjectDesc soup = random_soup(rng, 2000, 0);
    const BuiltScene scene =
        build_scene(scene_with({soup, sphere({0, 0, 0}, 0.5f, 0), bumpy_sphere(40),
                                sphere({1, 1, 1}, 0.5f, 1), box({2, 2, 2}, {3, 3, 3}, 0)}));
    ASSERT_TRUE(scene.has_bvh);
    ASSERT_EQ(scene.root_leaf, 0u);
    std::vector<std::vector<int>> seen(scene.shapes.size());
    for (size_t i = 0; i < scene.shapes.size(); ++i) {
        const auto& mesh = scene.shapes[i].mesh;
        seen[i].assign(mesh ? mesh->triangle_count() : 1, 0);
    }
    std::vector<int> block_used(scene.bvh_blocks.size(), 0);
    for (const Bvh8::Node& node : scene.bvh.nodes()) {
        for (int k = 0; k < 8; ++k) {
            const uint32_t first = node.child[k], count = node.count[k];
            if (count == 0) continue;
            ASSERT_EQ(first % PrimBlock::kLanes, 0u);
            ASSERT_LE(count, 8u);
            const uint32_t blocks = (count + 3) / 4;
            ASSERT_LE(first / 4 + blocks, scene.bvh_blocks.size());
            for (uint32_t b = first / 4; b < first / 4 + blocks; ++b) ++block_used[b];
            for (uint32_t slot = first; slot < first + count; ++slot) {
                const BvhPrim p = scene.bvh_prim(slot);
                ASSERT_LT(p.shape, scene.shapes.size());
                const auto& mesh = scene.shapes[p.shape].mesh;
                if (p.triangle == BvhPrim::kNotTriangle) {
                    EXPECT_FALSE(mesh);
                    ++seen[p.shape][0];
                    // a world-form sphere is a sphere lane (tested four at a time), by its
                    // centre, radius² and radius; other shapes are tested one by one
                    const Shape& s = scene.shapes[p.shape];
                    const PrimBlock& b = scene.bvh_blocks[slot / 4];
                    const int k = static_cast<int>(slot % 4);
                    const bool sphere_lane = (b.sphere_lanes() >> k) & 1u;
                    EXPECT_EQ(sphere_lane, s.world_form && s.type == ShapeType::sphere) << slot;
                    EXPECT_FALSE((b.triangle_lanes() >> k) & 1u);
                    if (sphere_lane) {
                        EXPECT_TRUE(b.corner(0, k) == s.centre);
                        EXPECT_EQ(b.v[1][0][k], s.radius * s.radius);
                        EXPECT_EQ(b.v[1][1][k], s.radius);
                    }
                    continue;
                }
                ASSERT_TRUE(mesh);
                ASSERT_LT(p.triangle, mesh->triangle_count());
                ++seen[p.shape][p.triangle];
                Vec3 p0, p1, p2;
                mesh->vertices(p.triangle, p0, p1, p2);
                EXPECT_TRUE(p.p0 == p0 && p.p1 == p1 && p.p2 == p2) << slot;
            }
            for (uint32_t slot = first + count; slot < first + 4 * blocks; ++slot) {
                const PrimBlock& b = scene.bvh_blocks[slot / 4];
                EXPECT_EQ(b.shape[slot % 4], PrimBlock::kPadding);
                EXPECT_FALSE((b.triangle_lanes() >> (slot % 4)) & 1u);
                EXPECT_TRUE(std::isnan(b.v[0][0][slot % 4]));
            }
        }
    }
    for (int used : block_used) EXPECT_EQ(used, 1);
    for (size_t i = 0; i < seen.size(); ++i)
        for (size_t t = 0; t < seen[i].size(); ++t) EXPECT_EQ(seen[i][t], 1) << i << " " << t;
}

// Counting primitives in blocks (leaf_block) changes only the costs: leaf_block 1 is the plain
// SAH tree; blocks of four give leaves that fill their blocks better.
TEST(Bvh, SahCountingBlocks) {
    Rng rng(3);
    std::vector<Bounds3> boxes;
    for (int i = 0; i < 5000; ++i) {
        const Vec3 c = random_point(rng, -10, 10);
        boxes.push_back(Bounds3{c - Vec3{0.1f}, c + Vec3{0.1f}});
    }
    BvhOptions one;
    one.leaf_block = 1;
    const Bvh plain = Bvh::build(boxes), same = Bvh::build(boxes, one);
    ASSERT_EQ(plain.nodes().size(), same.nodes().size());
    EXPECT_EQ(0, std::memcmp(plain.nodes().data(), same.nodes().data(),
                             plain.nodes().size() * sizeof(BvhNode)));
    EXPECT_EQ(plain.order(), same.order());
    BvhOptions four;
    four.leaf_block = 4;
    four.traversal_cost = 0.7f;
    const Bvh blocked = Bvh::build(boxes, four);
    const auto fill = [](const Bvh& bvh) {
        double prims = 0, blocks = 0;
        for (const BvhNode& n : bvh.nodes()) {
            if (!n.leaf()) continue;
            EXPECT_LE(n.count, 8u);
            prims += n.count;
            blocks += (n.count + 3) / 4;
        }
        return prims / (4 * blocks);
    };
    EXPECT_EQ(blocked.order().size(), boxes.size());
    EXPECT_GT(fill(blocked), fill(plain) + 0.2) << fill(blocked) << " vs " << fill(plain);
}

TEST(Bvh, EmptyAndCoincidentInputs) {
    EXPECT_TRUE(Bvh::build({}).empty());
    const std::vector<Bounds3> same(1000, Bounds3{{0, 0, 0}, {1, 1, 1}});
    const BinaryBvh one = BinaryBvh::build(same);  // nothing to split: a single leaf
    ASSERT_EQ(one.nodes().size(), 1u);
    EXPECT_EQ(one.nodes()[0].count, 1000u);
    uint64_t tests = 0;
    int visited = 0;
    float t_max = 100;
    one.nearest({{0.5f, 0.5f, -1}, {0, 0, 1}}, 0.0f, t_max, tests,
                [&](uint32_t, float&) { ++visited; });
    EXPECT_EQ(visited, 1000);
    EXPECT_EQ(tests, 1u);
}

TEST(Bvh, DeepChainsStayWithinTheTraversalStack) {
    // boxes of doubling sizes around one point: SAH would peel one at a time
    std::vector<Bounds3> boxes;
    for (int i = 0; i < 120; ++i) {
        const float s = std::ldexp(1.0f, i - 60);
        boxes.push_back({Vec3{s}, Vec3{s * 1.5f}});
    }
    const Bvh bvh = Bvh::build(boxes);
    std::vector<int> seen(boxes.size(), 0);
    EXPECT_LT(check_tree(bvh, boxes, 0, seen), Bvh::kMaxDepth);
}

TEST(Bvh, NearestVisitsNearChildrenFirstAndSkipsWhatLiesBeyond) {
    // a row of unit boxes along x; a ray along +x hits box 0 first and stops there
    std::vector<Bounds3> boxes;
    for (int i = 0; i < 64; ++i) boxes.push_back({{2.0f * i, 0, 0}, {2.0f * i + 1, 1, 1}});
    const BinaryBvh bvh = BinaryBvh::build(boxes);
    uint64_t tests = 0;
    std::vector<uint32_t> order;
    float t_max = std::numeric_limits<float>::infinity();
    bvh.nearest({{-1, 0.5f, 0.5f}, {1, 0, 0}}, 0.0f, t_max, tests, [&](uint32_t slot, float& t) {
        const uint32_t id = bvh.order()[slot];
        order.push_back(id);
        t = std::min(t, 2.0f * id + 1);  // the entry distance of box id
    });
    ASSERT_FALSE(order.empty());
    EXPECT_EQ(order.front(), 0u);
    EXPECT_LE(order.size(), 8u);  // one leaf or so, not all 64
    // the same ray the other way round starts from the last box
    order.clear();
    t_max = std::numeric_limits<float>::infinity();
    bvh.nearest({{200, 0.5f, 0.5f}, {-1, 0, 0}}, 0.0f, t_max, tests, [&](uint32_t slot, float& t) {
        const uint32_t id = bvh.order()[slot];
        order.push_back(id);
        t = std::min(t, 200.0f - (2.0f * id + 1));
    });
    ASSERT_FALSE(order.empty());
    EXPECT_EQ(*std::max_element(order.begin(), order.end()), 63u);
    EXPECT_LE(order.size(), 8u);
    // any() stops when told to
    int visits = 0;
    EXPECT_TRUE(bvh.any({{-1, 0.5f, 0.5f}, {1, 0, 0}}, 0.0f, 1000.0f, tests,
                        [&](uint32_t) { return ++visits == 3; }));
    EXPECT_EQ(visits, 3);
    EXPECT_FALSE(
        bvh.any({{-1, 5, 0.5f}, {1, 0, 0}}, 0.0f, 1000.0f, tests, [&](uint32_t) { return true; }));
}

}  // namespace
}  // namespace luz
