// What the samplers ask of a colour function: the sample at a pixel-space point, or many at
// once grouped as the colour function chooses, with the cost it reports for progress. The
// samplers know nothing else of how a colour is computed.
#pragma once

#include <type_traits>
#include <utility>

namespace luz {

// A colour function `colour` with counters of type Counters (one per work item) has
//   colour(x, y, c) -> S                 the sample at pixel-space point (x, y): an Rgb colour,
//                                        or a TermSample (its colour and its terms);
// and may have
//   colour.batch(xs, ys, n, c, out)      the samples at (xs[k], ys[k]), k < n, into out[k], at
//     -> double                          once (the ray tracer traces them side by side); returns
//                                        their cost;
//   colour.runs(xs, ys, n, c, out, done) the same samples in runs of its choice, calling
//                                        done(m, cost) once the first m are in out (m rising to
//                                        n), so that costly samples are reported soon.
// A cost is in progress reports' worth: the pixels done are handed over once it adds up to 1
// (render/pixel_progress.h). A colour function without batch() or runs() costs nothing.

/// The type of a colour function's samples.
template <class Colour, class Counters>
using SampleOf =
    std::decay_t<decltype(std::declval<Colour&>()(0.0f, 0.0f, std::declval<Counters&>()))>;

/// The samples at (xs[k], ys[k]) for k < n into out[k], by colour.batch() when the colour
/// function has one, else one by one; returns their cost.
template <class Colour, class Counters, class S>
double sample_points(Colour& colour, const float* xs, const float* ys, int n, Counters& c, S* out) {
    if constexpr (requires { colour.batch(xs, ys, n, c, out); }) {
        return colour.batch(xs, ys, n, c, out);
    } else {
        for (int k = 0; k < n; ++k) out[k] = colour(xs[k], ys[k], c);
        return 0.0;
    }
}

/// The samples at (xs[k], ys[k]) for k < n into out[k], by colour.runs() when the colour
/// function has one, else one by one; done(m, cost) once the first m are in out.
template <class Colour, class Counters, class S, class Done>
void sample_runs(Colour& colour, const float* xs, const float* ys, int n, Counters& c, S* out,
                 Done&& done) {
    if constexpr (requires { colour.runs(xs, ys, n, c, out, done); }) {
        colour.runs(xs, ys, n, c, out, done);
    } else {
        for (int k = 0; k < n; ++k) {
            out[k] = colour(xs[k], ys[k], c);
            done(k + 1, 0.0);
        }
    }
}

}  // namespace luz
