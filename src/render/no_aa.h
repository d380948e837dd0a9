// No antialiasing (docs/SCENES.md#antialiasing): one sample at the centre of each pixel.
#pragma once

#include <vector>

#include "render/aov.h"
#include "render/colour_function.h"
#include "render/tiles.h"

namespace luz {

/// The pixels of a w × h tile (w, h ≤ kSamplerTile) in the order they are sampled, as offsets
/// (dx[k], dy[k]): 8 × 8 blocks (a batch of the fast engine's 64 samples), each as eight 4 × 2
/// packets (the camera rays it finds together), pixels in row order within them — footprints
/// more compact than rows, whose rays, shadow rays and ray trees keep closer together. Returns
/// their number, w·h.
inline int tile_order(int w, int h, int* dx, int* dy) {
    int n = 0;
    for (int by = 0; by < kSamplerTile; by += 8)
        for (int bx = 0; bx < kSamplerTile; bx += 8)
            for (int py = by; py < by + 8; py += 2)
                for (int px = bx; px < bx + 8; px += 4)
                    for (int y = py; y < py + 2; ++y)
                        for (int x = px; x < px + 4; ++x)
                            if (x < w && y < h) {
                                dx[n] = x;
                                dy[n++] = y;
                            }
    return n;
}

/// The pixels of `tile` without antialiasing, into `out`: their centres asked of `colour` as
/// one run of samples in tile_order() (sample_runs(): the colour function groups them), each
/// pixel put and counted as its sample is done. `work` is the tile's counters, counts and
/// progress (render/tile_store.h).
template <class Colour, class Work, class Out>
void sample_tile_none(const PixelRect& tile, Colour& colour, Work& work, Out& out) {
    using S = SampleOf<Colour, decltype(work.counters)>;
    constexpr int kMost = kSamplerTile * kSamplerTile;
    int dx[kMost], dy[kMost];
    const int n = tile_order(tile.width(), tile.height(), dx, dy);
    float xs[kMost], ys[kMost];
    for (int k = 0; k < n; ++k) {
        xs[k] = (tile.x0 + dx[k]) + 0.5f;
        ys[k] = (tile.y0 + dy[k]) + 0.5f;
    }
    thread_local std::vector<S> got(kMost);
    int done = 0;
    sample_runs(colour, xs, ys, n, work.counters, got.data(), [&](int m, double cost) {
        work.progress.cost(cost);
        for (; done < m; ++done) {
            put(out, tile.x0 + dx[done], tile.y0 + dy[done], got[done]);
            work.progress.pixel();
        }
    });
    work.counts.samples += static_cast<uint64_t>(n);
}

}  // namespace luz
