// The raycast and raytrace pipelines: one RayTracer shared by all threads, asked for the colour
// at each sample point by the antialiasing sampler (render/sampler.h), which renders the image
// in tiles in parallel; counters per tile summed in tile order.
#include <algorithm>

#include "render/ray_tracer.h"
#include "render/sampler.h"

namespace luz {

void render_ray_traced(const BuiltScene& scene, const Settings& settings,
                       const RenderControl& control, Image& out, RenderStats& stats) {
    const RayTracer tracer(scene, settings, settings.render.pipeline == Pipeline::raytrace);
    const int w = settings.image.width, h = settings.image.height;
    std::vector<TraceCounters> counters;
    SamplerCounts counts;
    if (control.terms && control.terms->any()) {  // the colour and its terms (SPEC §1.5)
        TermOut term_out{out, *control.terms};
        counts = sample_image(
            settings.render.antialias, w, h, control,
            [&tracer](float x, float y, TraceCounters& c) { return tracer.sample_terms(x, y, c); },
            term_out, counters, control.aa_mask);
    } else {
        counts = sample_image(
            settings.render.antialias, w, h, control,
            [&tracer](float x, float y, TraceCounters& c) { return tracer.sample(x, y, c); }, out,
            counters, control.aa_mask);
    }
    for (const TraceCounters& c : counters) {
        stats.rays_primary += c.primary;
        stats.rays_shadow += c.shadow;
        stats.rays_reflection += c.reflection;
        stats.rays_refraction += c.refraction;
        stats.tests_primitive += c.tests.primitive;
        stats.tests_bounds += c.tests.bounds;
        stats.intersect_sampled_seconds += c.tests.query_ns * 1e-9;
        stats.sampled_seconds += c.timed_ns * 1e-9;
    }
    stats.samples += counts.samples;  // one primary ray per sample
    stats.pixels_refined += counts.pixels_refined;
}

}  // namespace luz
