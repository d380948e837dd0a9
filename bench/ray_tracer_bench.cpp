// The ray tracer in process (Google Benchmark): demo:whitted through raytrace and raycast on
// one thread, without process start-up, page faults of a fresh image or PNG encoding, so that
// changes to the tracing code can be compared at a few per cent. Counters: rays per second
// by kind. The whole-process comparison with POV-Ray is bench/whitted_vs_povray.sh.
//
//     cmake --preset native && cmake --build --preset native --target ray_tracer_bench
//     build/native/bench/ray_tracer_bench --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include "render/render.h"
#include "scene/scene_loader.h"

namespace {

using namespace luz;

void trace_whitted(benchmark::State& state, const char* pipeline) {
    const int width = static_cast<int>(state.range(0)), height = width * 3 / 4;
    const SceneDesc desc =
        load_scene("demo:whitted", {{"render.pipeline", std::string("\"") + pipeline + "\""},
                                    {"image.width", std::to_string(width)},
                                    {"image.height", std::to_string(height)}});
    const BuiltScene scene = build_scene(desc);
    RenderControl control;
    control.threads = 1;
    RenderStats total;
    for (auto _ : state) {
        RenderStats stats;
        const Image image = render(scene, desc, control, stats);
        benchmark::DoNotOptimize(image.pixels.data());
        total.rays_primary += stats.rays_primary;
        total.rays_shadow += stats.rays_shadow;
        total.rays_reflection += stats.rays_reflection;
        total.rays_refraction += stats.rays_refraction;
    }
    const auto rate = benchmark::Counter::kIsRate;
    state.counters["primary/s"] = benchmark::Counter(double(total.rays_primary), rate);
    state.counters["shadow/s"] = benchmark::Counter(double(total.rays_shadow), rate);
    state.counters["secondary/s"] =
        benchmark::Counter(double(total.rays_reflection + total.rays_refraction), rate);
    state.counters["rays/s"] =
        benchmark::Counter(double(total.rays_primary + total.rays_shadow + total.rays_reflection +
                                  total.rays_refraction),
                           rate);
}

void BM_WhittedRaytrace(benchmark::State& state) { trace_whitted(state, "raytrace"); }
void BM_WhittedRaycast(benchmark::State& state) { trace_whitted(state, "raycast"); }

BENCHMARK(BM_WhittedRaytrace)->Arg(800)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_WhittedRaycast)->Arg(800)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
