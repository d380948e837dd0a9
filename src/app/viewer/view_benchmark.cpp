// `luz view --benchmark`: how fast the viewer's preview refines, and how fast it cancels.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>
#include <vector>

#include "app/viewer/render_worker.h"
#include "app/viewer/viewer.h"
#include "luz/luz.h"

namespace luz {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

int run_view_benchmark(const ViewOptions& o) {
    std::vector<Override> overrides;
    for (const std::string& s : o.sets) overrides.push_back(parse_set(s));
    if (o.width > 0) overrides.push_back({"image.width", std::to_string(o.width), "--width"});
    if (o.height > 0) overrides.push_back({"image.height", std::to_string(o.height), "--height"});
    SceneDesc desc = load_scene(o.scene, overrides);
    const int threads = render_threads(o.threads);
    std::printf("scene %s  %dx%d  %d threads\n", o.scene.c_str(), desc.image.width,
                desc.image.height, threads);

    // Building the scene: what an edit of the objects, tessellation or accel costs before its
    // first pass (other edits reuse the built scene).
    double build_seconds = 0;
    int builds = 0;
    {
        const auto start = std::chrono::steady_clock::now();
        while (builds < 3 || (seconds_since(start) < 0.5 && builds < 1000)) {
            const Scene s = build(desc);
            s.prepare(desc.render.pipeline);
            ++builds;
        }
        build_seconds = seconds_since(start) / builds;
    }
    std::printf("scene build   %8.2f ms  (objects, tessellation or accel edited)\n",
                build_seconds * 1e3);

    // Each pass alone, repeated for at least half a second, on the built scene: as after an
    // edit of a light, material, camera or render setting.
    const Scene scene = build(desc);
    scene.prepare(desc.render.pipeline);
    const std::vector<PassPlan> plan = plan_passes(desc);
    double all_passes = 0;
    for (const PassPlan& p : plan) {
        int frames = 0;
        const auto start = std::chrono::steady_clock::now();
        while (frames < 3 || (seconds_since(start) < 0.5 && frames < 1000)) {
            RenderFrame f;
            render_pass(scene, desc, p, threads, nullptr, f);
            ++frames;
        }
        const double t = seconds_since(start) / frames;
        all_passes += t;
        std::printf("pass 1/%d%s  %4dx%-4d  %8.2f ms  %7.1f fps\n", p.divisor,
                    p.antialiased ? " + AA" : "     ", desc.image.width / p.divisor,
                    desc.image.height / p.divisor, t * 1e3, 1 / t);
    }
    std::printf("all passes    %8.2f ms\n", all_passes * 1e3);

    // Cancel latency: an edit arrives while the full-resolution pass renders.
    RenderWorker worker(threads);
    std::vector<double> latencies;
    for (int i = 0; i < 10; ++i) {
        worker.submit(scene, desc);
        std::this_thread::sleep_for(std::chrono::milliseconds(20 + 7 * i));
        const int before = worker.cancelled();
        worker.submit(scene, desc);
        const auto start = std::chrono::steady_clock::now();
        // Until the render under way stops (or the worker finds there was none to stop).
        while (worker.cancelled() == before && !worker.done() && seconds_since(start) < 5)
            std::this_thread::sleep_for(std::chrono::microseconds(100));
        if (worker.cancelled() != before) latencies.push_back(worker.last_cancel_latency());
        while (!worker.done() && seconds_since(start) < 30)
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    std::sort(latencies.begin(), latencies.end());
    if (!latencies.empty()) {
        std::printf("cancel latency  median %.2f ms  max %.2f ms  (%zu edits during a render)\n",
                    latencies[latencies.size() / 2] * 1e3, latencies.back() * 1e3,
                    latencies.size());
    } else {
        std::printf(
            "cancel latency  not measured: every render ended before its edit came (a "
            "larger image gives an edit a render to cancel)\n");
    }
    return 0;
}

}  // namespace luz
