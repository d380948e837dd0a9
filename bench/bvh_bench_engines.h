// A part of bench/bvh_vs_embree.cpp (included by it alone): the structures it compares —
// luz's Bvh8 and binary Bvh, luz's scene query, Embree 3 (one ray, packets) — traced in
// parallel chunks, and the comparison of their hits.
#pragma once

#include <embree3/rtcore.h>
#include <sys/resource.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include "bvh_bench_rays.h"
#include "bvh_reference.h"  // tests/geometry: the binary Bvh's traversal

namespace luz::bvh_bench {

// ---------------------------------------------------------------------------------------------
// Tracing in parallel

constexpr size_t kChunk = 4096;  // rays per chunk; chunks are handed out in order

/// Calls trace(first, end) over all chunks of [0, count) on `threads` threads.
inline void parallel_chunks(size_t count, int threads,
                            const std::function<void(size_t, size_t)>& trace) {
    std::atomic<size_t> next{0};
    const auto work = [&] {
        for (;;) {
            const size_t begin = next.fetch_add(kChunk);
            if (begin >= count) return;
            trace(begin, std::min(count, begin + kChunk));
        }
    };
    std::vector<std::thread> pool;
    for (int i = 1; i < threads; ++i) pool.emplace_back(work);
    work();
    for (auto& t : pool) t.join();
}

/// luz: a BVH (Bvh, binary, or Bvh8, 8-wide) over the mesh's triangle boxes; a leaf slot's
/// triangle is order()[slot], its vertices come through the mesh's index array (the
/// standalone use of bvh.h).
template <class B>
struct LuzAccel {
    const Mesh* mesh = nullptr;
    B bvh;

    Result trace(const Ray& r, uint64_t& box_tests, uint64_t& tri_tests) const {
        const WatertightRay w = prepare_watertight(r);
        const uint32_t* order = bvh.order().data();
        const uint32_t* index = mesh->indices.data();
        const Vec3* p = mesh->positions.data();
        Result res;
        bvh.nearest(r, 0.0f, res.t, box_tests, [&](uint32_t slot, float& t_max) {
            const uint32_t tri = order[slot];
            const uint32_t* i = index + 3 * tri;
            float t, b1, b2;
            ++tri_tests;
            if (intersect_triangle(w, p[i[0]], p[i[1]], p[i[2]], 0.0f, t_max, t, b1, b2)) {
                t_max = t;
                res.prim = tri;
            }
        });
        return res;
    }
    void trace(const std::vector<Ray>& rays, std::vector<Result>& out, int threads) const {
        parallel_chunks(rays.size(), threads, [&](size_t begin, size_t end) {
            uint64_t boxes = 0, tris = 0;
            for (size_t k = begin; k < end; ++k) out[k] = trace(rays[k], boxes, tris);
        });
    }
    size_t bytes() const {
        return mesh->positions.capacity() * sizeof(Vec3) +
               mesh->indices.capacity() * sizeof(uint32_t) + bvh.memory_bytes();
    }
};

/// The triangles' boxes, on huge pages as the renderer's (geometry/scene.cpp).
inline HugeVector<Bounds3> triangle_boxes(const Mesh& m) {
    HugeVector<Bounds3> boxes(m.triangle_count());
    for (size_t t = 0; t < boxes.size(); ++t) {
        Vec3 p0, p1, p2;
        m.vertices(t, p0, p1, p2);
        boxes[t].expand(p0);
        boxes[t].expand(p1);
        boxes[t].expand(p2);
    }
    return boxes;
}

/// Embree's memory: every allocation it reports to the device's monitor, summed.
inline std::atomic<int64_t> g_embree_bytes{0};
inline bool monitor(void*, ssize_t bytes, bool) {
    g_embree_bytes += bytes;
    return true;
}

inline void embree_error(void*, RTCError code, const char* what) {
    std::fprintf(stderr, "embree error %d: %s\n", static_cast<int>(code), what ? what : "");
    std::exit(1);
}

inline RTCDevice embree_device(int threads) {
    const std::string config = "threads=" + std::to_string(threads);
    RTCDevice d = rtcNewDevice(config.c_str());
    if (!d) throw std::runtime_error("rtcNewDevice failed");
    rtcSetDeviceErrorFunction(d, embree_error, nullptr);
    rtcSetDeviceMemoryMonitorFunction(d, monitor, nullptr);
    return d;
}

/// An Embree scene of one triangle geometry with the mesh's vertices and indices (copied into
/// Embree's own buffers), not yet committed.
inline RTCScene embree_scene(RTCDevice d, const Mesh& m, RTCBuildQuality quality, bool robust) {
    RTCScene s = rtcNewScene(d);
    rtcSetSceneBuildQuality(s, quality);
    rtcSetSceneFlags(s, robust ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
    RTCGeometry g = rtcNewGeometry(d, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(g, quality);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), m.positions.size()));
    for (size_t i = 0; i < m.positions.size(); ++i) {
        v[3 * i] = m.positions[i].x;
        v[3 * i + 1] = m.positions[i].y;
        v[3 * i + 2] = m.positions[i].z;
    }
    auto* idx = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), m.triangle_count()));
    std::memcpy(idx, m.indices.data(), m.indices.size() * sizeof(uint32_t));
    rtcCommitGeometry(g);
    rtcAttachGeometry(s, g);
    rtcReleaseGeometry(g);
    return s;
}

struct EmbreeAccel {
    RTCScene scene;

    void trace(const std::vector<Ray>& rays, std::vector<Result>& out, int threads) const {
        parallel_chunks(rays.size(), threads, [&](size_t begin, size_t end) {
            RTCIntersectContext ctx;
            rtcInitIntersectContext(&ctx);
            RTCRayHit rh;
            for (size_t k = begin; k < end; ++k) {
                const Ray& r = rays[k];
                rh.ray.org_x = r.origin.x;
                rh.ray.org_y = r.origin.y;
                rh.ray.org_z = r.origin.z;
                rh.ray.tnear = 0.0f;
                rh.ray.dir_x = r.direction.x;
                rh.ray.dir_y = r.direction.y;
                rh.ray.dir_z = r.direction.z;
                rh.ray.time = 0.0f;
                rh.ray.tfar = kInf;
                rh.ray.mask = 0xFFFFFFFFu;
                rh.ray.id = 0;
                rh.ray.flags = 0;
                rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
                rtcIntersect1(scene, &ctx, &rh);
                out[k] = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID
                             ? Result{}
                             : Result{rh.ray.tfar, rh.hit.primID};
            }
        });
    }
};

/// Embree's packets: rtcIntersect8 or rtcIntersect16 on N consecutive rays (a row or two of an
/// 8×8 tile for primary rays).
template <int N>
struct EmbreePackets {
    RTCScene scene;
    using RayHitN = std::conditional_t<N == 8, RTCRayHit8, RTCRayHit16>;

    void trace(const std::vector<Ray>& rays, std::vector<Result>& out, int threads) const {
        parallel_chunks(rays.size(), threads, [&](size_t begin, size_t end) {
            RTCIntersectContext ctx;
            rtcInitIntersectContext(&ctx);
            alignas(64) RayHitN rh;
            alignas(64) int valid[N];
            for (size_t first = begin; first < end; first += N) {
                const size_t n = std::min<size_t>(N, end - first);
                for (size_t k = 0; k < N; ++k) {
                    const Ray& r = rays[first + (k < n ? k : 0)];
                    valid[k] = k < n ? -1 : 0;
                    rh.ray.org_x[k] = r.origin.x;
                    rh.ray.org_y[k] = r.origin.y;
                    rh.ray.org_z[k] = r.origin.z;
                    rh.ray.tnear[k] = 0.0f;
                    rh.ray.dir_x[k] = r.direction.x;
                    rh.ray.dir_y[k] = r.direction.y;
                    rh.ray.dir_z[k] = r.direction.z;
                    rh.ray.time[k] = 0.0f;
                    rh.ray.tfar[k] = kInf;
                    rh.ray.mask[k] = 0xFFFFFFFFu;
                    rh.ray.id[k] = 0;
                    rh.ray.flags[k] = 0;
                    rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
                    rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
                }
                if constexpr (N == 8) {
                    rtcIntersect8(valid, scene, &ctx, &rh);
                } else {
                    rtcIntersect16(valid, scene, &ctx, &rh);
                }
                for (size_t k = 0; k < n; ++k) {
                    out[first + k] = rh.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID
                                         ? Result{}
                                         : Result{rh.ray.tfar[k], rh.hit.primID[k]};
                }
            }
        });
    }
};

/// luz's scene query (what the renderer calls): nearest_hit on a BuiltScene holding the mesh.
struct LuzScene {
    BuiltScene scene;

    void trace(const std::vector<Ray>& rays, std::vector<Result>& out, int threads) const {
        parallel_chunks(rays.size(), threads, [&](size_t begin, size_t end) {
            IntersectCounters counters;
            for (size_t k = begin; k < end; ++k) {
                Hit hit;
                out[k] = nearest_hit(scene, rays[k], 0.0f, kInf, hit, counters)
                             ? Result{hit.t, static_cast<uint32_t>(hit.part)}
                             : Result{};
            }
        });
    }
};

/// luz's packet query: nearest_hits() of 8 consecutive rays at once (as Embree's rtcIntersect8).
struct LuzScenePackets {
    const BuiltScene* scene;

    void trace(const std::vector<Ray>& rays, std::vector<Result>& out, int threads) const {
        parallel_chunks(rays.size(), threads, [&](size_t begin, size_t end) {
            IntersectCounters counters;
            Hit hits[kMaxPacket];
            bool found[kMaxPacket];
            for (size_t first = begin; first < end; first += kMaxPacket) {
                const int n = static_cast<int>(std::min<size_t>(kMaxPacket, end - first));
                nearest_hits(*scene, &rays[first], n, 0.0f, kInf, hits, found, counters);
                for (int k = 0; k < n; ++k) {
                    out[first + k] = found[k]
                                         ? Result{hits[k].t, static_cast<uint32_t>(hits[k].part)}
                                         : Result{};
                }
            }
        });
    }
};

// ---------------------------------------------------------------------------------------------
// Comparison

struct Agreement {
    size_t same = 0;       ///< both miss, or both hit the same triangle
    size_t tie = 0;        ///< both hit, other triangles at |Δt| ≤ 1e-4·t
    size_t hit_miss = 0;   ///< one hits, the other misses
    size_t different = 0;  ///< both hit, other triangles, t differs
    size_t agree() const { return same + tie; }
};

inline Agreement compare(const std::vector<Result>& a, const std::vector<Result>& b) {
    Agreement g;
    for (size_t k = 0; k < a.size(); ++k) {
        const bool ha = a[k].prim != kNoHit, hb = b[k].prim != kNoHit;
        if (ha != hb) {
            ++g.hit_miss;
        } else if (!ha || a[k].prim == b[k].prim) {
            ++g.same;
        } else if (std::fabs(a[k].t - b[k].t) <= 1e-4f * std::max(a[k].t, b[k].t)) {
            ++g.tie;
        } else {
            ++g.different;
        }
    }
    return g;
}

inline size_t hits(const std::vector<Result>& r) {
    return static_cast<size_t>(
        std::count_if(r.begin(), r.end(), [](const Result& x) { return x.prim != kNoHit; }));
}

}  // namespace luz::bvh_bench
