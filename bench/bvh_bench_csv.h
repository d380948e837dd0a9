// A part of bench/bvh_vs_embree.cpp (included by it alone): the rows it measures per mesh and
// thread count, and --csv, those rows appended as machine-readable lines.
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

#include "bvh_bench_engines.h"

namespace luz::bvh_bench {

// ---------------------------------------------------------------------------------------------
// One mesh

struct Row {
    std::string mesh, rays;
    size_t count = 0;
    int threads = 0;
    double luz8 = 0, luz2 = 0, embree = 0, scene = 0;  ///< Mrays/s
    double scene8 = 0, embree8 = 0, embree16 = 0;      ///< packets (with --scene), Mrays/s
    size_t scene8_differs = 0, embree8_differs = 0;    ///< rays where they differ from one by one
    Agreement agreement;                               ///< luz8 against Embree
    size_t luz2_differs = 0, scene_differs = 0;        ///< rays where they differ from luz8
};

struct BuildRow {
    std::string mesh;
    size_t triangles = 0;
    std::vector<double> luz2_ms, luz8_ms, medium_ms, high_ms;  ///< per thread count
    double luz2_bytes = 0, luz8_bytes = 0, medium_bytes = 0, high_bytes = 0,
           scene_bytes = 0;  ///< per triangle
    double leaf = 0;         ///< mean primitives per leaf
    size_t vertices = 0;
    /// --scene: build_scene() (mesh and BVH) and its BVH part (bvh_build_seconds), ms, median
    /// of up to 3 builds on scene_threads threads (the largest thread count)
    double scene_ms = 0, scene_bvh_ms = 0;
    int scene_threads = 0;
    int build_reps = 0;  ///< builds timed per engine and thread count
};

// ---------------------------------------------------------------------------------------------
// --csv

/// The CSV's columns: per mesh and thread count, the build times and bytes of the tables
/// (luz_build_ms = Bvh8_Nt, embree_build_ms = med_Nt, luz_bytes_per_tri = scene_B, …) and,
/// per ray set, Mrays/s (luz = the scene query, the tables' `scene`; luz_bvh8 = `Bvh8`).
/// Columns without a value (no --scene; the scene build on another thread count) are empty.
const char* const kRaySets[] = {"perspective", "orthographic", "incoherent"};

inline std::string csv_header() {
    std::string h =
        "mesh,triangles,vertices,threads,size,reps,build_reps,luz_build_ms,luz_bvh2_build_ms,"
        "embree_build_ms,embree_high_build_ms,luz_scene_build_ms,luz_scene_bvh_build_ms,"
        "luz_bytes_per_tri,luz_bvh8_bytes_per_tri,luz_bvh2_bytes_per_tri,embree_bytes_per_tri,"
        "embree_high_bytes_per_tri";
    for (const char* set : kRaySets) {
        const std::string r = set;
        h += "," + r + "_rays,luz_" + r + "_mrays,luz_bvh8_" + r + "_mrays,luz_bvh2_" + r +
             "_mrays,embree_" + r + "_mrays," + r + "_agree";
    }
    for (const char* set : kRaySets) {
        const std::string r = set;
        h += ",luz_packet_" + r + "_mrays,embree8_" + r + "_mrays,embree16_" + r + "_mrays";
    }
    return h + ",max_rss_mib";
}

/// Appends the rows of one mesh (its BuildRow and its tracing rows) to opt.csv, with the
/// header first if the file is new or empty; a file with another header is an error.
inline void append_csv(const Options& opt, const BuildRow& b, const std::vector<Row>& rows) {
    const std::string header = csv_header();
    {
        std::ifstream in(opt.csv);
        std::string first;
        if (in && std::getline(in, first) && !first.empty() && first != header)
            throw std::runtime_error(opt.csv + ": has other columns (an older CSV?); remove it");
    }
    std::ofstream out(opt.csv, std::ios::app);
    if (!out) throw std::runtime_error(opt.csv + ": cannot write");
    if (out.tellp() == 0) out << header << "\n";
    const auto num = [](double x, const char* fmt = "%.4f") {
        char s[64];
        std::snprintf(s, sizeof s, fmt, x);
        return std::string(s);
    };
    struct rusage ru {};
    getrusage(RUSAGE_SELF, &ru);
    for (size_t i = 0; i < opt.threads.size(); ++i) {
        const int t = opt.threads[i];
        const bool scene_here = opt.scene && t == b.scene_threads;
        out << b.mesh << ',' << b.triangles << ',' << b.vertices << ',' << t << ',' << opt.size
            << ',' << opt.reps << ',' << b.build_reps << ',' << num(b.luz8_ms[i]) << ','
            << num(b.luz2_ms[i]) << ',' << num(b.medium_ms[i]) << ',' << num(b.high_ms[i]) << ','
            << (scene_here ? num(b.scene_ms) : "") << ',' << (scene_here ? num(b.scene_bvh_ms) : "")
            << ',' << (opt.scene ? num(b.scene_bytes, "%.2f") : "") << ','
            << num(b.luz8_bytes, "%.2f") << ',' << num(b.luz2_bytes, "%.2f") << ','
            << num(b.medium_bytes, "%.2f") << ',' << num(b.high_bytes, "%.2f");
        for (const char* set : kRaySets) {
            const Row* r = nullptr;
            for (const Row& x : rows)
                if (x.mesh == b.mesh && x.threads == t && x.rays == set) r = &x;
            if (!r) {
                out << ",,,,,,";
                continue;
            }
            out << ',' << r->count << ',' << (opt.scene ? num(r->scene) : "") << ',' << num(r->luz8)
                << ',' << num(r->luz2) << ',' << num(r->embree) << ','
                << num(static_cast<double>(r->agreement.agree()) /
                           static_cast<double>(std::max<size_t>(1, r->count)),
                       "%.6f");
        }
        for (const char* set : kRaySets) {
            const Row* r = nullptr;
            for (const Row& x : rows)
                if (x.mesh == b.mesh && x.threads == t && x.rays == set) r = &x;
            if (!r || !opt.scene) {
                out << ",,,";
                continue;
            }
            out << ',' << num(r->scene8) << ',' << num(r->embree8) << ',' << num(r->embree16);
        }
        out << ',' << num(static_cast<double>(ru.ru_maxrss) / 1024.0, "%.0f") << "\n";
    }
    if (!out) throw std::runtime_error(opt.csv + ": cannot write");
}

}  // namespace luz::bvh_bench
