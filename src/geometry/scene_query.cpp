// BuiltScene ray queries: the choice of strategy (query_bvh.cpp with query_packet.cpp and
// query_leaf_packet.cpp, or query_all.cpp), of their kernels' instruction set (query_isa.h) and
// the time spent in them; the slab test of a box.
#include "geometry/scene_query.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <utility>

#include "geometry/query_isa.h"
#include "geometry/query_parts.h"

namespace luz {

#if defined(LUZ_QUERY_AVX2)
bool query::avx2::active() {
    static const bool on = [] {
        const char* isa = std::getenv("LUZ_ISA");
        if (isa != nullptr && std::strcmp(isa, "baseline") == 0) return false;
        __builtin_cpu_init();
        return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    }();
    return on;
}
#else
bool query::avx2::active() { return false; }
#endif

namespace {

bool use_bvh(const BuiltScene& scene) {
    return scene.has_bvh && scene.geometry.accel == Accel::bvh;
}

/// Runs f(), adding its duration to counters.query_ns when counters.timing is set.
template <class F>
auto timed(IntersectCounters& counters, F&& f) {
    if (!counters.timing) return f();
    const auto start = std::chrono::steady_clock::now();
    const auto result = f();
    counters.query_ns += static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                                   std::chrono::steady_clock::now() - start)
                                                   .count());
    return result;
}

// The BVH strategy's kernel `name` called with the arguments that follow, in the instruction set
// of query::avx2::active() (query_isa.h): two direct calls behind one branch.
#if defined(LUZ_QUERY_AVX2)
#define LUZ_KERNEL(name, ...) \
    (query::avx2::active() ? query::avx2::name(__VA_ARGS__) : query::name(__VA_ARGS__))
#else
#define LUZ_KERNEL(name, ...) query::name(__VA_ARGS__)
#endif

}  // namespace

bool nearest_hit(const BuiltScene& scene, const Ray& r, float t_min, float t_max, Hit& hit,
                 IntersectCounters& counters) {
    return timed(counters, [&] {
        if (use_bvh(scene))
            return LUZ_KERNEL(nearest_hit_bvh, scene, r, t_min, t_max, hit, counters);
        return query::nearest_hit_all(scene, r, t_min, t_max, hit, counters);
    });
}

void nearest_hits(const BuiltScene& scene, const Ray* rays, int n, float t_min, float t_max,
                  Hit* hits, bool* found, IntersectCounters& counters) {
    timed(counters, [&] {
        if (use_bvh(scene)) {
            ++counters.nearest_packets;
            LUZ_KERNEL(nearest_hits_bvh, scene, rays, n, t_min, t_max, hits, found, counters);
        } else {
            for (int k = 0; k < n; ++k)
                found[k] = query::nearest_hit_all(scene, rays[k], t_min, t_max, hits[k], counters);
        }
        return true;
    });
}

void nearest_hits_scattered(const BuiltScene& scene, const Ray* rays, int n, float t_min,
                            float t_max, Hit* hits, bool* found, IntersectCounters& counters) {
    if (use_bvh(scene) && scene.root_leaf != 0) {  // no traversal to diverge: side by side
        nearest_hits(scene, rays, n, t_min, t_max, hits, found, counters);
        return;
    }
    for (int k = 0; k < n; ++k)
        found[k] = nearest_hit(scene, rays[k], t_min, t_max, hits[k], counters);
}

float transmittance(const BuiltScene& scene, const Materials& materials, const Ray& r, float t_min,
                    float t_max, IntersectCounters& counters) {
    return timed(counters, [&] {
        if (use_bvh(scene))
            return LUZ_KERNEL(transmittance_bvh, scene, materials, r, t_min, t_max, counters,
                              nullptr);
        return query::transmittance_all(scene, materials, r, t_min, t_max, counters);
    });
}

void transmittances(const BuiltScene& scene, const Materials& materials, const SegmentLanes& s,
                    unsigned active, float* T, IntersectCounters& counters, ShadowCache* cache,
                    bool coherent) {
    if (use_bvh(scene) && scene.root_leaf != 0 && !counters.timing) {
        LUZ_KERNEL(transmittances_leaf, scene, materials, 0, scene.root_leaf, s, active, T,
                   counters);
        return;
    }
    if (use_bvh(scene) && scene.root_leaf == 0) {
        ShadowCache own;  // the segments of this call alone
        ShadowCache& c = cache ? *cache : own;
        // Coherent segments go down together while lit points come in a run (the cache empty:
        // the last segments went unblocked); behind an occluder, its cached block first.
        if (coherent && c.lanes == 0) {
            ++counters.shadow_packets;
            timed(counters, [&] {
                LUZ_KERNEL(transmittances_bvh, scene, materials, s, active, T, counters, c);
                return true;
            });
            return;
        }
        for (; active != 0; active &= active - 1) {
            const int k = __builtin_ctz(active);
            T[k] = timed(counters, [&] {
                return LUZ_KERNEL(transmittance_bvh, scene, materials, s.ray(k), 0.0f, s.t_max[k],
                                  counters, &c);
            });
        }
        return;
    }
    for (; active != 0; active &= active - 1) {
        const int k = __builtin_ctz(active);
        T[k] = transmittance(scene, materials, s.ray(k), 0.0f, s.t_max[k], counters);
    }
}

}  // namespace luz
