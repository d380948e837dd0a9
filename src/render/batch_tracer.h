// The fast engine of the ray pipelines: trace() of render/whitted.h for 64 samples at a time,
// the camera rays of neighbouring samples found as packets and shaded in SIMD lanes with their
// shadow rays, then the ray trees level by level, each level's rays side by side.
// It must equal Whitted::sample() sample by sample: the same colour bits and the same rays by
// kind (tests/render/ray_tracer_test.cpp, Pipelines.*); its intersection-test counts are its own.
#pragma once

#include <cstdint>

#include "render/whitted.h"

namespace luz {

/// A camera hit shaded with its packet (BatchTracer::shade_hits()).
struct ShadedHit {
    SurfacePoint sp;           ///< surface_at() of the hit
    Rgb local;                 ///< shade() at it
    uint64_t shadow_rays = 0;  ///< the shadow rays shade() traced for it
};

/// The most rays a batch keeps to trace level by level (BatchTracer::trace_trees()); the rays
/// spawned beyond are traced depth-first at once by the reference, so that a batch's list never
/// holds more than 3·kMaxTreeRays rays (each kept ray spawns two at most).
inline constexpr size_t kMaxTreeRays = 4096;

class BatchTracer {
  public:
    explicit BatchTracer(const Whitted& reference) : ref_(reference) {}

    /// Whitted::sample() at (px[k], py[k]) for k < n, into out[k], 64 points at a time. When
    /// `rays` is set, rays[k] receives the rays sample k traced, its camera ray included.
    /// A batch holding a sample counted 0 modulo kTimedSampleEvery is timed whole and in its
    /// scene queries (TraceCounters::timed_ns, tests.query_ns).
    void samples(const float* px, const float* py, int n, TraceCounters& counters, Rgb* out,
                 uint64_t* rays = nullptr) const;

  private:
    /// shade() at the hits `which` (bit k: rays[k], hits[k]) of up to eight rays side by side
    /// (shade_lanes(); in raytrace their shadow rays towards each light side by side too), into
    /// out[k]; the shadow rays are counted in out[k].shadow_rays. `coherent`: the hits of a
    /// camera packet or of secondary rays going one way, whose shadow rays towards a light may
    /// go down the BVH as one packet.
    void shade_hits(const Ray* rays, const Hit* hits, unsigned which, bool coherent, bool timed,
                    TraceCounters& counters, ShadedHit* out) const;

    /// The colours of the camera hits `packed` of a batch (bit k: rays[k], hits[k], shaded[k])
    /// with their secondary rays, into out[k]: the rays of one depth of all the trees side by
    /// side. tree_rays[k] receives the rays sample k's secondary rays traced.
    void trace_trees(const Ray* rays, const Hit* hits, const ShadedHit* shaded, uint64_t packed,
                     bool timed, TraceCounters& counters, Rgb* out, uint64_t* tree_rays) const;

    const Whitted& ref_;
};

}  // namespace luz
