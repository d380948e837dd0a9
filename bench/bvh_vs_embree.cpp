// Benchmark: luz's BVH (Bvh8 as scenes use it, and the binary Bvh) against Embree 3 rtcIntersect1
// on the same OBJ triangles — primary and incoherent rays, 1 and 2 threads, hits compared ray by
// ray; build times, bytes per triangle. Results: docs/BENCHMARKS.md. Besides OBJ files it
// takes procedural meshes (--sphere N: scripts/make_big_mesh.py's bumpy sphere built in memory)
// and appends machine-readable rows to --csv (bench/cost_growth.sh, "How cost grows").
#include <embree3/rtcore.h>
#include <tbb/task_arena.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bvh_bench_csv.h"
#include "bvh_bench_engines.h"
#include "bvh_bench_rays.h"

namespace {

using namespace luz;
using namespace luz::bvh_bench;

std::string base_name(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

void run_mesh(const MeshSource& source, const Options& opt, std::vector<Row>& rows,
              std::vector<BuildRow>& builds) {
    // 1. The mesh, through luz's OBJ loader (or the sphere's MeshData made here) and mesh code
    //    (flat: positions shared by corners).
    std::vector<std::string> warnings;
    ObjectDesc o;
    o.type = ShapeType::mesh;
    o.smooth = false;
    o.path = "objects.0";
    std::string name;
    if (source.sphere > 0) {
        o.mesh = std::make_shared<const MeshData>(bumpy_sphere(source.sphere));
        o.file = name = o.mesh->file;
    } else {
        o.file = source.path;
        o.mesh = std::make_shared<const MeshData>(load_obj(source.path, false, warnings));
        name = base_name(source.path);
    }
    const Mesh mesh = build_mesh(o);
    const size_t n_tri = mesh.triangle_count();
    std::printf("\n== %s: %zu triangles, %zu vertices\n", name.c_str(), n_tri,
                mesh.positions.size());
    std::fflush(stdout);

    BuildRow build;
    build.mesh = name;
    build.triangles = n_tri;
    build.vertices = mesh.positions.size();
    const int build_reps = opt.build_reps > 0 ? opt.build_reps : n_tri > 200000 ? 5 : 21;
    build.build_reps = build_reps;

    // 2. Build times. luz: triangle boxes + Bvh::build (+ the collapse to Bvh8), in a TBB arena
    //    of 1 or 2 threads made beforehand (as Embree's device is); Embree: rtcCommitScene on a
    //    device of 1 or 2 threads.
    LuzAccel<BinaryBvh> luz2;
    LuzAccel<Bvh8> luz8;
    luz2.mesh = luz8.mesh = &mesh;
    for (int threads : opt.threads) {
        tbb::task_arena arena(threads);
        arena.initialize();
        std::vector<double> s2, s8;
        for (int k = 0; k < build_reps; ++k) {
            double t0 = now_seconds();
            BinaryBvh b2;
            arena.execute([&] { b2 = BinaryBvh::build(triangle_boxes(mesh), opt.bvh); });
            s2.push_back(now_seconds() - t0);
            t0 = now_seconds();
            decltype(luz8.bvh) b8;
            arena.execute([&] { b8 = decltype(luz8.bvh)::build(triangle_boxes(mesh), opt.bvh); });
            s8.push_back(now_seconds() - t0);
            if (k == 0) {
                luz2.bvh = std::move(b2);
                luz8.bvh = std::move(b8);
            }
        }
        build.luz2_ms.push_back(1000 * median(s2));
        build.luz8_ms.push_back(1000 * median(s8));
    }
    {
        size_t leaves = 0, slots = 0;
        for (const BvhNode& nd : luz2.bvh.nodes())
            if (nd.leaf()) ++leaves, slots += nd.count;
        build.leaf = static_cast<double>(slots) / static_cast<double>(leaves);
    }
    build.luz2_bytes = static_cast<double>(luz2.bytes()) / static_cast<double>(n_tri);
    build.luz8_bytes = static_cast<double>(luz8.bytes()) / static_cast<double>(n_tri);

    RTCScene traced = nullptr;
    RTCDevice traced_device = nullptr;
    for (size_t ti = 0; ti < opt.threads.size(); ++ti) {
        RTCDevice d = embree_device(opt.threads[ti]);
        for (RTCBuildQuality q : {RTC_BUILD_QUALITY_MEDIUM, RTC_BUILD_QUALITY_HIGH}) {
            std::vector<double> s;
            for (int k = 0; k < build_reps; ++k) {
                const int64_t before = g_embree_bytes;
                RTCScene sc = embree_scene(d, mesh, q, opt.robust);
                const double t0 = now_seconds();
                rtcCommitScene(sc);
                s.push_back(now_seconds() - t0);
                const double bytes = static_cast<double>(g_embree_bytes - before) / n_tri;
                (q == RTC_BUILD_QUALITY_MEDIUM ? build.medium_bytes : build.high_bytes) = bytes;
                // the scene traced: medium quality, on the device with the most threads
                if (q == RTC_BUILD_QUALITY_MEDIUM && k == 0 && ti + 1 == opt.threads.size()) {
                    traced = sc;
                } else {
                    rtcReleaseScene(sc);
                }
            }
            (q == RTC_BUILD_QUALITY_MEDIUM ? build.medium_ms : build.high_ms)
                .push_back(1000 * median(s));
        }
        if (ti + 1 == opt.threads.size()) {
            traced_device = d;
        } else {
            rtcReleaseDevice(d);
        }
    }
    EmbreeAccel embree{traced};

    std::unique_ptr<LuzScene> scene;
    if (opt.scene) {
        SceneDesc desc;
        desc.render.pipeline = Pipeline::raytrace;
        desc.geometry.accel = Accel::bvh;
        desc.materials.resize(1);
        desc.objects = {o};
        // timed in an arena of the largest thread count (as the traced Embree scene's device)
        tbb::task_arena arena(opt.threads.back());
        arena.initialize();
        std::vector<double> s, s_bvh;
        for (int k = 0; k < std::min(build_reps, 3); ++k) {
            const double t0 = now_seconds();
            auto built = std::make_unique<LuzScene>();
            arena.execute([&] { built->scene = build_scene(desc); });
            s.push_back(now_seconds() - t0);
            s_bvh.push_back(built->scene.bvh_build_seconds);
            if (k == 0) scene = std::move(built);
        }
        build.scene_ms = 1000 * median(s);
        build.scene_bvh_ms = 1000 * median(s_bvh);
        build.scene_threads = opt.threads.back();
        build.scene_bytes = static_cast<double>(scene->scene.bvh_bytes() +
                                                mesh.positions.capacity() * sizeof(Vec3) +
                                                mesh.indices.capacity() * sizeof(uint32_t)) /
                            static_cast<double>(n_tri);
    }
    builds.push_back(build);
    std::printf("build (%d thread): luz Bvh %.2f ms, Bvh8 %.2f, embree medium %.2f, high %.2f\n",
                opt.threads[0], build.luz2_ms[0], build.luz8_ms[0], build.medium_ms[0],
                build.high_ms[0]);
    std::fflush(stdout);

    // 3. Rays: primary (perspective, orthographic), then incoherent rays from the perspective
    //    hits (luz's, traced once untimed).
    const Framing f = frame_mesh(mesh);
    struct RaySet {
        std::string name;
        std::vector<Ray> rays;
    };
    std::vector<RaySet> sets;
    sets.push_back({"perspective", perspective_rays(f, opt.size)});
    sets.push_back({"orthographic", orthographic_rays(f, opt.size)});
    {
        std::vector<Result> first(sets[0].rays.size());
        luz8.trace(sets[0].rays, first, 2);
        sets.push_back({"incoherent", incoherent_rays(mesh, sets[0].rays, first)});
    }

    // 4. Counters per ray (luz, untimed).
    for (const RaySet& s : sets) {
        uint64_t boxes2 = 0, tris2 = 0, boxes8 = 0, tris8 = 0;
        for (const Ray& r : s.rays) luz2.trace(r, boxes2, tris2);
        for (const Ray& r : s.rays) luz8.trace(r, boxes8, tris8);
        const double n = static_cast<double>(s.rays.size());
        std::printf(
            "%-12s %8zu rays: per ray, Bvh %.1f box and %.2f triangle tests, Bvh8 %.1f and "
            "%.2f\n",
            s.name.c_str(), s.rays.size(), boxes2 / n, tris2 / n, boxes8 / n, tris8 / n);
    }
    std::fflush(stdout);

    // 5. Timing: luz and Embree alternately, per ray set and thread count.
    for (const RaySet& s : sets) {
        for (int threads : opt.threads) {
            const size_t count = s.rays.size();
            std::vector<Result> r8(count), r2(count), re(count), rs(count), rs8(count), re8(count),
                re16(count);
            const LuzScenePackets scene_packets{scene ? &scene->scene : nullptr};
            const EmbreePackets<8> embree8{traced};
            const EmbreePackets<16> embree16{traced};
            std::vector<std::function<void()>> configs = {
                [&] { luz8.trace(s.rays, r8, threads); },
                [&] { embree.trace(s.rays, re, threads); },
                [&] { luz2.trace(s.rays, r2, threads); }};
            if (scene) {
                configs.push_back([&] { scene->trace(s.rays, rs, threads); });
                configs.push_back([&] { scene_packets.trace(s.rays, rs8, threads); });
                configs.push_back([&] { embree8.trace(s.rays, re8, threads); });
                configs.push_back([&] { embree16.trace(s.rays, re16, threads); });
            }
            const std::vector<double> sec = interleaved(configs, opt.reps, opt.idle_wait);
            Row row;
            row.mesh = name;
            row.rays = s.name;
            row.count = count;
            row.threads = threads;
            const double n = static_cast<double>(count) * 1e-6;
            row.luz8 = n / sec[0];
            row.embree = n / sec[1];
            row.luz2 = n / sec[2];
            if (scene) {
                row.scene = n / sec[3];
                row.scene8 = n / sec[4];
                row.embree8 = n / sec[5];
                row.embree16 = n / sec[6];
                row.scene8_differs = count - compare(rs, rs8).same;
                row.embree8_differs =
                    (count - compare(re, re8).same) + (count - compare(re, re16).same);
            }
            row.agreement = compare(r8, re);
            row.luz2_differs = count - compare(r8, r2).same;
            if (scene) row.scene_differs = count - compare(r8, rs).same;
            std::printf(
                "%-12s %dt: Mrays/s luz Bvh8 %6.2f, Bvh %6.2f, embree %6.2f (Bvh8/embree %.2f)"
                "%s; hits luz %zu embree %zu; agree %zu/%zu (same %zu, tie %zu, hit/miss %zu, "
                "other %zu); Bvh differs on %zu, scene on %zu\n",
                s.name.c_str(), threads, row.luz8, row.luz2, row.embree, row.luz8 / row.embree,
                scene ? (", scene " + std::to_string(row.scene)).c_str() : "", hits(r8), hits(re),
                row.agreement.agree(), count, row.agreement.same, row.agreement.tie,
                row.agreement.hit_miss, row.agreement.different, row.luz2_differs,
                row.scene_differs);
            std::fflush(stdout);
            rows.push_back(row);
        }
    }
    rtcReleaseScene(traced);
    rtcReleaseDevice(traced_device);
}

// ---------------------------------------------------------------------------------------------

void usage(FILE* out) {
    std::fprintf(
        out,
        "usage: bvh_vs_embree [--size N] [--reps N] [--threads 1,2] [--idle-wait S] [--robust]\n"
        "                     [--scene] [--build-reps N] [--cpu-time] [--bins N] [--leaf N]\n"
        "                     [--traversal-cost C] [--sphere N[,N...]] [--csv PATH]\n"
        "                     [MESH.obj...]\n"
        "  Builds each OBJ mesh into luz's BVH and into Embree 3, traces N×N perspective and\n"
        "  orthographic primary rays (default 1024) and one incoherent ray per primary hit\n"
        "  with both (rtcIntersect1), on each thread count; prints Mrays/s (median of --reps\n"
        "  timed passes, default 5), the ratio luz/Embree, the hit agreement, build times and\n"
        "  bytes per triangle. --robust: Embree's RTC_SCENE_FLAG_ROBUST. --scene: also time\n"
        "  luz's scene query nearest_hit(). Runs disturbed by other processes are repeated\n"
        "  after waiting up to --idle-wait seconds (default 60; 0: never) for an idle machine.\n"
        "  --bins, --leaf, --traversal-cost: luz's BvhOptions (default: its defaults).\n"
        "  --build-reps: builds timed per engine (default 21, or 5 above 200k triangles).\n"
        "  --cpu-time: rays per CPU second of the process instead of per wall second (only\n"
        "  for comparing variants on a busy machine; not for published figures).\n"
        "  --sphere N: also (in command-line order) the bumpy sphere of scripts/make_big_mesh.py\n"
        "  built in memory, N segments and N/2 rings, N·(N/2−1)·2 triangles, named sphere_N\n"
        "  (repeatable, or a comma list; N even, >= 8).\n"
        "  --csv PATH: append one row per mesh and thread count (build ms, bytes per triangle,\n"
        "  Mrays/s per ray set; luz = the scene query with --scene) to PATH, a header first if\n"
        "  it is new.\n");
}

}  // namespace

int main(int argc, char** argv) {
    Options opt;
    const auto int_list = [](const std::string& list) {
        std::vector<int> v;
        for (size_t p = 0; p < list.size();) {
            const size_t q = list.find(',', p);
            v.push_back(std::stoi(list.substr(p, q - p)));
            p = q == std::string::npos ? list.size() : q + 1;
        }
        return v;
    };
    try {
        for (int i = 1; i < argc; ++i) {
            const std::string a = argv[i];
            const auto next = [&]() -> std::string {
                if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
                return argv[++i];
            };
            if (a == "--size") {
                opt.size = std::stoi(next());
            } else if (a == "--reps") {
                opt.reps = std::stoi(next());
            } else if (a == "--threads") {
                opt.threads.clear();
                for (int t : int_list(next())) opt.threads.push_back(t);
            } else if (a == "--sphere") {
                for (int n : int_list(next())) {
                    if (n < 8 || n % 2) throw std::runtime_error("--sphere: N must be even, >= 8");
                    opt.meshes.push_back({"", n});
                }
            } else if (a == "--csv") {
                opt.csv = next();
            } else if (a == "--idle-wait") {
                opt.idle_wait = std::stod(next());
            } else if (a == "--robust") {
                opt.robust = true;
            } else if (a == "--scene") {
                opt.scene = true;
            } else if (a == "--cpu-time") {
                opt.cpu_time = g_cpu_time = true;
            } else if (a == "--bins") {
                opt.bvh.bins = std::stoi(next());
            } else if (a == "--leaf") {
                opt.bvh.max_leaf_size = static_cast<uint32_t>(std::stoi(next()));
            } else if (a == "--traversal-cost") {
                opt.bvh.traversal_cost = std::stof(next());
            } else if (a == "--build-reps") {
                opt.build_reps = std::stoi(next());
            } else if (a == "--help" || a == "-h") {
                usage(stdout);
                return 0;
            } else if (!a.empty() && a[0] == '-') {
                throw std::runtime_error("unknown option " + a);
            } else {
                opt.meshes.push_back({a, 0});
            }
        }
        if (opt.meshes.empty()) throw std::runtime_error("no mesh given (MESH.obj or --sphere N)");
        if (opt.size < 8 || opt.reps < 1 || opt.threads.empty())
            throw std::runtime_error("bad --size, --reps or --threads");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bvh_vs_embree: %s\n", e.what());
        usage(stderr);
        return 2;
    }

    std::vector<Row> rows;
    std::vector<BuildRow> builds;
    try {
        RTCDevice probe = embree_device(1);
        std::printf("Embree %zd.%zd.%zd, %s rays, %d×%d primary rays, %d timed passes\n",
                    rtcGetDeviceProperty(probe, RTC_DEVICE_PROPERTY_VERSION_MAJOR),
                    rtcGetDeviceProperty(probe, RTC_DEVICE_PROPERTY_VERSION_MINOR),
                    rtcGetDeviceProperty(probe, RTC_DEVICE_PROPERTY_VERSION_PATCH),
                    opt.robust ? "robust" : "default", opt.size, opt.size, opt.reps);
        rtcReleaseDevice(probe);
        if (opt.idle_wait > 0) wait_for_idle(opt.idle_wait);
        for (const MeshSource& m : opt.meshes) {
            run_mesh(m, opt, rows, builds);
            if (!opt.csv.empty()) append_csv(opt, builds.back(), rows);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bvh_vs_embree: %s\n", e.what());
        return 2;
    }

    // Summary tables.
    std::printf(
        "\nTracing, Mrays/s (median of %d passes): luz Bvh8 (8-wide), luz Bvh (binary), Embree "
        "(rtcIntersect1)%s;\nratios luz/Embree; agree = Bvh8 and Embree give the same hit or "
        "miss and the same triangle, or |dt| <= 1e-4 t\n",
        opt.reps, opt.scene ? ", luz scene query nearest_hit()" : "");
    std::printf("%-15s %-12s %8s %3s %7s %7s %7s %s %6s %6s  %s\n", "mesh", "rays", "count", "thr",
                "Bvh8", "Bvh", "embree", opt.scene ? "  scene" : "", "r_Bvh8", "r_Bvh", "agree");
    for (const Row& r : rows) {
        char scene[32] = "";
        if (opt.scene) std::snprintf(scene, sizeof scene, "%7.2f", r.scene);
        std::printf("%-15s %-12s %8zu %3d %7.2f %7.2f %7.2f %s %6.2f %6.2f  %zu/%zu\n",
                    r.mesh.c_str(), r.rays.c_str(), r.count, r.threads, r.luz8, r.luz2, r.embree,
                    scene, r.luz8 / r.embree, r.luz2 / r.embree, r.agreement.agree(), r.count);
    }
    if (opt.scene) {
        std::printf(
            "\nPackets, Mrays/s (same rays, same passes): luz scene = nearest_hit() one ray at a "
            "time, scene8 = nearest_hits() of 8 consecutive rays;\nEmbree rtcIntersect1, "
            "rtcIntersect8 and rtcIntersect16 on 8 or 16 consecutive rays (a row or two of an 8x8 "
            "tile); r_s8 = scene8/embree, r_s8_e8 = scene8/embree8;\ndiffer = rays whose "
            "hit differs from the same engine one ray at a time (must be 0)\n");
        std::printf("%-15s %-12s %8s %3s %7s %7s %7s %7s %8s %6s %7s  %s\n", "mesh", "rays",
                    "count", "thr", "scene", "scene8", "embree", "embree8", "embree16", "r_s8",
                    "r_s8_e8", "differ");
        for (const Row& r : rows) {
            std::printf("%-15s %-12s %8zu %3d %7.2f %7.2f %7.2f %7.2f %8.2f %6.2f %7.2f  %zu/%zu\n",
                        r.mesh.c_str(), r.rays.c_str(), r.count, r.threads, r.scene, r.scene8,
                        r.embree, r.embree8, r.embree16, r.scene8 / r.embree, r.scene8 / r.embree8,
                        r.scene8_differs, r.embree8_differs);
        }
    }
    std::printf(
        "\nBuild, ms (median): luz Bvh = triangle boxes + Bvh::build, Bvh8 = that + collapse; "
        "Embree rtcCommitScene, medium and high quality.\nMemory, bytes per triangle: luz = mesh "
        "vertex and index arrays + nodes + order; scene = mesh arrays + the scene's BVH (nodes, "
        "primitives with vertex copies); Embree = all it allocates (monitor)\n");
    std::printf("%-15s %9s", "mesh", "triangles");
    for (int t : opt.threads) std::printf("   Bvh_%dt  Bvh8_%dt   med_%dt  high_%dt", t, t, t, t);
    std::printf("  Bvh8/med   Bvh_B  Bvh8_B   med_B  high_B%s  leaf\n",
                opt.scene ? " scene_B" : "");
    for (const BuildRow& b : builds) {
        std::printf("%-15s %9zu", b.mesh.c_str(), b.triangles);
        for (size_t i = 0; i < opt.threads.size(); ++i)
            std::printf(" %8.2f %8.2f %8.2f %8.2f", b.luz2_ms[i], b.luz8_ms[i], b.medium_ms[i],
                        b.high_ms[i]);
        std::printf("  %8.2f %7.1f %7.1f %7.1f %7.1f", b.luz8_ms.back() / b.medium_ms.back(),
                    b.luz2_bytes, b.luz8_bytes, b.medium_bytes, b.high_bytes);
        if (opt.scene) std::printf(" %7.1f", b.scene_bytes);
        std::printf("  %4.2f\n", b.leaf);
    }

    // The targets, on the largest thread count: with --scene, the renderer's scene query against
    // Embree's rtcIntersect1 (issue 16: primary >= 1.0, incoherent >= 0.8), one ray at a time
    // and as packets of 8; without it, Bvh8 (the earlier targets: >= 0.7 and >= 0.5). Build <= 2 x
    // Embree's (medium quality), <= 100 bytes per triangle.
    const int t = opt.threads.back();
    const double want_primary = opt.scene ? 1.0 : 0.7, want_incoherent = opt.scene ? 0.8 : 0.5;
    std::printf("\nTargets (%d thread%s; luz = %s):\n", t, t > 1 ? "s" : "",
                opt.scene ? "the scene query, one ray / packets of 8" : "Bvh8");
    const auto verdict = [](bool ok) { return ok ? "met" : "MISSED"; };
    for (const BuildRow& b : builds) {
        double primary = 1e30, incoherent = 1e30, primary8 = 1e30, incoherent8 = 1e30;
        for (const Row& r : rows) {
            if (r.mesh != b.mesh || r.threads != t) continue;
            const bool inc = r.rays == "incoherent";
            double& worst = inc ? incoherent : primary;
            double& worst8 = inc ? incoherent8 : primary8;
            worst = std::min(worst, (opt.scene ? r.scene : r.luz8) / r.embree);
            worst8 = std::min(worst8, r.scene8 / r.embree);
        }
        const double build = b.luz8_ms.back() / b.medium_ms.back();
        // bytes: what the renderer holds (the scene's mesh and BVH) when measured, else Bvh8's
        const double bytes = opt.scene ? b.scene_bytes : b.luz8_bytes;
        char packets[96] = "";
        if (opt.scene) std::snprintf(packets, sizeof packets, " / %.2f", primary8);
        char packets_inc[96] = "";
        if (opt.scene) std::snprintf(packets_inc, sizeof packets_inc, " / %.2f", incoherent8);
        std::printf(
            "  %-15s primary %.2f%s (>= %.1f: %s), incoherent %.2f%s (>= %.1f: %s), build %.2f x "
            "(<= 2: %s), %.1f B/triangle %s(<= 100: %s)\n",
            b.mesh.c_str(), primary, packets, want_primary,
            verdict(std::max(primary, opt.scene ? primary8 : 0.0) >= want_primary), incoherent,
            packets_inc, want_incoherent,
            verdict(std::max(incoherent, opt.scene ? incoherent8 : 0.0) >= want_incoherent), build,
            verdict(build <= 2.0), bytes, opt.scene ? "in the scene " : "",
            verdict(bytes <= 100.0));
    }
    return 0;
}
