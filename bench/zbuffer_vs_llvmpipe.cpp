// Benchmark: luz's zbuffer frame time against Mesa's llvmpipe (OpenGL through OSMesa) on the
// same tessellated torus (~5k, ~100k, ~1M triangles), 1024×1024, orthographic,
// docs/SCENES.md#models phong with one light, per-pixel shading, 1 and 2 threads. Results go to
// docs/BENCHMARKS.md.
//
// llvmpipe reads LP_NUM_THREADS once, when its screen is created (the first context of the
// process), so each llvmpipe thread count runs in its own child process (this program
// re-executed with --llvmpipe-child) started with LP_NUM_THREADS and GALLIUM_DRIVER=llvmpipe
// set. The child builds the same mesh through the same luz code (checked by a hash), then
// renders batches of frames on request, so that luz and llvmpipe batches alternate in one
// timeline: a machine whose speed drifts (a shared virtual machine) slows all alike. At the end
// the child writes its image, and the parent checks that both renderers drew the same picture.
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
#include "render/zbuffer.h"
#include "zbuffer_bench_llvmpipe.h"
#include "zbuffer_bench_workload.h"

namespace {

using namespace luz;
using namespace luz::zbuffer_bench;

// ---------------------------------------------------------------------------------------------
// luz

/// One luz frame of prepared geometry on `threads` threads, into `out`.
std::function<void()> luz_frame(const BuiltScene& scene, const Settings& settings,
                                const ZbufferGeometry& g, int threads, Image& out) {
    return [&scene, &settings, &g, threads, &out] {
        RenderControl control;
        control.threads = threads;
        RenderStats stats;
        render_zbuffer(scene, settings, g, control, out, stats);
    };
}

/// Waits until other processes leave the CPUs nearly idle (< 0.1 core over one second),
/// for at most `max_seconds`; false if they never did.
bool wait_for_idle(double max_seconds) {
    using clock = std::chrono::steady_clock;
    const auto start = clock::now();
    bool said = false;
    for (;;) {
        const double m0 = machine_busy_seconds(), c0 = cpu_seconds();
        const auto t0 = clock::now();
        usleep(1000000);
        const double wall = std::chrono::duration<double>(clock::now() - t0).count();
        const double busy = (machine_busy_seconds() - m0 - (cpu_seconds() - c0)) / wall;
        if (m0 < 0 || busy < 0.1) return true;
        if (std::chrono::duration<double>(clock::now() - start).count() >= max_seconds) {
            std::fprintf(stderr, "  machine still busy (%.2f cores): measuring anyway\n", busy);
            return false;
        }
        if (!said)
            std::fprintf(stderr, "  waiting for an idle machine (%.2f cores busy)...\n", busy);
        said = true;
    }
}

/// Measures configurations side by side: in rounds, one batch of frames of each per round
/// (in an order rotated every round, with a short pause between batches so that idle worker
/// threads go to sleep), until each has at least min_frames frames and min_seconds of frames
/// and there were at least 3 rounds. A first batch of 2 frames warms each up and is not
/// counted. A batch during which other processes took more than 0.15 core is dropped and
/// measured again once the machine is idle.
std::vector<Timing> side_by_side(const std::vector<std::function<Batch(int)>>& configs,
                                 const Options& opt) {
    const size_t n = configs.size();
    std::vector<Series> series(n);
    std::vector<double> estimate_ms(n);
    for (size_t c = 0; c < n; ++c) {
        const Batch warm = configs[c](2);
        estimate_ms[c] = *std::min_element(warm.ms.begin(), warm.ms.end());
    }
    const double batch_seconds = std::max(0.05, opt.min_seconds / 5);
    int dropped = 0;
    for (size_t round = 0;; ++round) {
        bool done = round >= 3;
        for (const Series& s : series)
            done = done && static_cast<int>(s.ms.size()) >= opt.min_frames &&
                   s.seconds >= opt.min_seconds;
        if (done) break;
        for (size_t i = 0; i < n; ++i) {
            const size_t c = (i + round) % n;
            const int k = std::clamp(
                static_cast<int>(std::lround(1000.0 * batch_seconds / estimate_ms[c])), 1, 200);
            usleep(20000);
            const Batch b = configs[c](k);
            if (opt.idle_wait > 0 && b.others > 0.15 && dropped < 50) {
                ++dropped;
                std::fprintf(stderr, "  other processes took %.2f cores: batch dropped\n",
                             b.others);
                wait_for_idle(opt.idle_wait);
                --i;  // the same configuration again
                continue;
            }
            series[c].add(b);
            estimate_ms[c] = series[c].median();
        }
    }
    std::vector<Timing> t;
    for (const Series& s : series) t.push_back(s.timing());
    return t;
}

/// Share of pixels whose 8-bit colours differ by at most `tolerance` in every channel, and
/// the largest difference.
struct Agreement {
    double within = 0;
    int max_diff = 0;
};

Agreement compare(const Image& luz_image, const std::vector<uint8_t>& rgba, int tolerance) {
    Agreement a;
    size_t ok = 0;
    for (size_t i = 0; i < luz_image.pixels.size(); ++i) {
        int worst = 0;
        for (int c = 0; c < 3; ++c) {
            const int v = encode_8bit(luz_image.pixels[i][c], Encoding::linear);
            worst = std::max(worst, std::abs(v - static_cast<int>(rgba[4 * i + c])));
        }
        a.max_diff = std::max(a.max_diff, worst);
        if (worst <= tolerance) ++ok;
    }
    a.within = 100.0 * static_cast<double>(ok) / static_cast<double>(luz_image.pixels.size());
    return a;
}

Image to_image(const std::vector<uint8_t>& rgba) {
    Image img(kWidth, kHeight);
    for (size_t i = 0; i < img.pixels.size(); ++i)
        img.pixels[i] =
            Rgb{rgba[4 * i] / 255.0f, rgba[4 * i + 1] / 255.0f, rgba[4 * i + 2] / 255.0f};
    return img;
}

/// luz frame time split from outside, one thread, by rendering variants of the same mesh:
/// - behind: the camera turned away, every triangle behind it: the per-frame fixed cost
///   (fragment buffers, background fill of 1024² pixels), vertex projection, and the fetch and
///   clip codes of every triangle (all rejected by the camera plane);
/// - offscreen: the torus just outside the image (inside the guard band): + triangle set-up
///   (fixed-point vertices), every triangle then rejected by the binner;
/// - tiny: the view 64× wider, the whole mesh on a few pixels: + binning and the
///   per-triangle part of rasterization (edge functions, bounding box), almost no pixels;
/// - unlit: the benchmark frame with no light: pixels rasterized and shaded with Ia·Ka only;
/// - full: the benchmark frame.
struct Breakdown {
    Timing behind, offscreen, tiny, unlit, full;
};

Breakdown luz_breakdown(int level, const Options& opt) {
    const TorusScene torus = torus_scene(level);
    // The same scene and mesh for every variant; only the settings differ.
    const ZbufferGeometry g = prepare_zbuffer(torus.scene, torus.desc);
    const Settings full = torus.desc;
    Settings behind = full;
    behind.camera.look_at = {0, 0, 20};  // looking along +z from z = 10: torus behind
    Settings offscreen = full;
    offscreen.camera.position.x -= 2.5f * full.camera.view_height;
    offscreen.camera.look_at.x -= 2.5f * full.camera.view_height;
    Settings tiny = full;
    tiny.camera.view_height *= 64.0f;
    Settings unlit = full;
    unlit.lights.clear();
    Image out;
    std::vector<std::function<Batch(int)>> configs;
    for (const Settings* s :
         std::initializer_list<const Settings*>{&behind, &offscreen, &tiny, &unlit, &full})
        configs.push_back(
            [&, s](int k) { return run_batch(luz_frame(torus.scene, *s, g, 1, out), k); });
    const std::vector<Timing> t = side_by_side(configs, opt);
    return {t[0], t[1], t[2], t[3], t[4]};
}

/// One configuration's result on standard error, as it comes.
void report(const char* size, const char* renderer, int threads, const Timing& t) {
    std::fprintf(stderr,
                 "[%s] %s %dt: %.2f ms median of %d frames, cpu %.2f ms/frame, other processes "
                 "%.2f cores%s\n",
                 size, renderer, threads, t.median_ms, t.frames, t.cpu_ms, t.others,
                 t.others > 0.2 ? "  (machine busy: figures unreliable)" : "");
}

void print_usage() {
    std::printf(
        "usage: zbuffer_vs_llvmpipe [--sizes 5k,100k,1M] [--frames N] [--seconds S]\n"
        "                           [--luz-only | --llvmpipe-only] [--no-breakdown]\n"
        "                           [--idle-wait S] [--float-target] [--save DIR]\n"
        "       zbuffer_vs_llvmpipe --profile LEVEL [--threads T] [--frames N]\n"
        "  Times luz's zbuffer and Mesa's llvmpipe (OSMesa) on the same torus at 1024x1024,\n"
        "  1 and 2 threads, in alternating batches (median of >= N frames and >= S seconds of\n"
        "  frames per configuration; defaults 10, 1). Batches during which other processes\n"
        "  used the CPUs are measured again after waiting up to --idle-wait seconds (default\n"
        "  120; 0: never) for an idle machine.\n"
        "  --float-target: llvmpipe renders to RGBA32F instead of RGBA8.\n"
        "  --save DIR: write luz_SIZE.png and llvmpipe_SIZE.png there.\n"
        "  --profile renders N luz frames only (for perf or valgrind --tool=callgrind).\n");
}

int run(int argc, char** argv) {
    Options opt;
    std::string child_image;
    int child_level = 0;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&]() -> std::string {
            if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
            return argv[++i];
        };
        if (a == "--llvmpipe-child") {
            child_level = std::stoi(next());
            child_image = next();
        } else if (a == "--frames") {
            opt.min_frames = opt.profile_frames = std::max(1, std::stoi(next()));
        } else if (a == "--seconds") {
            opt.min_seconds = std::stod(next());
        } else if (a == "--sizes") {
            opt.sizes.clear();
            std::string list = next() + ",";
            for (size_t p = 0, q; (q = list.find(',', p)) != std::string::npos; p = q + 1) {
                const std::string name = list.substr(p, q - p);
                bool found = false;
                for (const BenchSize& s : kSizes)
                    if (name == s.name) opt.sizes.push_back(s), found = true;
                if (!found) throw std::runtime_error("unknown size " + name + " (5k, 100k, 1M)");
            }
        } else if (a == "--luz-only") {
            opt.llvmpipe = false;
        } else if (a == "--llvmpipe-only") {
            opt.luz = false;
        } else if (a == "--idle-wait") {
            opt.idle_wait = std::stod(next());
        } else if (a == "--no-breakdown") {
            opt.breakdown = false;
        } else if (a == "--float-target") {
            opt.float_target = true;
        } else if (a == "--save") {
            opt.save_dir = next();
        } else if (a == "--profile") {
            opt.profile_level = std::stoi(next());
        } else if (a == "--threads") {
            opt.profile_threads = std::stoi(next());
        } else if (a == "--help" || a == "-h") {
            print_usage();
            return 0;
        } else {
            print_usage();
            return 2;
        }
    }
    if (child_level > 0) return llvmpipe_child(child_level, child_image, opt);

    if (opt.profile_level > 0) {  // a few luz frames and nothing else
        const TorusScene torus = torus_scene(opt.profile_level);
        const ZbufferGeometry g = prepare_zbuffer(torus.scene, torus.desc);
        RenderControl control;
        control.threads = opt.profile_threads;
        Image out;
        for (int f = 0; f < opt.profile_frames; ++f) {
            RenderStats stats;
            render_zbuffer(torus.scene, torus.desc, g, control, out, stats);
        }
        std::printf("profiled %d frames of %zu triangles\n", opt.profile_frames,
                    g.mesh.triangle_count());
        return 0;
    }

    std::printf("zbuffer vs llvmpipe: torus, %dx%d, orthographic, phong, 1 light, culling off\n",
                kWidth, kHeight);
    std::printf(
        "median of >= %d frames and >= %.1f s of frames per configuration, configurations\n"
        "measured in alternating batches\n\n",
        opt.min_frames, opt.min_seconds);

    struct Row {
        BenchSize size;
        size_t triangles = 0;
        Timing luz[2], gl[2];
        Agreement agreement;
        Breakdown breakdown;
    };
    std::vector<Row> rows;
    std::string renderer;
    for (const BenchSize& size : opt.sizes) {
        Row row;
        row.size = size;
        const TorusScene torus = torus_scene(size.level);
        const ZbufferGeometry g = prepare_zbuffer(torus.scene, torus.desc);
        row.triangles = g.mesh.triangle_count();
        const uint64_t hash = mesh_hash(g.mesh);
        std::fprintf(stderr, "[%s] level %d: %zu triangles, %zu vertices, mesh hash %016llx\n",
                     size.name, size.level, row.triangles, g.mesh.positions.size(),
                     static_cast<unsigned long long>(hash));
        if (opt.idle_wait > 0) wait_for_idle(opt.idle_wait);

        // The configurations, measured side by side: llvmpipe 1t, 2t (children), luz 1t, 2t.
        std::vector<std::unique_ptr<LlvmpipeChild>> children;
        std::vector<std::function<Batch(int)>> configs;
        Image image;
        if (opt.llvmpipe) {
            for (int t = 1; t <= 2; ++t) {
                children.push_back(
                    std::make_unique<LlvmpipeChild>(size.level, t, opt.float_target));
                LlvmpipeChild& child = *children.back();
                if (child.hash != hash) throw std::runtime_error("llvmpipe child saw another mesh");
                renderer = child.renderer + ", OpenGL " + child.version;
                std::fprintf(stderr, "[%s] llvmpipe child, LP_NUM_THREADS=%d: %d threads in all\n",
                             size.name, t, child.threads_in_process);
                configs.push_back([&child](int k) { return child.frames(k); });
            }
        }
        if (opt.luz) {
            for (int t = 1; t <= 2; ++t)
                configs.push_back([&, t](int k) {
                    return run_batch(luz_frame(torus.scene, torus.desc, g, t, image), k);
                });
        }
        const std::vector<Timing> timings = side_by_side(configs, opt);
        size_t next = 0;
        if (opt.llvmpipe) {
            for (int t = 0; t < 2; ++t) {
                row.gl[t] = timings[next++];
                report(size.name, "llvmpipe", t + 1, row.gl[t]);
            }
        }
        if (opt.luz) {
            for (int t = 0; t < 2; ++t) {
                row.luz[t] = timings[next++];
                report(size.name, "luz", t + 1, row.luz[t]);
            }
        }
        std::vector<uint8_t> gl_image;
        if (opt.llvmpipe) {
            gl_image = children[1]->finish();  // 2 threads
            children[0]->finish();
        }
        if (opt.luz && opt.llvmpipe) row.agreement = compare(image, gl_image, 3);
        if (!opt.save_dir.empty()) {
            if (opt.luz) write_image(opt.save_dir + "/luz_" + size.name + ".png", image);
            if (opt.llvmpipe)
                write_image(opt.save_dir + "/llvmpipe_" + size.name + ".png", to_image(gl_image));
        }
        if (opt.luz && opt.breakdown) row.breakdown = luz_breakdown(size.level, opt);
        rows.push_back(row);
    }

    if (!renderer.empty()) std::printf("llvmpipe: %s\n\n", renderer.c_str());
    std::printf("%-5s %9s %10s %10s %15s %15s %9s\n", "size", "triangles", "luz_1t_ms", "luz_2t_ms",
                "llvmpipe_1t_ms", "llvmpipe_2t_ms", "ratio_2t");
    for (const Row& r : rows) {
        const double ratio = r.luz[1].median_ms > 0 ? r.gl[1].median_ms / r.luz[1].median_ms : 0;
        std::printf("%-5s %9zu %10.2f %10.2f %15.2f %15.2f %9.2f\n", r.size.name, r.triangles,
                    r.luz[0].median_ms, r.luz[1].median_ms, r.gl[0].median_ms, r.gl[1].median_ms,
                    ratio);
    }
    std::printf("(ratio_2t = llvmpipe_2t_ms / luz_2t_ms: > 1 means luz is faster)\n\n");

    auto fps = [](const Timing& t) { return t.median_ms > 0 ? 1000.0 / t.median_ms : 0.0; };
    std::printf("%-5s %10s %10s %15s %15s\n", "size", "luz_1t_fps", "luz_2t_fps", "llvmpipe_1t_fps",
                "llvmpipe_2t_fps");
    for (const Row& r : rows)
        std::printf("%-5s %10.1f %10.1f %15.1f %15.1f\n", r.size.name, fps(r.luz[0]), fps(r.luz[1]),
                    fps(r.gl[0]), fps(r.gl[1]));

    // CPU time per frame over all threads: cpu/wall is how many cores a renderer kept busy;
    // `others` is what other processes used meanwhile (> 0.2 cores: the wall times suffer).
    std::printf("\n%-5s %10s %10s %15s %15s %13s\n", "size", "luz_1t_cpu", "luz_2t_cpu",
                "llvmpipe_1t_cpu", "llvmpipe_2t_cpu", "others_cores");
    for (const Row& r : rows) {
        double others = 0;
        for (const Timing& t : {r.luz[0], r.luz[1], r.gl[0], r.gl[1]})
            others = std::max(others, t.others);
        std::printf("%-5s %10.2f %10.2f %15.2f %15.2f %13.2f\n", r.size.name, r.luz[0].cpu_ms,
                    r.luz[1].cpu_ms, r.gl[0].cpu_ms, r.gl[1].cpu_ms, others);
    }
    std::printf(
        "(CPU ms per frame, all threads of the renderer; others_cores: the most that other\n"
        " processes used during any of the four runs)\n");
    if (opt.luz && opt.llvmpipe) {
        std::printf("\nimage agreement (luz vs llvmpipe 2t, 8-bit): pixels within 3/255\n");
        for (const Row& r : rows)
            std::printf("%-5s %6.2f %%  (max difference %d/255)\n", r.size.name, r.agreement.within,
                        r.agreement.max_diff);
    }
    if (opt.luz && opt.breakdown) {
        std::printf("\nluz frame time by variant of the same mesh, 1 thread, median ms:\n");
        std::printf("%-5s %8s %10s %8s %8s %8s\n", "size", "behind", "offscreen", "tiny", "unlit",
                    "full");
        for (const Row& r : rows) {
            const Breakdown& b = r.breakdown;
            std::printf("%-5s %8.2f %10.2f %8.2f %8.2f %8.2f\n", r.size.name, b.behind.median_ms,
                        b.offscreen.median_ms, b.tiny.median_ms, b.unlit.median_ms,
                        b.full.median_ms);
        }
        std::printf("\nso, ms per frame (differences of medians; noisy when small):\n");
        std::printf("%-5s %14s %10s %16s %12s %11s\n", "size", "fixed+project", "tri_setup",
                    "bin+tri_raster", "pixels", "light_loop");
        for (const Row& r : rows) {
            const Breakdown& b = r.breakdown;
            const double behind = b.behind.median_ms, offscreen = b.offscreen.median_ms,
                         tiny = b.tiny.median_ms, unlit = b.unlit.median_ms,
                         full = b.full.median_ms;
            std::printf("%-5s %14.2f %10.2f %16.2f %12.2f %11.2f\n", r.size.name, behind,
                        offscreen - behind, tiny - offscreen, full - tiny, full - unlit);
        }
        std::printf(
            "(fixed+project = behind: buffers, background fill, vertex projection, clip codes;\n"
            " tri_setup = offscreen - behind; bin+tri_raster = tiny - offscreen;\n"
            " pixels = full - tiny: per-pixel rasterization and shading;\n"
            " light_loop = full - unlit: the lit part of shade())\n");
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "zbuffer_vs_llvmpipe: %s\n", e.what());
        return 1;
    }
}
