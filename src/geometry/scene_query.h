// Ray queries on a whole scene: the nearest hit (camera, reflected and refracted rays) and the
// transmittance of a segment (shadow rays). Every shape is tested, after its bounding box.
#pragma once

#include <cstdint>

#include "geometry/intersect.h"
#include "geometry/scene.h"

namespace luz {

/// Intersection tests counted by the queries (per thread; summed at the end).
struct IntersectCounters {
    uint64_t primitive = 0;  ///< ray–shape tests
    uint64_t bounds = 0;     ///< ray–box tests
};

/// Whether ray r meets box b in (t_min, t_max) (slab test; inv_dir = 1/direction).
bool hit_bounds(const Bounds3& b, const Ray& r, const Vec3& inv_dir, float t_min, float t_max);

/// The nearest hit of r among the scene's shapes in (t_min, t_max); hit.shape is its index.
bool nearest_hit(const Scene& scene, const Ray& r, float t_min, float t_max, Hit& hit,
                 IntersectCounters& counters);

/// The product of `transparency` over every surface r crosses in (t_min, t_max): 1 if none,
/// 0 as soon as an opaque one is met (SPEC §1: vis_j; a closed glass shape counts twice).
float transmittance(const Scene& scene, const Ray& r, float t_min, float t_max,
                    IntersectCounters& counters);

}  // namespace luz
