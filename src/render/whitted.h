// The lecture's ray tracer (docs/SCENES.md#ray-tracing): trace(ray, depth) with shadow rays, mirror
// reflection and refraction by Snell's law, in whitted.cpp on one screen. It is the reference: the
// batch engine (render/batch_tracer.h) gives its bits. raycast is the same code with depth 0 and no
// shadow rays. What the viewer's ray tree and the per-term images need, they get by observing
// trace() (an Observer: NoObserver, RayTreeRecorder in ray_tree.h, TermRecorder in aov.h).
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "geometry/scene.h"
#include "geometry/scene_query.h"
#include "render/aov.h"
#include "render/ray_tree.h"
#include "render/recursion.h"
#include "scene/camera.h"
#include "shading/shade.h"

namespace luz {

/// Rays traced and intersection tests, counted per thread and summed at the end.
struct TraceCounters {
    uint64_t primary = 0, shadow = 0, reflection = 0, refraction = 0;
    IntersectCounters tests;  ///< tests.query_ns: time in scene queries of the timed samples
    uint64_t timed_ns = 0;    ///< total time of the timed samples (1 in kTimedSampleEvery)
};

/// One primary sample in this many is timed whole and in its scene queries, to measure the
/// share of time spent in intersection (RenderStats::intersect_sampled_seconds).
inline constexpr uint64_t kTimedSampleEvery = 256;

/// Rays traced so far (all kinds): the cost RayColour reports to the samplers
/// (render/ray_colour.h).
inline uint64_t work_of(const TraceCounters& c) {
    return c.primary + c.shadow + c.reflection + c.refraction;
}

/// A sample tracing more rays than this means an exploding ray tree (the render warns once).
inline constexpr uint64_t kExplodingTreeRays = 4096;

/// The observer of a render: sees nothing, costs nothing. An observer is told, ray by ray, in
/// trace()'s order: ray() when a ray starts; found() what it met; terms() may give shade() a
/// place for its terms; shaded() the local model at an object hit; bounced() the directions of
/// its secondary rays; secondary() each traced child's colour, A and contribution (after the
/// child's own events); done() the ray's colour, which it returns.
struct NoObserver {
    void ray(const Ray&, int) {}
    void found(float, RayHit, int) {}
    ShadeTerms* terms() { return nullptr; }
    void shaded(const Hit&, int, const SurfacePoint&, const ShadeTerms*, const Rgb&) {}
    void bounced(const Bounce&) {}
    void secondary(RayKind, float, const Rgb&, float, const Rgb&) {}
    Rgb done(const Rgb& c) { return c; }
};

/// The reference ray tracer of one render: trace() and the samples built on it.
class Whitted {
  public:
    /// `full`: raytrace (shadow rays, reflection, refraction up to max_depth); otherwise
    /// raycast (the local model with every light visible, no secondary rays). Once `cancel`
    /// (if set) is true, every ray returns black at once.
    Whitted(const BuiltScene& scene, const Settings& settings, bool full,
            const std::atomic<bool>* cancel = nullptr);

    /// The colour seen along `ray` at ray-tree depth `depth` (docs/SCENES.md#ray-tracing); `weight`
    /// is the product of the coefficients that scale it (1 for a camera ray, for min_weight).
    /// `distance` receives the distance to what the ray hit (infinity on a miss).
    template <class Observer = NoObserver>
    Rgb trace(const Ray& ray, int depth, float weight, TraceCounters& counters, float& distance,
              Observer& seen) const;
    Rgb trace(const Ray& ray, int depth, TraceCounters& counters, float& distance) const {
        NoObserver none;
        return trace(ray, depth, 1.0f, counters, distance, none);
    }

    /// The colour at pixel-space point (px, py): one camera ray. One call in kTimedSampleEvery
    /// (counted in `counters`) is timed (TraceCounters::timed_ns, tests.query_ns).
    Rgb sample(float px, float py, TraceCounters& counters) const;
    /// The same sample with its terms (docs/SCENES.md#terms), observed at the primary hit.
    TermSample sample_terms(float px, float py, TraceCounters& counters) const;

    /// The nearest visible light sphere along ray within (0, t_max), or −1; t_max becomes its
    /// distance.
    int nearest_light(const Ray& ray, float& t_max, TraceCounters& counters) const {
        return visible_lights_.empty() ? -1 : nearest_light_sphere(ray, t_max, counters);
    }

    const BuiltScene& scene() const { return scene_; }
    const Settings& settings() const { return settings_; }
    const Camera& camera() const { return camera_; }
    const Lighting& lighting() const { return lighting_; }
    const TreeRules& rules() const { return rules_; }
    bool full() const { return full_; }
    bool sees_lights() const { return !visible_lights_.empty(); }
    bool cancelled() const { return cancel_ && cancel_->load(std::memory_order_relaxed); }

  private:
    /// The local model at sp seen from S (shade()), with shadow rays in raytrace.
    Rgb local(const SurfacePoint& sp, const Vec3& S, const Material& m, TraceCounters& counters,
              ShadeTerms* terms) const;
    int nearest_light_sphere(const Ray& ray, float& t_max, TraceCounters& counters) const;
    template <class Observer>
    Rgb secondary(RayKind kind, const Ray& ray, float coefficient, int depth, float weight,
                  TraceCounters& counters, Observer& seen) const;

    const BuiltScene& scene_;
    const Settings& settings_;
    std::vector<int> visible_lights_;  ///< lights with radius > 0, seen by rays
    Camera camera_;
    Lighting lighting_;
    TreeRules rules_;
    const std::atomic<bool>* cancel_;
    bool full_;
};

}  // namespace luz
