// render(): dispatches a runtime scene to the pipeline its settings name.
#include "render/render.h"

#include <algorithm>
#include <chrono>

#include "render/parallel.h"
#include "render/ray_tracer.h"
#include "render/zbuffer.h"

namespace luz {

Image render(const BuiltScene& scene, const Settings& settings, const RenderControl& control,
             RenderStats& stats) {
    const auto start = std::chrono::steady_clock::now();
    const ImageDesc& img = settings.image;
    stats.width = img.width;
    stats.height = img.height;
    stats.threads = resolve_threads(control.threads);
    Image out;
    switch (settings.render.pipeline) {
        case Pipeline::zbuffer: {
            out = Image(img.width, img.height, img.background);  // what no triangle covers
            const ZbufferGeometry geometry = prepare_zbuffer(scene, settings);
            render_zbuffer(scene, settings, geometry, control, out, stats);
            break;
        }
        case Pipeline::raycast:
        case Pipeline::raytrace:
            // Every pixel is written by the sampler: the memory is first touched there, by all
            // threads, instead of being filled here by one.
            out = Image(img.width, img.height, Unwritten{});
            render_ray_traced(scene, settings, control, out, stats);
            if (control.cancel && control.cancel->load()) {  // incomplete: no unwritten pixel
                // On every core, whatever the render's thread count: most of these pages are
                // touched for the first time here (0.15 s a core for 92 MB), and an interrupted
                // render has a second to keep its checkpoint before mpirun kills it.
                const size_t rows = static_cast<size_t>(img.height);
                parallel_items(0, rows, [&](size_t y) {
                    const auto row =
                        out.pixels.begin() + static_cast<std::ptrdiff_t>(y * img.width);
                    std::fill(row, row + img.width, img.background);
                });
            }
            stats.triangles += scene.mesh_triangles;  // raytrace: triangles in meshes (SPEC §3)
            break;
    }
    if (settings.render.pipeline != Pipeline::zbuffer) {
        // Only rays use the BVH: a zbuffer render reports none, even when an earlier ray-traced
        // render of the same scene built one (and never reads it while another builds it).
        stats.bvh_nodes = scene.bvh.nodes().size();
        stats.bvh_build_seconds = scene.bvh_build_seconds;
        stats.bvh_bytes = scene.bvh_bytes();
    }
    stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

}  // namespace luz
