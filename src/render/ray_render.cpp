// The raycast and raytrace pipelines: the image in 16×16 tiles rendered in parallel, one
// RayTracer shared by all threads, counters per tile summed in tile order.
#include <algorithm>
#include <atomic>

#include "render/parallel.h"
#include "render/ray_tracer.h"

namespace luz {

namespace {
constexpr int kTileSize = 16;
}  // namespace

void render_ray_traced(const Scene& scene, const RenderControl& control, Image& out,
                       RenderStats& stats) {
    const RayTracer tracer(scene, scene.desc.render.pipeline == Pipeline::raytrace);
    const int w = scene.desc.image.width, h = scene.desc.image.height;
    const int tiles_x = (w + kTileSize - 1) / kTileSize, tiles_y = (h + kTileSize - 1) / kTileSize;
    const size_t tile_count = static_cast<size_t>(tiles_x) * tiles_y;
    std::vector<TraceCounters> counters(tile_count);
    std::atomic<size_t> done{0};
    parallel_items(control.threads, tile_count, [&](size_t t) {
        if (control.cancel && control.cancel->load(std::memory_order_relaxed)) return;
        const int x0 = static_cast<int>(t % tiles_x) * kTileSize;
        const int y0 = static_cast<int>(t / tiles_x) * kTileSize;
        TraceCounters& c = counters[t];
        for (int y = y0; y < std::min(h, y0 + kTileSize); ++y)
            for (int x = x0; x < std::min(w, x0 + kTileSize); ++x)
                out.at(x, y) = tracer.sample(x + 0.5f, y + 0.5f, c);
        if (control.progress) control.progress(static_cast<double>(++done) / tile_count);
    });
    for (const TraceCounters& c : counters) {
        stats.rays_primary += c.primary;
        stats.rays_shadow += c.shadow;
        stats.rays_reflection += c.reflection;
        stats.rays_refraction += c.refraction;
        stats.tests_primitive += c.tests.primitive;
        stats.tests_bounds += c.tests.bounds;
    }
    stats.samples += stats.rays_primary;
}

}  // namespace luz
