// The scene queries' AVX2 kernels (geometry/query_isa.h) against the portable ones, called side
// by side in one process: nearest hits (one ray and packets), transmittances (with and without
// the shadow cache, and a one-leaf scene's four-segment path) bit for bit, on a crowded scene of
// every bounded shape kind, a mesh, transparent materials and a plane. Skipped where the build
// has no such kernels (-march=native, another CPU family) or the CPU lacks AVX2 or FMA.
#include "geometry/query_isa.h"

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "bvh_fixtures.h"
#include "geometry/query_parts.h"
#include "geometry/scene.h"
#include "geometry_fixtures.h"

namespace luz {
namespace {

using test::random_direction;
using test::random_point;
using test::Rng;
using test::uniform;

#if defined(LUZ_QUERY_AVX2)
bool cpu_has_avx2() {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
}
#endif

[[maybe_unused]] bool same_hit(bool f1, const Hit& a, bool f2, const Hit& b) {
    return f1 == f2 && (!f1 || (std::memcmp(&a.t, &b.t, sizeof(float)) == 0 && a.shape == b.shape &&
                                a.part == b.part && std::memcmp(&a.u, &b.u, sizeof(float)) == 0 &&
                                std::memcmp(&a.v, &b.v, sizeof(float)) == 0));
}

TEST(QueryIsa, Avx2KernelsGiveThePortableKernelsBits) {
#if !defined(LUZ_QUERY_AVX2)
    GTEST_SKIP() << "this build has no AVX2 kernels (-march=native or not x86-64)";
#else
    if (!cpu_has_avx2()) GTEST_SKIP() << "this CPU has no AVX2 and FMA";
    for (const int n : {5, 500}) {  // one leaf (root_leaf) and a deep BVH
        Rng rng{static_cast<uint32_t>(4242 + n)};
        const SceneDesc desc = test::crowded_scene(rng, n, n > 10 ? 200 : 0);
        const BuiltScene scene = build_scene(desc);
        ASSERT_EQ(scene.root_leaf != 0, n == 5);
        IntersectCounters c1, c2;
        int hits = 0, mismatches = 0, partial = 0;
        ShadowCache cache1, cache2;
        for (int i = 0; i < 20000; ++i) {
            // eight rays from near one point (a packet), scattered now and then
            const Vec3 o = random_point(rng, -9, 9);
            const float spread = i % 5 == 0 ? 1.0f : 0.01f;
            const Vec3 d0 = random_direction(rng);
            Ray rays[kMaxPacket];
            for (int k = 0; k < kMaxPacket; ++k)
                rays[k] = {o, normalize(d0 + random_point(rng, -spread, spread))};
            const float t_max = i % 3 == 0 ? uniform(rng, 1.0f, 10.0f) : 1e30f;
            Hit h1[kMaxPacket], h2[kMaxPacket];
            bool f1[kMaxPacket], f2[kMaxPacket];
            query::nearest_hits_bvh(scene, rays, kMaxPacket, 0.0f, t_max, h1, f1, c1);
            query::avx2::nearest_hits_bvh(scene, rays, kMaxPacket, 0.0f, t_max, h2, f2, c2);
            for (int k = 0; k < kMaxPacket; ++k)
                if (!same_hit(f1[k], h1[k], f2[k], h2[k]) && ++mismatches <= 5)
                    ADD_FAILURE() << "packet " << i << " ray " << k << ": t " << h1[k].t << " / "
                                  << h2[k].t << ", shape " << h1[k].shape << " / " << h2[k].shape;
            Hit a, b;
            const bool fa = query::nearest_hit_bvh(scene, rays[0], 1e-4f, t_max, a, c1);
            const bool fb = query::avx2::nearest_hit_bvh(scene, rays[0], 1e-4f, t_max, b, c2);
            hits += fa;
            if (!same_hit(fa, a, fb, b) && ++mismatches <= 5)
                ADD_FAILURE() << "ray " << i << ": t " << a.t << " / " << b.t;
            // shadow segments: one by one with each side's cache, then four at a time
            const float T1 = query::transmittance_bvh(scene, desc.materials, rays[1], 0.0f, t_max,
                                                      c1, i % 2 ? &cache1 : nullptr);
            const float T2 = query::avx2::transmittance_bvh(scene, desc.materials, rays[1], 0.0f,
                                                            t_max, c2, i % 2 ? &cache2 : nullptr);
            partial += T1 > 0 && T1 < 1;
            if (std::memcmp(&T1, &T2, sizeof(float)) != 0 && ++mismatches <= 5)
                ADD_FAILURE() << "segment " << i << ": " << T1 << " / " << T2;
            if (scene.root_leaf != 0) {
                SegmentLanes s;
                for (int k = 0; k < kMaxPacket; ++k) {
                    s.ox[k] = rays[k].origin.x, s.oy[k] = rays[k].origin.y;
                    s.oz[k] = rays[k].origin.z;
                    s.dx[k] = rays[k].direction.x, s.dy[k] = rays[k].direction.y;
                    s.dz[k] = rays[k].direction.z;
                    s.t_max[k] = uniform(rng, 0.5f, 20.0f);
                }
                float Ta[kMaxPacket], Tb[kMaxPacket];
                query::transmittances_leaf(scene, desc.materials, 0, scene.root_leaf, s, 0xFFu, Ta,
                                           c1);
                query::avx2::transmittances_leaf(scene, desc.materials, 0, scene.root_leaf, s,
                                                 0xFFu, Tb, c2);
                if (std::memcmp(Ta, Tb, sizeof Ta) != 0 && ++mismatches <= 5)
                    ADD_FAILURE() << "segments " << i << " (one leaf)";
            }
        }
        EXPECT_EQ(mismatches, 0) << n << " shapes";
        EXPECT_GT(hits, 2000) << "rays that hit something";
        EXPECT_GT(partial, 200) << "segments through glass only";
    }
#endif
}

}  // namespace
}  // namespace luz
