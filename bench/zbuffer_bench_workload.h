// A part of bench/zbuffer_vs_llvmpipe.cpp (included by it alone): its sizes and options, the
// torus both renderers draw, and the timed batches of frames.
#pragma once

#include <GL/osmesa.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/scene.h"
#include "image/image_io.h"
#include "machine_load.h"
#include "render/zbuffer.h"
#include "scene/camera.h"

namespace luz::zbuffer_bench {

constexpr int kWidth = 1024, kHeight = 1024;

/// A benchmark size: the torus tessellation level giving about that many triangles
/// (level·max(3, level/2)·2 triangles).
struct BenchSize {
    const char* name;
    int level;
};
constexpr BenchSize kSizes[] = {{"5k", 72}, {"100k", 316}, {"1M", 1000}};

/// What a run measures: many frames, their median wall time and the process CPU time.
struct Timing {
    double median_ms = 0;
    double cpu_ms = 0;  ///< process CPU time per frame, all threads (utilization = cpu/wall)
    double others = 0;  ///< cores kept busy by other processes meanwhile (should be ≈ 0)
    int frames = 0;
};

struct Options {
    int min_frames = 10;
    double min_seconds = 1.0;
    std::vector<BenchSize> sizes{std::begin(kSizes), std::end(kSizes)};
    bool luz = true, llvmpipe = true, breakdown = true;
    bool float_target = false;  ///< llvmpipe renders to RGBA32F instead of RGBA8
    double idle_wait = 120;     ///< longest wait for an idle machine, in seconds (0: never)
    std::string save_dir;       ///< write both images of every size there
    int profile_level = 0;      ///< > 0: only render luz frames at this level (for callgrind)
    int profile_threads = 1, profile_frames = 3;
};

// ---------------------------------------------------------------------------------------------
// The workload

/// A description and the runtime scene built from it (the scene no longer carries its
/// description: renders take the settings beside it).
struct TorusScene {
    SceneDesc desc;
    BuiltScene scene;
};

/// The benchmark scene: one torus seen at 45° from its axis, filling most of a 1024² image,
/// orthographic camera, one white point light, phong.
inline TorusScene torus_scene(int level) {
    SceneDesc d;
    d.name = "bench_torus";
    d.source = "zbuffer_vs_llvmpipe";
    d.image.width = kWidth;
    d.image.height = kHeight;
    d.image.background = Rgb{0.05f, 0.05f, 0.08f};
    d.camera.projection = Projection::orthographic;
    d.camera.position = {0, 0, 10};
    d.camera.look_at = {0, 0, 0};
    d.camera.up = {0, 1, 0};
    d.camera.view_height = 3.0f;
    d.render.pipeline = Pipeline::zbuffer;
    d.render.model = Model::phong;
    d.geometry.tessellation = level;
    d.ambient = Rgb{1.0f};
    d.attenuation_k = 1.0f;
    d.lights = {Light{{4, 5, 8}, Rgb{12.0f}, 0.0f}};
    Material m;
    m.name = "bench";
    m.ka = Rgb{0.1f};
    m.kd = Rgb{0.7f, 0.35f, 0.2f};
    m.ks = Rgb{0.5f};
    m.n = 30.0f;
    d.materials = {m};
    ObjectDesc torus;
    torus.type = ShapeType::torus;
    torus.path = "objects.0";
    torus.center = {0, 0, 0};
    torus.axis = {0, 1, 1};
    torus.major_radius = 1.0f;
    torus.minor_radius = 0.4f;
    d.objects = {torus};
    BuiltScene scene = build_scene(d);
    return {std::move(d), std::move(scene)};
}

/// FNV-1a over the mesh arrays: both processes must render the very same data.
inline uint64_t mesh_hash(const TriangleMesh& m) {
    uint64_t h = 1469598103934665603ull;
    auto add = [&](const void* data, size_t bytes) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ull;
    };
    add(m.positions.data(), m.positions.size() * sizeof(Vec3));
    add(m.normals.data(), m.normals.size() * sizeof(Vec3));
    add(m.indices.data(), m.indices.size() * sizeof(uint32_t));
    return h;
}

using bench::cpu_seconds;
using bench::machine_busy_seconds;

/// The number of threads of this process (/proc/self/status), or −1.
inline int process_threads() {
    std::ifstream in("/proc/self/status");
    for (std::string line; std::getline(in, line);)
        if (line.rfind("Threads:", 0) == 0) return std::stoi(line.substr(8));
    return -1;
}

/// Frames timed one by one, with the process CPU time and other processes' load meanwhile.
struct Batch {
    std::vector<double> ms;
    double cpu_ms = 0;  ///< process CPU time over the whole batch, all threads
    double others = 0;  ///< cores used by other processes meanwhile
};

/// Runs `frame` k times.
inline Batch run_batch(const std::function<void()>& frame, int k) {
    using clock = std::chrono::steady_clock;
    Batch b;
    const double cpu_start = cpu_seconds(), machine_start = machine_busy_seconds();
    const auto start = clock::now();
    for (int i = 0; i < k; ++i) {
        const auto t0 = clock::now();
        frame();
        b.ms.push_back(std::chrono::duration<double, std::milli>(clock::now() - t0).count());
    }
    const double wall = std::chrono::duration<double>(clock::now() - start).count();
    const double own = cpu_seconds() - cpu_start;
    b.cpu_ms = 1000.0 * own;
    if (machine_start >= 0)
        b.others = std::max(0.0, (machine_busy_seconds() - machine_start - own) / wall);
    return b;
}

/// The frames of one configuration, gathered batch by batch.
struct Series {
    std::vector<double> ms;
    double cpu_ms = 0, seconds = 0, others = 0;

    void add(const Batch& b) {
        ms.insert(ms.end(), b.ms.begin(), b.ms.end());
        cpu_ms += b.cpu_ms;
        for (double x : b.ms) seconds += x / 1000.0;
        others = std::max(others, b.others);
    }
    double median() const {
        if (ms.empty()) return 0;
        std::vector<double> x = ms;
        std::sort(x.begin(), x.end());
        return x.size() % 2 ? x[x.size() / 2] : 0.5 * (x[x.size() / 2 - 1] + x[x.size() / 2]);
    }
    Timing timing() const {
        Timing t;
        t.frames = static_cast<int>(ms.size());
        t.median_ms = median();
        t.cpu_ms = t.frames ? cpu_ms / t.frames : 0;
        t.others = others;
        return t;
    }
};

}  // namespace luz::zbuffer_bench
