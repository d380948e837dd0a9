// The ray tracer as the samplers' colour function (render/colour_function.h): samples by the
// batch engine in batches it traces side by side, or one at a time by the reference; their cost
// in rays for progress; and the rays of each sample for the exploding-tree warning.
#pragma once

#include <algorithm>
#include <cstdint>
#include <type_traits>

#include "render/batch_tracer.h"
#include "render/whitted.h"

namespace luz {

/// Samples the batch engine traces together when it is handed a tile's pixels
/// (BatchTracer::samples(): their ray trees level by level, side by side).
inline constexpr int kRaysRun = 64;
/// The rays a sample takes on average above which the samples after it are traced one at a
/// time, so that progress moves pixel by pixel even when one takes seconds (an exploding ray
/// tree); a run's first sample is traced alone to find out.
inline constexpr uint64_t kHeavySampleRays = 4096;
/// The rays worth one progress report (the cost unit of render/colour_function.h).
inline constexpr uint64_t kRaysPerReport = 2048;

/// A colour function over the ray tracer: `one(x, y, counters)` is one sample by the reference
/// (Whitted::sample() or sample_terms()); `engine`, if set, traces Rgb samples in batches;
/// `watch(rays)` is told the rays of every sample.
template <class One, class Watch>
struct RayColour {
    One one;
    const BatchTracer* engine;  ///< null: the reference, one sample at a time
    const Watch& watch;

    using Sample = std::decay_t<decltype(one(0.0f, 0.0f, std::declval<TraceCounters&>()))>;

    Sample operator()(float x, float y, TraceCounters& c) const {
        Sample s;
        batch(&x, &y, 1, c, &s);
        return s;
    }

    double batch(const float* xs, const float* ys, int n, TraceCounters& c, Sample* out) const {
        const uint64_t before = work_of(c);
        if constexpr (std::is_same_v<Sample, Rgb>) {
            if (engine) {
                uint64_t rays[kRaysRun];
                for (int first = 0; first < n; first += kRaysRun) {
                    const int m = std::min(kRaysRun, n - first);
                    engine->samples(xs + first, ys + first, m, c, out + first, rays);
                    for (int k = 0; k < m; ++k) watch(rays[k]);
                }
                return static_cast<double>(work_of(c) - before) / kRaysPerReport;
            }
        }
        for (int k = 0; k < n; ++k) {
            const uint64_t start = work_of(c);
            out[k] = one(xs[k], ys[k], c);
            watch(work_of(c) - start);
        }
        return static_cast<double>(work_of(c) - before) / kRaysPerReport;
    }

    /// kRaysRun samples at a time, the first alone, and one at a time after heavy ones.
    template <class Done>
    void runs(const float* xs, const float* ys, int n, TraceCounters& c, Sample* out,
              Done&& done) const {
        for (int first = 0, size = 1, m; first < n; first += m) {
            m = std::min(size, n - first);
            const uint64_t before = work_of(c);
            batch(xs + first, ys + first, m, c, out + first);
            const uint64_t rays = work_of(c) - before;
            done(first + m, static_cast<double>(rays) / kRaysPerReport);
            size = rays >= kHeavySampleRays * static_cast<uint64_t>(m) ? 1 : kRaysRun;
        }
    }
};
// Spelled out for compilers without C++20's deduction for aggregates (the web build's Clang).
template <class One, class Watch>
RayColour(One, const BatchTracer*, const Watch&) -> RayColour<One, Watch>;

}  // namespace luz
