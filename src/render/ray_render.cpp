// The raycast and raytrace pipelines: one engine shared by all threads, asked for the colour at
// each sample point by the antialiasing sampler (render/sampler.h), which renders the image in
// tiles in parallel, through RayColour (render/ray_colour.h); counters per tile summed in tile
// order. The reference (Whitted) observed by a TermRecorder gives the per-term images;
// otherwise the batch engine gives the colour.
#include "render/ray_render.h"

#include <algorithm>
#include <atomic>
#include <string>
#include <type_traits>

#include "render/batch_tracer.h"
#include "render/ray_colour.h"
#include "render/sampler.h"

namespace luz {

namespace {

Image& image_of(Image& out) { return out; }
Image& image_of(ImageRows& out) { return out.rows; }  // not called: ImageRows takes no terms

/// render_ray_traced() into an Image (with the terms when asked) or into ImageRows.
template <class Out>
void render_into(const BuiltScene& scene, const Settings& settings, const RenderControl& control,
                 Out& out, RenderStats& stats) {
    const Whitted tracer(scene, settings, settings.render.pipeline == Pipeline::raytrace,
                         control.cancel);
    const BatchTracer batch(tracer);
    const int w = settings.image.width, h = settings.image.height;
    // An exploding ray tree (2^depth rays a sample on reflective and transparent surfaces):
    // said once, when a sample traces more than kExplodingTreeRays rays and min_weight is 0.
    std::atomic<bool> warned{false};
    const bool watch = control.warning && settings.render.min_weight == 0;
    const auto warn = [&](uint64_t rays) {  // apart: the check below is inlined for every sample
        if (warned.exchange(true)) return;
        control.warning("a sample traced " + std::to_string(rays) +
                        " rays: the ray tree grows as 2^depth on reflective and transparent "
                        "surfaces (render.max_depth " +
                        std::to_string(settings.render.max_depth) +
                        "); render.min_weight (e.g. --set render.min_weight=0.01) stops rays "
                        "that weigh little, or lower render.max_depth");
    };
    auto watch_rays = [&](uint64_t rays) {
        if (watch && rays > kExplodingTreeRays) [[unlikely]]
            warn(rays);
    };
    std::vector<TraceCounters> counters;
    SamplerCounts counts;
    const AntialiasDesc& aa = settings.render.antialias;
    constexpr bool kWhole = std::is_same_v<Out, Image>;  // ImageRows: colour only
    if (kWhole && control.terms &&
        control.terms->any()) {  // the colour and its terms (docs/SCENES.md#terms)
        // One sample at a time: each sample's `tests` term counts its own tests.
        TermOut term_out{image_of(out), *control.terms};
        const RayColour colour{
            [&](float x, float y, TraceCounters& c) { return tracer.sample_terms(x, y, c); },
            nullptr, watch_rays};
        counts = sample_image(aa, w, h, control, colour, term_out, counters, control.aa_mask);
    } else {
        // The colour, by one engine for the whole render: the batch engine, or the reference
        // where the sampler asks for one point at a time (adaptive antialiasing). The same bits
        // either way.
        const BatchTracer* engine = aa.mode == AaMode::adaptive ? nullptr : &batch;
        const RayColour colour{
            [&](float x, float y, TraceCounters& c) { return tracer.sample(x, y, c); }, engine,
            watch_rays};
        counts = sample_image(aa, w, h, control, colour, out, counters, control.aa_mask);
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

}  // namespace

void render_ray_traced(const BuiltScene& scene, const Settings& settings,
                       const RenderControl& control, Image& out, RenderStats& stats) {
    render_into(scene, settings, control, out, stats);
}

void render_ray_traced(const BuiltScene& scene, const Settings& settings,
                       const RenderControl& control, ImageRows& out, RenderStats& stats) {
    render_into(scene, settings, control, out, stats);
}

}  // namespace luz
