// No antialiasing (docs/SCENES.md#antialiasing): one sample at the centre of each pixel.
#pragma once

#include <vector>

#include "render/aov.h"
#include "render/colour_function.h"
#include "render/tiles.h"

namespace luz {

/// The pixels of `tile` without antialiasing, into `out`: their centres asked of `colour` as
/// one run of samples in row order (sample_runs(): the colour function groups them), each
/// pixel put and counted as its sample is done. `work` is the tile's counters, counts and
/// progress (render/tile_store.h).
template <class Colour, class Work, class Out>
void sample_tile_none(const PixelRect& tile, Colour& colour, Work& work, Out& out) {
    using S = SampleOf<Colour, decltype(work.counters)>;
    constexpr int kMost = kSamplerTile * kSamplerTile;
    const int w = tile.width(), n = w * tile.height();
    float xs[kMost], ys[kMost];
    for (int k = 0; k < n; ++k) {
        xs[k] = (tile.x0 + k % w) + 0.5f;
        ys[k] = (tile.y0 + k / w) + 0.5f;
    }
    thread_local std::vector<S> got(kMost);
    int done = 0;
    sample_runs(colour, xs, ys, n, work.counters, got.data(), [&](int m, double cost) {
        work.progress.cost(cost);
        for (; done < m; ++done) {
            put(out, tile.x0 + done % w, tile.y0 + done / w, got[done]);
            work.progress.pixel();
        }
    });
    work.counts.samples += static_cast<uint64_t>(n);
}

}  // namespace luz
