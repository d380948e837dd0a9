// nearest_hits() on packets of rays against nearest_hit() ray by ray, in scenes with a BVH,
// with one leaf and with no BVH: every ray gets exactly what it gets alone.
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
using test::degenerate_mesh;
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

}  // namespace
}  // namespace luz
