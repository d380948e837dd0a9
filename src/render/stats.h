// RenderStats is a public type (include/luz/stats.h): the layers use it from there, and add the
// counters of threads and frames with add_counters().
#pragma once

#include "luz/stats.h"

namespace luz {

/// Adds another thread's counters to `into` (times and sizes are not summed).
inline void add_counters(RenderStats& into, const RenderStats& o) {
    into.rays_primary += o.rays_primary;
    into.rays_shadow += o.rays_shadow;
    into.rays_reflection += o.rays_reflection;
    into.rays_refraction += o.rays_refraction;
    into.tests_primitive += o.tests_primitive;
    into.tests_bounds += o.tests_bounds;
    into.pixels_refined += o.pixels_refined;
    into.samples += o.samples;
    into.triangles += o.triangles;
}

}  // namespace luz
