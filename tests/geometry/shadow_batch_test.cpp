// Shadow segments down a BVH deeper than one leaf (transmittances() with a ShadowCache, one by one
// or as a packet): every transmittance bit for bit what transmittance() gives segment by segment,
// whatever the cache holds — opaque and transparent occluders, blocks mixing both, a light's
// cache shared by calls.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "bvh_fixtures.h"
#include "geometry/scene.h"
#include "geometry/scene_query.h"
#include "geometry_fixtures.h"

namespace luz {
namespace {

using test::random_point;
using test::Rng;
using test::scene_with;
using test::sphere;

/// Eight shadow segments as the ray tracer makes them: from points near `centre` (coherent,
/// neighbouring pixels) or anywhere (scattered) towards the light at `light`.
SegmentLanes towards(Rng& rng, const Vec3& light, const Vec3& centre, float spread) {
    SegmentLanes s;
    for (int k = 0; k < kMaxPacket; ++k) {
        const Vec3 p = centre + random_point(rng, -spread, spread);
        const Vec3 to = light - p;
        const float d = length(to);
        const Vec3 L = to / d;
        s.ox[k] = p.x;
        s.oy[k] = p.y;
        s.oz[k] = p.z;
        s.dx[k] = L.x;
        s.dy[k] = L.y;
        s.dz[k] = L.z;
        s.t_max[k] = d;
    }
    return s;
}

TEST(ShadowBatch, SegmentsWithTheLastOccluderFirstGiveTransmittanceBitForBit) {
    Rng rng{2718};
    const SceneDesc desc = test::crowded_scene(rng, 400, 300);
    const BuiltScene scene = build_scene(desc);
    ASSERT_EQ(scene.root_leaf, 0u) << "a BVH of several leaves";
    const std::vector<Vec3> lights = {{0, 0, 0}, {9, 8, 7}, {-3, 20, 2}};
    std::vector<ShadowCache> caches(lights.size());  // one per light, kept from call to call
    IntersectCounters batched, one_by_one;
    int mismatches = 0, partial = 0, blocked = 0, open = 0, packets = 0;
    for (int call = 0; call < 6000; ++call) {
        const size_t j = static_cast<size_t>(call) % lights.size();
        // runs of neighbouring points, now and then a scattered packet or another light's cache
        const Vec3 centre = random_point(rng, -6, 6);
        const float spread = call % 11 == 5 ? 6.0f : call % 3 == 0 ? 0.05f : 0.4f;
        const SegmentLanes s = towards(rng, lights[j], centre, spread);
        const unsigned active = call % 7 == 3 ? (call * 37u) & 0xFFu : 0xFFu;
        ShadowCache* cache = call % 13 == 6   ? &caches[(j + 1) % lights.size()]
                             : call % 17 == 8 ? nullptr
                                              : &caches[j];
        // as the ray tracer says: the shadow rays of camera hits are coherent (a packet goes
        // down the BVH together while the cache is empty), the others are not
        const bool coherent = call % 4 != 1;
        packets += coherent && (cache == nullptr || cache->lanes == 0);
        float T[kMaxPacket];
        transmittances(scene, desc.materials, s, active, T, batched, cache, coherent);
        for (int k = 0; k < kMaxPacket; ++k) {
            if (!(active >> k & 1u)) continue;
            const float expected =
                transmittance(scene, desc.materials, s.ray(k), 0.0f, s.t_max[k], one_by_one);
            if (std::memcmp(&expected, &T[k], sizeof(float)) != 0 && ++mismatches <= 5) {
                ADD_FAILURE() << "call " << call << " lane " << k << ": " << T[k]
                              << " vs transmittance() " << expected;
            }
            partial += expected > 0 && expected < 1;
            blocked += expected == 0;
            open += expected == 1;
        }
    }
    EXPECT_EQ(mismatches, 0);
    EXPECT_GT(partial, 3000) << "segments through glass only";
    EXPECT_GT(blocked, 3000);
    EXPECT_GT(open, 3000);
    EXPECT_GT(packets, 1000) << "calls down the BVH as one packet";
    // The cache spares traversals: fewer box tests than segment by segment.
    EXPECT_LT(batched.bounds, one_by_one.bounds);
}

TEST(ShadowBatch, ACachedBlockOfGlassAndStoneCountsItsGlassOnce) {
    // Two spheres in one leaf on the segments' line: glass (0.7) nearer the light, stone behind
    // the points. The cache holds the leaf's block after a segment the stone blocked; segments
    // that pass the stone but cross the glass must still count the glass once (0.7² for its two
    // crossings), not again for the cached block's test.
    std::vector<ObjectDesc> objects = {sphere({0, 0, 5}, 1.0f, 1), sphere({0, 0, -5}, 1.0f, 0)};
    Rng rng{99};
    for (int i = 0; i < 60; ++i)  // far away: a BVH of several leaves
        objects.push_back(sphere(random_point(rng, 40, 60), 0.5f, 0));
    const SceneDesc desc = scene_with(objects);
    const BuiltScene scene = build_scene(desc);
    ASSERT_EQ(scene.root_leaf, 0u);
    const Vec3 light{0, 0, 10};
    ShadowCache cache;
    IntersectCounters counters;
    const auto segment_from = [&](float z) {
        SegmentLanes s;
        for (int k = 0; k < kMaxPacket; ++k) {
            s.ox[k] = 0.01f * static_cast<float>(k);
            s.oy[k] = 0.0f;
            s.oz[k] = z;
            const Vec3 to = light - Vec3{s.ox[k], 0.0f, z};
            const float d = length(to);
            s.dx[k] = to.x / d;
            s.dy[k] = to.y / d;
            s.dz[k] = to.z / d;
            s.t_max[k] = d;
        }
        return s;
    };
    float T[kMaxPacket];
    transmittances(scene, desc.materials, segment_from(-8.0f), 0xFFu, T, counters, &cache);
    for (int k = 0; k < kMaxPacket; ++k) EXPECT_EQ(T[k], 0.0f);
    ASSERT_NE(cache.lanes, 0u) << "the stone's block cached";
    transmittances(scene, desc.materials, segment_from(0.0f), 0xFFu, T, counters, &cache);
    const float glass = transmittance(scene, desc.materials, segment_from(0.0f).ray(0), 0.0f,
                                      segment_from(0.0f).t_max[0], counters);
    EXPECT_EQ(glass, 0.7f * 0.7f);
    for (int k = 0; k < kMaxPacket; ++k) EXPECT_EQ(T[k], glass) << k;
}

// A ground quad with spheres standing on it, as tree.nff's ground and tree: mesh triangles and
// other shapes keep leaves of their own, so the ground's leaf has a flat box, which segments
// leaving the ground (lifted off it, as the ray tracer lifts them) miss. They reach the light
// with no primitive test, one by one and as packets; sharing a leaf with a sphere, the ground
// cost every one of them a test of its triangles and of the sphere (issue 39).
TEST(ShadowBatch, SegmentsLeavingAGroundQuadTestNothingThere) {
    std::vector<ObjectDesc> objects = {test::mesh_object(
        {{-50, -50, 0}, {50, -50, 0}, {50, 50, 0}, {-50, 50, 0}}, {0, 1, 2, 0, 2, 3}, 0)};
    Rng rng{4};
    for (int i = 0; i < 40; ++i) {  // near its centre, some sunk into it to their centres
        const float r = 0.05f + 0.3f * static_cast<float>(i % 5) / 4.0f;
        const Vec3 c = random_point(rng, -1, 1);
        objects.push_back(sphere({c.x, c.y, (r + 1.0f) * static_cast<float>(i % 3)}, r, 0));
    }
    const SceneDesc desc = scene_with(objects);
    const BuiltScene scene = build_scene(desc);
    ASSERT_EQ(scene.root_leaf, 0u);
    const Vec3 light{0, 0, 100};
    IntersectCounters counters;
    for (int call = 0; call < 200; ++call) {
        const Vec3 centre = random_point(rng, 10, 40) * Vec3{call % 2 ? 1.0f : -1.0f, 1, 0};
        SegmentLanes s = towards(rng, light, centre, 0.5f);
        for (int k = 0; k < kMaxPacket; ++k) {  // on the ground, lifted by kRayEpsilon
            s.oz[k] = 1e-4f;
            s.t_max[k] = length(light - s.ray(k).origin);
            const Vec3 L = (light - s.ray(k).origin) / s.t_max[k];
            s.dx[k] = L.x, s.dy[k] = L.y, s.dz[k] = L.z;
        }
        float T[kMaxPacket];
        ShadowCache cache;
        transmittances(scene, desc.materials, s, 0xFFu, T, counters, &cache, true);
        for (int k = 0; k < kMaxPacket; ++k) {
            EXPECT_EQ(T[k], 1.0f);
            EXPECT_EQ(transmittance(scene, desc.materials, s.ray(k), 0.0f, s.t_max[k], counters),
                      1.0f);
        }
    }
    EXPECT_GT(counters.shadow_packets, 0u);
    EXPECT_EQ(counters.primitive, 0u);
}

}  // namespace
}  // namespace luz
