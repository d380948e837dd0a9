// A part of bench/bvh_vs_embree.cpp (included by it alone): its options, timing, the meshes
// it measures (OBJ files, the bumpy sphere) and the rays it traces.
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

#include "geometry/bvh.h"
#include "geometry/mesh.h"
#include "geometry/scene.h"
#include "geometry/scene_query.h"
#include "geometry/shapes.h"
#include "geometry/wide_bvh.h"
#include "machine_load.h"
#include "scene/obj_loader.h"

namespace luz::bvh_bench {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr uint32_t kNoHit = 0xFFFFFFFFu;

/// A mesh to measure: an OBJ file, or (sphere > 0) the bumpy sphere of N = sphere segments.
struct MeshSource {
    std::string path;
    int sphere = 0;
};

struct Options {
    std::vector<MeshSource> meshes;
    std::string csv;                 ///< --csv: append one row per mesh and thread count here
    int size = 1024;                 ///< primary rays: size × size
    int reps = 5;                    ///< timed passes per engine and configuration (median)
    std::vector<int> threads{1, 2};  ///< thread counts for tracing and building
    double idle_wait = 60;           ///< longest wait for an idle machine (0: never wait)
    bool robust = false;             ///< Embree: RTC_SCENE_FLAG_ROBUST
    bool scene = false;              ///< also time luz's scene query (nearest_hit)
    bool cpu_time = false;  ///< time by process CPU time (while developing on a busy machine)
    int build_reps = 0;     ///< 0: 21 (small meshes) or 5
    BvhOptions bvh;         ///< luz's build settings (default: BvhOptions{})
};

inline bool g_cpu_time = false;

// ---------------------------------------------------------------------------------------------
// Time and load

inline double now_seconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

using bench::cpu_seconds;
using bench::machine_busy_seconds;

/// Waits until other processes leave the CPUs nearly idle (< 0.1 core over half a second), for
/// at most `max_seconds`.
inline void wait_for_idle(double max_seconds) {
    const double start = now_seconds();
    bool said = false;
    while (now_seconds() - start < max_seconds) {
        const double m0 = machine_busy_seconds(), c0 = cpu_seconds(), t0 = now_seconds();
        usleep(500000);
        const double busy =
            (machine_busy_seconds() - m0 - (cpu_seconds() - c0)) / (now_seconds() - t0);
        if (m0 < 0 || busy < 0.1) return;
        if (!said) std::fprintf(stderr, "  waiting for an idle machine (%.2f cores busy)\n", busy);
        said = true;
    }
    std::fprintf(stderr, "  machine still busy: measuring anyway\n");
}

/// Runs f() once; its wall seconds, and in `others` the cores other processes used meanwhile.
inline double timed(const std::function<void()>& f, double& others) {
    const double m0 = machine_busy_seconds(), c0 = cpu_seconds(), t0 = now_seconds();
    f();
    const double wall = now_seconds() - t0;
    const double own = cpu_seconds() - c0;
    others = m0 < 0 ? 0 : std::max(0.0, (machine_busy_seconds() - m0 - own) / wall);
    return g_cpu_time ? own : wall;
}

inline double median(std::vector<double> x) {
    if (x.empty()) return 0;
    std::sort(x.begin(), x.end());
    const size_t n = x.size();
    return n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
}

/// Runs each of `configs` `reps` times, interleaved (a, b, c, b, c, a, …: the order rotated
/// every round) so that a drifting machine slows all alike; a run during which other processes
/// used more than 0.15 core is dropped and repeated once the machine is idle. One untimed
/// warm-up run each. Returns the median seconds of each.
inline std::vector<double> interleaved(const std::vector<std::function<void()>>& configs, int reps,
                                       double idle_wait) {
    const size_t n = configs.size();
    std::vector<std::vector<double>> seconds(n);
    for (const auto& f : configs) f();
    int dropped = 0;
    for (int round = 0; round < reps; ++round) {
        for (size_t i = 0; i < n; ++i) {
            const size_t c = (i + static_cast<size_t>(round)) % n;
            double others = 0;
            const double s = timed(configs[c], others);
            if (idle_wait > 0 && others > 0.15 && dropped < 40) {
                ++dropped;
                std::fprintf(stderr, "  other processes took %.2f cores: run dropped\n", others);
                wait_for_idle(idle_wait);
                --i;
                continue;
            }
            seconds[c].push_back(s);
            if (std::getenv("LUZ_BENCH_VERBOSE")) std::fprintf(stderr, "  run %zu: %.4f s\n", c, s);
        }
    }
    std::vector<double> m;
    for (const auto& s : seconds) m.push_back(median(s));
    return m;
}

// ---------------------------------------------------------------------------------------------
// Rays

/// A 32-bit integer hash (Wellons' lowbias32): the deterministic RNG of the secondary rays.
inline uint32_t hash32(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}
inline float unit_float(uint32_t h) { return static_cast<float>(h >> 8) * 0x1p-24f; }

/// The camera framing a mesh: looking at the centre of its bounds from direction `to_eye`,
/// y up, the sphere around the centre through the farthest vertex just fitting the image.
struct Framing {
    Vec3 centre, forward, right, up;
    float radius;
};

inline Framing frame_mesh(const Mesh& m) {
    Framing f;
    f.centre = m.bounds.centre();
    f.radius = 0;
    for (const Vec3& p : m.positions) f.radius = std::max(f.radius, length(p - f.centre));
    f.forward = -normalize(Vec3{0.35f, 0.3f, 1.0f});
    f.right = normalize(cross(f.forward, Vec3{0, 1, 0}));
    f.up = cross(f.right, f.forward);
    return f;
}

/// Pixel (x, y) of the k-th ray when an n×n image is walked in 8×8 tiles (as renderers do).
inline void tile_pixel(int k, int n, int& x, int& y) {
    const int tiles_x = (n + 7) / 8;
    const int tile = k / 64, in = k % 64;
    x = (tile % tiles_x) * 8 + in % 8;
    y = (tile / tiles_x) * 8 + in / 8;
}

/// n×n perspective rays (vertical field of view 40°), unit directions, in 8×8 tiles.
inline std::vector<Ray> perspective_rays(const Framing& f, int n) {
    const float half = std::tan(20.0f * 3.14159265f / 180.0f);
    const Vec3 eye = f.centre - f.forward * (f.radius / std::sin(20.0f * 3.14159265f / 180.0f));
    std::vector<Ray> rays;
    rays.reserve(static_cast<size_t>(n) * n);
    for (int k = 0; k < n * n; ++k) {
        int x, y;
        tile_pixel(k, n, x, y);
        if (x >= n || y >= n) continue;
        const float u = (2.0f * (x + 0.5f) / n - 1.0f) * half;
        const float v = (1.0f - 2.0f * (y + 0.5f) / n) * half;
        rays.push_back({eye, normalize(f.forward + f.right * u + f.up * v)});
    }
    return rays;
}

/// n×n orthographic rays over a square of side 2·radius, in 8×8 tiles.
inline std::vector<Ray> orthographic_rays(const Framing& f, int n) {
    std::vector<Ray> rays;
    rays.reserve(static_cast<size_t>(n) * n);
    const Vec3 plane = f.centre - f.forward * (2.0f * f.radius);
    for (int k = 0; k < n * n; ++k) {
        int x, y;
        tile_pixel(k, n, x, y);
        if (x >= n || y >= n) continue;
        const float u = (2.0f * (x + 0.5f) / n - 1.0f) * f.radius;
        const float v = (1.0f - 2.0f * (y + 0.5f) / n) * f.radius;
        rays.push_back({plane + f.right * u + f.up * v, f.forward});
    }
    return rays;
}

struct Result {
    float t = kInf;
    uint32_t prim = kNoHit;
};

/// One incoherent ray per hit primary ray: from the hit point moved 1e-4 along the face normal
/// (turned towards the primary ray's origin), in a cosine-distributed direction about it.
inline std::vector<Ray> incoherent_rays(const Mesh& m, const std::vector<Ray>& primary,
                                        const std::vector<Result>& hits) {
    std::vector<Ray> rays;
    for (size_t k = 0; k < primary.size(); ++k) {
        if (hits[k].prim == kNoHit) continue;
        const Ray& r = primary[k];
        Vec3 n = m.face_normal(hits[k].prim);
        if (dot(n, r.direction) > 0) n = -n;
        const Vec3 p = r.at(hits[k].t) + n * 1e-4f;
        // cosine-weighted: a uniform point on the unit disc lifted to the hemisphere
        const float u1 = unit_float(hash32(2 * static_cast<uint32_t>(k)));
        const float u2 = unit_float(hash32(2 * static_cast<uint32_t>(k) + 1));
        const float rad = std::sqrt(u1), phi = 2.0f * 3.14159265f * u2;
        const float lx = rad * std::cos(phi), ly = rad * std::sin(phi);
        const float lz = std::sqrt(std::max(0.0f, 1.0f - u1));
        // orthonormal basis about n (Duff et al., JCGT 2017)
        const float sign = std::copysign(1.0f, n.z);
        const float a = -1.0f / (sign + n.z), b = n.x * n.y * a;
        const Vec3 b1{1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x};
        const Vec3 b2{b, sign + n.y * n.y * a, -n.y};
        rays.push_back({p, normalize(b1 * lx + b2 * ly + n * lz)});
    }
    return rays;
}

/// scripts/make_big_mesh.py's bumpy sphere (r = 1 + ripples in latitude and longitude), built
/// in memory as the OBJ loader would give it: n segments around and n/2 rings, one vertex at
/// each pole, counter-clockwise from outside, n·(n/2 − 1)·2 triangles; the same vertex and face
/// order, the same formula in double, each coordinate rounded to the file's 6 decimals (so
/// sphere_1024 is, to the float, the mesh bench/run_bvh_bench.sh writes).
inline MeshData bumpy_sphere(int n) {
    if (n < 8 || n % 2) throw std::runtime_error("--sphere N: N must be an even number >= 8");
    const int rings = n / 2;
    const double pi = 3.141592653589793;
    const auto radius = [](double th, double ph) {
        return 1.0 + 0.04 * std::sin(12 * th) * std::sin(15 * ph) +
               0.015 * std::sin(60 * th + 3 * ph);
    };
    const auto six = [](double x) { return static_cast<float>(std::round(x * 1e6) / 1e6); };
    MeshData d;
    d.file = "sphere_" + std::to_string(n);
    const size_t un = static_cast<size_t>(n);
    d.positions.reserve(2 + (static_cast<size_t>(rings) - 1) * un);
    d.positions.push_back({0.0f, six(radius(0.0, 0.0)), 0.0f});
    for (int j = 1; j < rings; ++j) {
        const double th = pi * j / rings, st = std::sin(th), ct = std::cos(th);
        for (int i = 0; i < n; ++i) {
            const double ph = 2 * pi * i / n, r = radius(th, ph);
            d.positions.push_back(
                {six(r * st * std::cos(ph)), six(r * ct), six(r * st * std::sin(ph))});
        }
    }
    const uint32_t south = static_cast<uint32_t>(d.positions.size());
    d.positions.push_back({0.0f, six(-radius(pi, 0.0)), 0.0f});
    // vertex i (mod n) on ring j (1 .. rings-1), 0-based
    const auto at = [&](int i, int j) {
        return static_cast<uint32_t>(1 + static_cast<size_t>(j - 1) * un + (i % n));
    };
    const size_t triangles = un * (static_cast<size_t>(rings) - 1) * 2;
    d.position.reserve(3 * triangles);
    const auto face = [&](uint32_t a, uint32_t b, uint32_t c) {
        d.position.insert(d.position.end(), {a, b, c});
    };
    for (int i = 0; i < n; ++i) face(0, at(i + 1, 1), at(i, 1));
    for (int j = 1; j < rings - 1; ++j) {
        for (int i = 0; i < n; ++i) {
            const uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), e = at(i, j + 1);
            face(a, b, c);
            face(a, c, e);
        }
    }
    for (int i = 0; i < n; ++i) face(south, at(i, rings - 1), at(i + 1, rings - 1));
    d.normal.assign(d.position.size(), -1);
    d.material.assign(triangles, -1);
    return d;
}

}  // namespace luz::bvh_bench
