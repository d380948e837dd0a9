// The raycast and raytrace pipelines as a whole render: the sampler asks the engine for the
// colour of each sample (render/ray_render.cpp).
#pragma once

#include "geometry/scene.h"
#include "image/image.h"
#include "render/aov.h"
#include "render/render.h"
#include "render/stats.h"

namespace luz {

/// Renders the scene with the raycast or raytrace pipeline into `out`.
void render_ray_traced(const BuiltScene& scene, const Settings& settings,
                       const RenderControl& control, Image& out, RenderStats& stats);
/// The same into rows kept apart (render_rows()): colour only, no terms.
void render_ray_traced(const BuiltScene& scene, const Settings& settings,
                       const RenderControl& control, ImageRows& out, RenderStats& stats);

}  // namespace luz
