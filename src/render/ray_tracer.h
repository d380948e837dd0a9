// The ray tracer of SPEC §1.1: trace(ray, depth) with shadow rays, mirror reflection and
// refraction by Snell's law; raycast is the same code with depth 0 and no shadow rays.
#pragma once

#include <atomic>
#include <cstdint>
#include <utility>
#include <vector>

#include "geometry/scene.h"
#include "geometry/scene_query.h"
#include "image/image.h"
#include "render/aov.h"
#include "render/ray_tree.h"
#include "render/render.h"
#include "render/stats.h"
#include "scene/camera.h"
#include "shading/shade.h"

namespace luz {

/// Rays traced and intersection tests, counted per thread and summed at the end.
struct TraceCounters {
    uint64_t primary = 0, shadow = 0, reflection = 0, refraction = 0;
    IntersectCounters tests;  ///< tests.query_ns: time in scene queries of the timed samples
    uint64_t timed_ns = 0;    ///< total time of the timed samples (every kTimedSampleEvery-th)
};

/// One primary sample in this many is timed whole and in its scene queries, to measure the
/// share of time spent in intersection (RenderStats::intersect_sampled_seconds).
inline constexpr uint64_t kTimedSampleEvery = 256;

/// Rays traced so far (all kinds): the work the samplers' progress counts (render/sampler.h).
inline uint64_t work_of(const TraceCounters& c) {
    return c.primary + c.shadow + c.reflection + c.refraction;
}
inline uint64_t primary_rays_of(const TraceCounters& c) { return c.primary; }

/// A sample tracing more rays than this means an exploding ray tree (the render warns once).
inline constexpr uint64_t kExplodingTreeRays = 4096;

/// The most rays a batch of samples() keeps to trace level by level (RayTracer::trace_trees());
/// the rays spawned beyond are traced depth-first at once, so that a batch's list never holds
/// more than 3·kMaxTreeRays rays (each kept ray spawns two at most): about 0.9 MB a thread.
inline constexpr size_t kMaxTreeRays = 4096;

/// Offset of secondary and shadow ray origins along the geometric normal (SPEC §1.1: ≤ 1e-4).
inline constexpr float kRayEpsilon = 1e-4f;

/// A ray leaving surface point P in direction `dir`, its origin moved by kRayEpsilon along the
/// geometric normal Ng to the side the ray leaves towards (SPEC §1.1), so that a surface never
/// shadows or reflects itself by rounding.
inline Ray spawn_ray(const Vec3& P, const Vec3& Ng, const Vec3& dir) {
    return {P + Ng * (dot(dir, Ng) > 0 ? kRayEpsilon : -kRayEpsilon), dir};
}

/// Mirror direction of unit direction D about unit normal N.
inline Vec3 reflect(const Vec3& D, const Vec3& N) { return D - N * (2 * dot(D, N)); }

/// Refraction of unit direction D at a surface with unit normal N facing D's side
/// (dot(D, N) < 0), from index n1 into n2: n1·sin i = n2·sin r. False on total internal
/// reflection.
bool refract(const Vec3& D, const Vec3& N, float n1, float n2, Vec3& T);

/// The directions of the secondary rays leaving a hit `sp` of a ray in unit direction D
/// (SPEC §1.1). `reflected`: the mirror direction about the normal facing D (two-sided).
/// `refracted` (only when m.transparency > 0): by Snell's law, from the medium around (1.0)
/// into m.ior when the ray enters (D against Ng), from m.ior back to 1.0 when it leaves; on
/// total internal reflection (`tir`) the mirror direction.
struct Bounce {
    Vec3 reflected, refracted;
    bool tir = false;
};
Bounce bounce(const Vec3& D, const SurfacePoint& sp, const Material& m);

/// A camera hit shaded with its packet (RayTracer::shade_hits()).
struct ShadedHit {
    SurfacePoint sp;           ///< surface_at() of the hit
    Rgb local;                 ///< shade() at it
    uint64_t shadow_rays = 0;  ///< the shadow rays shade() traced for it
};

class RayTracer {
  public:
    /// `full`: raytrace (shadow rays, reflection, refraction up to max_depth); otherwise
    /// raycast (the local model with every light visible, no secondary rays).
    RayTracer(const BuiltScene& scene, const Settings& settings, bool full,
              const std::atomic<bool>* cancel = nullptr);

    /// The colour seen along `ray` at ray-tree depth `depth` (SPEC §1.1). `distance` receives
    /// the distance to what the ray hit (infinity on a miss). When `tree` is set, appends this
    /// ray's node and its children's with the numbers used (render/ray_tree.h); normal renders
    /// pass nullptr and record nothing.
    /// Secondary rays weighing less than render.min_weight are not traced (SPEC §2); a
    /// recorded tree stops recording at kRayTreeMaxNodes nodes (RayTree::truncated), the
    /// colour still traced in full. Once `cancel` (if set) is true, every ray returns at once.
    Rgb trace(const Ray& ray, int depth, TraceCounters& counters, float& distance,
              RayTree* tree = nullptr) const;

    /// The colour at pixel-space point (px, py): one primary ray. Every kTimedSampleEvery-th
    /// call (counted in `counters`) is timed (TraceCounters::timed_ns, tests.query_ns).
    Rgb sample(float px, float py, TraceCounters& counters) const;

    /// sample() at (px[k], py[k]) for k < n, into out[k] (the same bits and counts), 64 points
    /// at a time: the camera rays of up to kMaxPacket neighbouring points found as one packet
    /// (nearest_hits()) and their hits shaded side by side (shade_hits()), then the secondary
    /// rays of the 64 ray trees level by level (trace_trees()). When `rays` is set, rays[k]
    /// receives the rays sample k traced, its primary ray included.
    void samples(const float* px, const float* py, int n, TraceCounters& counters, Rgb* out,
                 uint64_t* rays = nullptr) const;

    /// The same sample with its terms (SPEC §1.5), taken from the numbers trace() and shade()
    /// compute at the primary hit; its colour has the bits sample() gives.
    TermSample sample_terms(float px, float py, TraceCounters& counters) const;

    const Camera& camera() const { return camera_; }

  private:
    /// trace() with ray-tree recording (kRecord, `tree` set) or without: the renders' copy
    /// carries none of the recording's branches and state. kTerms: also fills `terms` with this
    /// ray's terms (a primary ray; its children are traced without).
    /// `weight`: the product of the coefficients that scale this ray (1 for a primary ray).
    /// `primary`: the ray's nearest object hit when the caller has found it already (found,
    /// hit), as nearest_hit() gives it.
    template <bool kRecord, bool kTerms = false>
    Rgb trace_impl(const Ray& ray, int depth, float weight, TraceCounters& counters,
                   float& distance, RayTree* tree_in, TermSample* terms = nullptr,
                   const std::pair<bool, Hit>* primary = nullptr) const;

    /// shade() at the hits `which` (bit k: rays[k], hits[k]) of up to eight rays (a packet of
    /// camera rays, or a level's secondary rays in trace_trees()) side by side (shade_lanes();
    /// in raytrace the shadow rays towards each light side by side too, transmittances()),
    /// into out[k]: the bits and counts trace_impl() finds one by one. The
    /// shadow rays are counted in out[k].shadow_rays, for the caller to add sample by sample.
    void shade_hits(const Ray* rays, const Hit* hits, unsigned which, TraceCounters& counters,
                    ShadedHit* out) const;

    /// The colours of the camera hits `packed` of a batch (bit k: rays[k], hits[k], shaded[k],
    /// k < 64) with their secondary rays, into out[k]: the bits and counts trace_impl() gives
    /// each one by one. The trees are traced level by level, the rays of one depth of all the
    /// trees side by side (nearest_hits_scattered(), shade_hits()); a batch's trees of more than
    /// kMaxTreeRays rays go on depth-first. tree_rays[k] receives the rays sample k's secondary
    /// rays traced (theirs and their shadow rays).
    void trace_trees(const Ray* rays, const Hit* hits, const ShadedHit* shaded, uint64_t packed,
                     TraceCounters& counters, Rgb* out, uint64_t* tree_rays) const;

    /// The nearest visible light sphere along ray within (0, t_max), or −1.
    int nearest_light(const Ray& ray, float& t_max, TraceCounters& counters) const;

    const BuiltScene& scene_;
    const Settings& settings_;         ///< camera, lights, materials … of this render
    std::vector<int> visible_lights_;  ///< lights with radius > 0, seen by rays
    Camera camera_;
    Lighting lighting_;
    int max_depth_;
    float min_weight_;
    const std::atomic<bool>* cancel_;
    bool full_;
    bool tree_attenuation_;
};

/// Renders the scene with the raycast or raytrace pipeline into `out` (ray_render.cpp).
void render_ray_traced(const BuiltScene& scene, const Settings& settings,
                       const RenderControl& control, Image& out, RenderStats& stats);
/// The same into rows kept apart (render_rows()): colour only, no terms.
void render_ray_traced(const BuiltScene& scene, const Settings& settings,
                       const RenderControl& control, ImageRows& out, RenderStats& stats);

}  // namespace luz
