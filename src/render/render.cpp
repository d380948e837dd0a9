// render(): dispatches a runtime scene to the pipeline its settings name.
#include "render/render.h"

#include <algorithm>
#include <chrono>

#include "render/parallel.h"
#include "render/ray_render.h"
#include "render/zbuffer.h"

namespace luz {

namespace {

/// What every render reports of its image and threads.
void set_image_stats(const Settings& settings, const RenderControl& control, RenderStats& stats) {
    stats.width = settings.image.width;
    stats.height = settings.image.height;
    stats.threads = resolve_threads(control.threads);
}

/// What a ray-traced render reports of the BVH (only rays use it: a zbuffer render reports
/// none, even when an earlier ray-traced render of the same scene built one, and never reads it
/// while another builds it).
void set_bvh_stats(const BuiltScene& scene, RenderStats& stats) {
    stats.bvh_nodes = scene.bvh.nodes().size();
    stats.bvh_build_seconds = scene.bvh_build_seconds;
    stats.bvh_bytes = scene.bvh_bytes();
}

}  // namespace

Image render(const BuiltScene& scene, const Settings& settings, const RenderControl& control,
             RenderStats& stats) {
    const auto start = std::chrono::steady_clock::now();
    const ImageDesc& img = settings.image;
    set_image_stats(settings, control, stats);
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
            stats.triangles += scene.mesh_triangles;  // raytrace: triangles in meshes (docs/CLI.md)
            break;
    }
    if (settings.render.pipeline != Pipeline::zbuffer) set_bvh_stats(scene, stats);
    stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

bool renders_in_rows(const Settings& settings, const RenderControl& control) {
    const AntialiasDesc& aa = settings.render.antialias;
    return settings.render.pipeline != Pipeline::zbuffer &&
           (aa.mode == AaMode::none || (aa.mode == AaMode::grid && aa.filter == AaFilter::box)) &&
           !(control.terms && control.terms->any()) && !control.aa_mask && !control.checkpoint &&
           control.region.empty() && !control.share;
}

void render_rows(const BuiltScene& scene, const Settings& settings, const RenderControl& control,
                 int y0, int count, Image& rows, RenderStats& stats) {
    set_image_stats(settings, control, stats);
    RenderControl band = control;
    band.region = {0, y0, settings.image.width, y0 + count};
    ImageRows out{rows, y0};
    render_ray_traced(scene, settings, band, out, stats);
    stats.triangles = scene.mesh_triangles;  // as render() reports them
    set_bvh_stats(scene, stats);
}

}  // namespace luz
